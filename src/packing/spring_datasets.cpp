// A packing's tangential springs as two HDF5 datasets (packing/spring_datasets.hpp).
#include "packing/spring_datasets.hpp"

#include <cmath>
#include <cstdint>

#include "core/error.hpp"
#include "io/h5.hpp"

namespace granwave::packing {

void write_springs(io::H5Writer& w, const std::string& prefix, const std::vector<SpringHistory>& springs) {
  const std::size_t m = springs.size();
  std::vector<std::int64_t> pairs(2 * m);
  std::vector<double> xi(3 * m);
  for (std::size_t c = 0; c < m; ++c) {
    pairs[2 * c] = springs[c].i, pairs[2 * c + 1] = springs[c].j;
    for (int d = 0; d < 3; ++d) xi[3 * c + d] = springs[c].xi[d];
  }
  w.write(prefix + "spring_pairs", pairs, {m, 2});
  w.write(prefix + "spring_xi", xi, {m, 3});
}

std::vector<SpringHistory> read_springs(const io::H5Reader& r, const std::string& prefix, std::size_t n, double longest,
                                        const std::string& where) {
  const auto refuse = [&](const std::string& what) { throw InputError(where + ": " + what); };
  for (const char* name : {"spring_pairs", "spring_xi"})
    if (!r.has(prefix + name)) refuse(std::string("a frictional packing (prepare_friction) needs the dataset ") + name);
  std::vector<std::size_t> dp, dx;
  const auto pairs = r.read_int(prefix + "spring_pairs", &dp);
  const auto xi = r.read_double(prefix + "spring_xi", &dx);
  if (dp.size() != 2 || dp[1] != 2) refuse("dataset spring_pairs must have the shape [contacts, 2]");
  if (dx.size() != 2 || dx[1] != 3 || dx[0] != dp[0]) refuse("dataset spring_xi must have the shape [contacts, 3], one row per spring_pairs row");
  const std::size_t m = dp[0];
  std::vector<SpringHistory> springs(m);
  for (std::size_t c = 0; c < m; ++c) {
    const std::int64_t i = pairs[2 * c], j = pairs[2 * c + 1];
    if (!(i >= 0 && j > i && j < static_cast<std::int64_t>(n)))
      refuse("dataset spring_pairs: row " + std::to_string(c) + " is not two particle indices i < j < " + std::to_string(n));
    SpringHistory& s = springs[c];
    s.i = static_cast<std::uint32_t>(i), s.j = static_cast<std::uint32_t>(j);
    if (c > 0 && !(springs[c - 1].i < s.i || (springs[c - 1].i == s.i && springs[c - 1].j < s.j)))
      refuse("dataset spring_pairs: row " + std::to_string(c) + " is out of order or repeated (sorted by (i, j), once each)");
    for (int d = 0; d < 3; ++d) {
      s.xi[d] = xi[3 * c + d];
      if (!(std::abs(s.xi[d]) < longest)) refuse("dataset spring_xi: row " + std::to_string(c) + " is not finite or longer than d");
    }
  }
  return springs;
}

}  // namespace granwave::packing
