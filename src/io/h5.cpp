// Writing granwave's HDF5 files (io/h5.hpp): NAME.tmp written, checksummed, renamed on commit;
// with h5_read.cpp, the only translation units that include H5Cpp.h (heavy to compile).
#include "io/h5.hpp"

#include <H5Cpp.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <mutex>

#include "core/error.hpp"
#include "core/resources.hpp"
#include "core/version.hpp"

#include "io/h5_internal.hpp"

namespace granwave::io {

namespace detail {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : path) {
    if (c == '/') {
      if (!cur.empty()) parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) parts.push_back(cur);
  return parts;
}

namespace {
herr_t walk_error(unsigned, const H5E_error2_t* e, void* data) {
  auto* f = static_cast<LibraryFailure*>(data);
  const std::string d = e->desc ? e->desc : "";
  if (d.find("checksum") != std::string::npos || d.find("Fletcher32") != std::string::npos) f->checksum = true;
  // A failed system call: its message alone ("File too large"), not the buffer addresses around it.
  std::string text = d;
  if (const auto m = d.find("error message = '"); m != std::string::npos) {
    const auto from = m + 17, to = d.find('\'', from);
    text = "write failed: " + d.substr(from, to == std::string::npos ? std::string::npos : to - from);
  }
  if (!text.empty()) f->why = (e->func_name ? std::string(e->func_name) + ": " : std::string()) + text;
  return 0;
}
}  // namespace
LibraryFailure library_failure() {
  LibraryFailure f;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walk_error, &f);
  H5Eclear2(H5E_DEFAULT);
  if (f.why.empty()) f.why = "the HDF5 library gave no reason";
  return f;
}

}  // namespace detail

namespace {
using detail::library_failure, detail::split_path;


// Open or create every group along `path` (not including the last element when leaf_is_dataset).
void ensure_groups(H5::H5File& file, const std::string& path, bool leaf_is_dataset) {
  auto parts = split_path(path);
  if (leaf_is_dataset && !parts.empty()) parts.pop_back();
  std::string cur;
  for (const auto& p : parts) {
    cur += "/" + p;
    if (!file.nameExists(cur)) file.createGroup(cur);
  }
}

std::vector<hsize_t> shape_of(std::vector<std::size_t> dims, std::size_t n) {
  if (dims.empty()) dims = {n};
  std::size_t prod = 1;
  for (auto d : dims) prod *= d;
  if (prod != n) throw RunError("internal: HDF5 dataset dims do not match the data size");
  return {dims.begin(), dims.end()};
}

// An HDF5 object (group or dataset) opened by path, closed on scope exit (C API: attributes
// work the same on both, which the C++ API's protected H5Object does not let us share).
struct ObjectHandle {
  hid_t id;
  ObjectHandle(hid_t file, const std::string& object) : id(H5Oopen(file, object.empty() ? "/" : object.c_str(), H5P_DEFAULT)) {}
  ~ObjectHandle() { if (id >= 0) H5Oclose(id); }
  ObjectHandle(const ObjectHandle&) = delete;
  ObjectHandle& operator=(const ObjectHandle&) = delete;
};

void write_attr(hid_t file, const std::string& object, const std::string& name, hid_t type, const void* value) {
  ObjectHandle obj(file, object);
  if (obj.id < 0) throw RunError("internal: no HDF5 object '" + object + "'");
  if (H5Aexists(obj.id, name.c_str()) > 0) H5Adelete(obj.id, name.c_str());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj.id, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t err = a >= 0 ? H5Awrite(a, type, value) : -1;
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  if (err < 0) throw RunError("internal: cannot write HDF5 attribute '" + name + "' on '" + object + "'");
}

bool exists(H5::H5File& file, const std::string& tmp_path, const std::string& object) {
  try {
    return file.nameExists(object);
  } catch (const H5::Exception& e) {
    throw RunError("cannot look up '" + object + "' in '" + tmp_path + "': " + e.getDetailMsg());
  }
}

}  // namespace

// Files whose H5Fclose failed: the library's clean-up at exit would close them again and crash.
std::atomic<int> g_abandoned{0};

namespace {
// The library takes two open files in memory of the same name for one file: each gets its own.
std::string memory_file_name(const std::string& name) {
  static std::atomic<unsigned long> serial{0};
  return name + " (in memory, " + std::to_string(++serial) + ")";
}
}  // namespace


