// A thin HDF5 layer (the only header the rest of granwave needs; H5Cpp stays in h5.cpp).
// Files are written to NAME.tmp and renamed on commit(): a crash never leaves a half file
// under the final name (HDF5 files are not crash-safe in place). Written files carry checksums
// (data/SCHEMA.md §1, "Checksums"): metadata in the 1.10 file format, numeric and string datasets
// chunked with Fletcher-32, strings fixed-length. The reader refuses, with InputError naming the
// file and the object, anything the library cannot read, a checksum that does not match, and a
// size the file or the memory could not hold.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace granwave::io {

class H5Writer {
 public:
  // disk: NAME.tmp, renamed to NAME by commit(). memory: a file that only lives in memory (HDF5's
  // core driver, no backing store), named NAME in messages; nothing touches the disk. An H5Reader
  // opened on it before commit() keeps it until the reader is gone.
  enum class Storage { disk, memory };
  explicit H5Writer(std::string final_path, Storage storage = Storage::disk);
  ~H5Writer();  // removes the temporary file unless commit() succeeded
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  // Datasets: `path` like "/chain/contact_force"; parent groups are created on demand.
  // dims multiply to data.size(); row-major ([nt, n] = nt rows).
  void write(const std::string& path, const std::vector<double>& data, std::vector<std::size_t> dims = {});
  void write(const std::string& path, const std::vector<std::int64_t>& data, std::vector<std::size_t> dims = {});
  void write(const std::string& path, const std::vector<std::string>& data);
  // Attributes on a group or dataset ("/" for the root).
  void attr(const std::string& object, const std::string& name, const std::string& value);
  void attr(const std::string& object, const std::string& name, double value);
  void attr(const std::string& object, const std::string& name, std::int64_t value);
  void group(const std::string& path);

  void commit();  // close and rename NAME.tmp -> NAME (memory: close)
  const std::string& path() const { return final_path_; }

 private:
  friend class H5Reader;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string final_path_;
  bool committed_ = false;
};

class H5Reader {
 public:
  explicit H5Reader(const std::string& path);  // throws InputError if unreadable
  // The file `w` is writing (Storage::memory: the run's trace measured in memory), not committed yet.
  explicit H5Reader(const H5Writer& w);
  ~H5Reader();
  bool has(const std::string& path) const;
  std::vector<double> read_double(const std::string& path, std::vector<std::size_t>* dims = nullptr) const;
  std::vector<std::int64_t> read_int(const std::string& path, std::vector<std::size_t>* dims = nullptr) const;
  std::vector<std::string> read_strings(const std::string& path) const;
  bool has_attr(const std::string& object, const std::string& name) const;
  std::string attr_string(const std::string& object, const std::string& name) const;
  double attr_double(const std::string& object, const std::string& name) const;
  const std::string& path() const { return path_; }

 private:
  void check_heaps() const;  // before the first variable-length string: the global heap is sound
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
};

// Root attributes every granwave file carries: code, version, git describe, UTC time.
void write_provenance(H5Writer& w, const std::string& code = "granwave");
std::string utc_now_iso8601();

// Files given up after the library failed to close them (a full disk: H5Fclose fails half way and
// leaves the file half released). The HDF5 library's clean-up at exit would close them again and
// crash: main() ends the process with _Exit instead when this is not 0.
int abandoned_files();

// Inside a catch (...) block: the HDF5 library's message if the exception in flight is one of its
// own (H5::Exception is no std::exception), else "". Lets main() name a stray one without H5Cpp.h.
std::string hdf5_exception_message();

}  // namespace granwave::io
