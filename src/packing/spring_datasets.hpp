// A packing's tangential springs as two datasets of an HDF5 file (data/SCHEMA.md §2): spring_pairs
// (int [m, 2], the pair's particle indices i < j, sorted by (i, j), each once) and spring_xi (float
// [m, 3], the spring, m). Written by the system file and its /prepared group alike.
#pragma once
#include <string>
#include <vector>

#include "packing/random_packing.hpp"

namespace granwave::io {
class H5Reader;
class H5Writer;
}  // namespace granwave::io

namespace granwave::packing {

// Writes prefix + "spring_pairs" and prefix + "spring_xi".
void write_springs(io::H5Writer& w, const std::string& prefix, const std::vector<SpringHistory>& springs);

// Reads them for a packing of n particles: both datasets present and shaped as above, every pair two
// indices i < j < n in order and once, every spring finite and shorter than `longest`. Else throws
// InputError "where: what", naming the dataset.
std::vector<SpringHistory> read_springs(const io::H5Reader& r, const std::string& prefix, std::size_t n, double longest,
                                        const std::string& where);

}  // namespace granwave::packing