H5Writer::H5Writer(std::string final_path, Storage storage) : impl_(std::make_unique<Impl>()), final_path_(std::move(final_path)) {
  H5::Exception::dontPrint();
  impl_->in_memory = storage == Storage::memory;
  impl_->tmp_path = impl_->in_memory ? final_path_ : final_path_ + ".tmp";
  try {
    // The 1.10 file format: superblock, object headers, B-trees, heaps and chunk indexes carry
    // checksums that the library verifies on every read (data/SCHEMA.md §1).
    H5::FileAccPropList fapl;
    H5Pset_libver_bounds(fapl.getId(), H5F_LIBVER_V110, H5F_LIBVER_LATEST);
    if (impl_->in_memory) H5Pset_fapl_core(fapl.getId(), 1 << 20, /*backing_store=*/0);
    impl_->file = std::make_unique<H5::H5File>(impl_->in_memory ? memory_file_name(final_path_) : impl_->tmp_path, H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, fapl);
  } catch (const H5::Exception& e) {
    if (!impl_->in_memory) std::remove(impl_->tmp_path.c_str());  // the library may have created it before failing
    throw RunError("cannot create '" + impl_->tmp_path + "': " + e.getDetailMsg());
  }
}

H5Writer::~H5Writer() {
  if (!committed_ && impl_) {
    try {
      if (impl_->file) impl_->file->close();
    } catch (...) {
      (void)impl_->file.release();  // as in commit(): never closed twice
      ++g_abandoned;
    }
    if (!impl_->in_memory) std::remove(impl_->tmp_path.c_str());
  }
}

namespace {
// Every HDF5 failure while writing (a full disk, a file-size limit) is a failed run naming the file
// and the object: no H5::Exception leaves io/.
template <class F>
void writing(const std::string& tmp_path, const std::string& object, F&& f) {
  try {
    f();
  } catch (const H5::Exception& e) {
    throw RunError("cannot write '" + object + "' to '" + tmp_path + "': " + e.getDetailMsg() + " (" +
                   library_failure().why + ")");
  }
}

// Chunked with the Fletcher-32 checksum filter, chunks of at most 1 MiB (the library's default
// chunk cache), taken along the first dimension (time, for a trace). An empty dataset cannot be
// chunked: it stays contiguous, and holds nothing to check.
H5::DSetCreatPropList checksummed(const std::vector<hsize_t>& shape, std::size_t element_size) {
  H5::DSetCreatPropList dcpl;
  double n = 1;
  for (auto d : shape) n *= static_cast<double>(d);
  if (n == 0) return dcpl;
  std::vector<hsize_t> chunk = shape;
  if (chunk.empty()) return dcpl;  // scalar
  constexpr double kChunkBytes = 1 << 20;
  for (std::size_t i = 0; i < chunk.size(); ++i) {
    double bytes = static_cast<double>(element_size);
    for (auto c : chunk) bytes *= static_cast<double>(c);
    if (bytes <= kChunkBytes) break;
    // k equal chunks along dimension i, so that the last one is not mostly empty (file size).
    const double others = bytes / static_cast<double>(chunk[i]);
    const double k = std::ceil(static_cast<double>(chunk[i]) / std::max(1.0, std::floor(kChunkBytes / others)));
    chunk[i] = std::max<hsize_t>(1, static_cast<hsize_t>(std::ceil(static_cast<double>(chunk[i]) / k)));
    if (chunk[i] > 1) break;
  }
  dcpl.setChunk(static_cast<int>(chunk.size()), chunk.data());
  dcpl.setFletcher32();
  return dcpl;
}

template <class T>
void write_numeric(H5::H5File& file, const std::string& path, const std::vector<T>& data, std::vector<std::size_t> dims,
                   const H5::PredType& type) {
  auto shape = shape_of(std::move(dims), data.size());
  ensure_groups(file, path, true);
  H5::DataSpace space(static_cast<int>(shape.size()), shape.data());
  H5::DataSet ds = file.createDataSet(path, type, space, checksummed(shape, sizeof(T)));
  if (!data.empty()) ds.write(data.data(), type);
}
}  // namespace

void H5Writer::write(const std::string& path, const std::vector<double>& data, std::vector<std::size_t> dims) {
  writing(impl_->tmp_path, path, [&] { write_numeric(*impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_DOUBLE); });
}

void H5Writer::write(const std::string& path, const std::vector<std::int64_t>& data, std::vector<std::size_t> dims) {
  writing(impl_->tmp_path, path, [&] { write_numeric(*impl_->file, path, data, std::move(dims), H5::PredType::NATIVE_INT64); });
}

void H5Writer::write(const std::string& path, const std::vector<std::string>& data) {
  writing(impl_->tmp_path, path, [&] {
    ensure_groups(*impl_->file, path, true);
    // Fixed-length, so that the text sits in checksummed chunks (variable-length strings live in
    // the global heap, which has no checksum).
    hsize_t n = data.size();
    std::size_t len = 1;
    for (const auto& s : data) len = std::max(len, s.size());
    H5::DataSpace space(1, &n);
    H5::StrType type(H5::PredType::C_S1, len);
    type.setCset(H5T_CSET_UTF8);
    type.setStrpad(H5T_STR_NULLPAD);
    H5::DataSet ds = impl_->file->createDataSet(path, type, space, checksummed({n}, len));
    std::vector<char> buf(n * len, '\0');
    for (std::size_t i = 0; i < data.size(); ++i) std::memcpy(buf.data() + i * len, data[i].data(), data[i].size());
    if (!data.empty()) ds.write(buf.data(), type);
  });
}

void H5Writer::group(const std::string& path) {
  writing(impl_->tmp_path, path, [&] { ensure_groups(*impl_->file, path, false); });
}

void H5Writer::attr(const std::string& object, const std::string& name, const std::string& value) {
  if (object != "/" && !exists(*impl_->file, impl_->tmp_path, object)) group(object);
  // Fixed-length: inside the object header, under its checksum (not in the global heap).
  H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(value.size(), 1));
  type.setCset(H5T_CSET_UTF8);
  type.setStrpad(H5T_STR_NULLPAD);
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  write_attr(impl_->file->getId(), object, name, type.getId(), padded.data());
}

void H5Writer::attr(const std::string& object, const std::string& name, double value) {
  if (object != "/" && !exists(*impl_->file, impl_->tmp_path, object)) group(object);
  write_attr(impl_->file->getId(), object, name, H5T_NATIVE_DOUBLE, &value);
}

void H5Writer::attr(const std::string& object, const std::string& name, std::int64_t value) {
  if (object != "/" && !exists(*impl_->file, impl_->tmp_path, object)) group(object);
  write_attr(impl_->file->getId(), object, name, H5T_NATIVE_INT64, &value);
}

void H5Writer::commit() {
  if (committed_) return;
  if (impl_->in_memory) {  // a reader opened on it keeps the file
    impl_->file->close();
    committed_ = true;
    return;
  }
  try {
    impl_->file->close();
  } catch (const H5::Exception& e) {
    // A failed H5Fclose (a full disk) leaves the file half released: closing it again (here or in
    // ~H5File) crashes the library. The handle is given up; the destructor removes NAME.tmp.
    (void)impl_->file.release();
    ++g_abandoned;
    throw RunError("cannot close '" + impl_->tmp_path + "' (" + e.getDetailMsg() + ": " + library_failure().why +
                   "): nothing written to '" +
                   final_path_ + "'");
  }
  std::error_code ec;
  std::filesystem::rename(impl_->tmp_path, final_path_, ec);
  if (ec) throw RunError("cannot rename '" + impl_->tmp_path + "' to '" + final_path_ + "': " + ec.message());
  committed_ = true;
}

int abandoned_files() { return g_abandoned.load(); }

std::string hdf5_exception_message() {
  try {
    throw;
  } catch (const H5::Exception& e) {
    return e.getFuncName() + ": " + e.getDetailMsg();
  } catch (...) {
    return {};
  }
}

std::string utc_now_iso8601() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

void write_provenance(H5Writer& w, const std::string& code) {
  w.attr("/", "schema_version", std::int64_t{1});
  w.attr("/", "code", code);
  w.attr("/", "code_version", std::string(version()));
  w.attr("/", "git_describe", std::string(git_describe()));
  w.attr("/", "created_utc", utc_now_iso8601());
  w.attr("/", "units", std::string("SI"));
}

}  // namespace granwave::io
