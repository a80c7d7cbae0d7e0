// The one translation unit that includes H5Cpp.h (it is heavy to compile).
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

namespace granwave::io {
namespace {

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

// The innermost description on the HDF5 error stack (the most specific), and whether any entry
// reports a checksum failure (Fletcher-32 on raw data, Jenkins lookup3 on metadata). Clears it.
struct LibraryFailure {
  std::string why;
  bool checksum = false;
};
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
LibraryFailure library_failure() {
  LibraryFailure f;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walk_error, &f);
  H5Eclear2(H5E_DEFAULT);
  if (f.why.empty()) f.why = "the HDF5 library gave no reason";
  return f;
}

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

struct H5Writer::Impl {
  std::string tmp_path;
  std::unique_ptr<H5::H5File> file;
  bool in_memory = false;
};

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

// ---------------------------------------------------------------------------------------------
// Reading files from elsewhere (docs/design.md §2.3, "Files from elsewhere"): the C API, so that
// every failure is a return code whose error stack we read (a checksum failure is named as such),
// every size read from the file is checked against the file's size and the memory guard before
// anything is allocated, and a scalar attribute is refused unless it holds exactly one value.

namespace {

// A C handle closed on scope exit.
struct Hid {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  Hid(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~Hid() { if (id >= 0) close(id); }
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  explicit operator bool() const { return id >= 0; }
};

// ---- variable-length strings (legacy granwave files, h5py's str attributes) ----
// They live in the global heap, which carries no checksum in any file-format version, and
// HDF5 1.10 trusts a heap object's index and size (H5HG_read): a damaged heap can crash the
// library. So, before the first variable-length read, every global heap collection in the file is
// walked the way the library walks it and the file refused unless each one is consistent. A
// damaged reference to a sound collection is not caught that way, nor damaged metadata in the
// formats without checksums (object headers before 1.8, v1 B-trees): every library call of the
// reader runs under a crash guard, the last line of defence, which prints a message prepared
// beforehand naming the file and the object and ends the process with exit code 2
// (docs/design.md §2.3).

std::uint64_t le(const unsigned char* p, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// "" when every collection ("GCOL", version 1; data/SCHEMA.md cites the format) is consistent.
std::string check_global_heaps(const std::string& path) {
  std::FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) return "cannot reopen the file to check its global heap";
  std::vector<unsigned char> buf;
  std::string problem;
  // Read in blocks with an overlap, so that a collection header across a block edge is seen.
  constexpr std::size_t kBlock = 1 << 22, kHead = 16;
  std::vector<unsigned char> block(kBlock + kHead);
  std::uint64_t base = 0;  // file offset of block[0]
  std::size_t have = 0;
  const auto file_size = std::filesystem::file_size(path);
  for (;;) {
    const std::size_t got = std::fread(block.data() + have, 1, kBlock, fp);
    const std::size_t len = have + got;
    const std::size_t scan_end = got ? (len > kHead ? len - kHead : 0) : len;
    for (std::size_t i = 0; i + 4 <= scan_end || (!got && i + 4 <= len); ++i) {
      if (std::memcmp(block.data() + i, "GCOL", 4) != 0) continue;
      if (i + kHead > len || block[i + 4] != 1) continue;  // not a version-1 collection header
      const std::uint64_t at = base + i;
      const std::uint64_t size = le(block.data() + i + 8, 8);
      if (size < kHead || size > file_size - at) {
        problem = "global heap collection at byte " + std::to_string(at) + " claims " + std::to_string(size) +
                  " bytes, past the end of the file";
        break;
      }
      std::vector<unsigned char> col(size);
      const long keep = std::ftell(fp);
      if (std::fseek(fp, static_cast<long>(at), SEEK_SET) != 0 || std::fread(col.data(), 1, size, fp) != size) {
        problem = "cannot read the global heap collection at byte " + std::to_string(at);
        break;
      }
      std::fseek(fp, keep, SEEK_SET);
      std::uint64_t p = kHead;
      while (p < size) {
        if (p + kHead > size) break;  // a tail too small for an object header is free space
        const std::uint64_t idx = le(col.data() + p, 2), osize = le(col.data() + p + 8, 8);
        const std::uint64_t need = idx > 0 ? (osize > size ? size + 1 : kHead + ((osize + 7) / 8) * 8) : osize;
        if (need == 0 || need > size - p) {  // the library would loop forever or read past the collection
          problem = "global heap collection at byte " + std::to_string(at) + ": object " + std::to_string(idx) +
                    " at offset " + std::to_string(p) + " has an impossible size " + std::to_string(osize);
          break;
        }
        p += need;
      }
      if (!problem.empty()) break;
    }
    if (!problem.empty() || !got) break;
    // Keep the last kHead bytes for the next block.
    std::memmove(block.data(), block.data() + scan_end, len - scan_end);
    have = len - scan_end;
    base += scan_end;
  }
  std::fclose(fp);
  return problem;
}

// Signal-safe state of the crash guard: one thread in the reader at a time (HDF5 serialises its
// calls anyway); guards nest (has_attr calls has), the innermost names the object.
std::recursive_mutex g_guard_mutex;
int g_guard_depth = 0;
char g_guard_message[1024];
std::size_t g_guard_length = 0;
constexpr int kGuardSignals = 3;
constexpr int kGuardSignal[kGuardSignals] = {SIGSEGV, SIGBUS, SIGABRT};
struct sigaction g_guard_old[kGuardSignals];
extern "C" void on_library_crash(int) {
  if (g_guard_length) [[maybe_unused]] auto w = ::write(2, g_guard_message, g_guard_length);
  ::_exit(2);
}

// Around the HDF5 library's calls of the reader: a crash inside them (a file whose format has no
// checksums, damaged) prints a message prepared beforehand and exits 2 (docs/design.md §2.3).
class CrashGuard {
 public:
  CrashGuard(const std::string& file, const std::string& object, const char* why = nullptr) : lock_(g_guard_mutex) {
    saved_length_ = g_guard_length;
    std::memcpy(saved_, g_guard_message, saved_length_);
    const std::string m = "granwave: error: " + file + ": damaged file: the HDF5 library crashed reading '" + object +
                          "' (" + (why ? why : "a file format without checksums: its metadata cannot be verified") +
                          "); refused\n";
    g_guard_length = std::min(m.size(), sizeof g_guard_message);
    std::memcpy(g_guard_message, m.data(), g_guard_length);
    if (g_guard_depth++ == 0) {
      struct sigaction sa {};
      sa.sa_handler = on_library_crash;
      sigemptyset(&sa.sa_mask);
      for (int i = 0; i < kGuardSignals; ++i) sigaction(kGuardSignal[i], &sa, &g_guard_old[i]);
    }
  }
  ~CrashGuard() {
    if (--g_guard_depth == 0)
      for (int i = 0; i < kGuardSignals; ++i) sigaction(kGuardSignal[i], &g_guard_old[i], nullptr);
    g_guard_length = saved_length_;
    std::memcpy(g_guard_message, saved_, saved_length_);
  }
  CrashGuard(const CrashGuard&) = delete;
  CrashGuard& operator=(const CrashGuard&) = delete;

 private:
  std::lock_guard<std::recursive_mutex> lock_;
  char saved_[sizeof g_guard_message];
  std::size_t saved_length_ = 0;
};

}  // namespace

struct H5Reader::Impl {
  hid_t file = -1;
  double file_size = 0.0;
  double memory = 0.0;       // the memory guard (core/resources.hpp): MemAvailable
  bool heaps_checked = false;
  ~Impl() {
    if (file >= 0) H5Fclose(file);
  }
};

H5Reader::H5Reader(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": no such file");
  impl_->file_size = static_cast<double>(std::filesystem::file_size(path, ec));
  impl_->memory = memory_limit(ResourceLimits{});
  {
    CrashGuard guard(path, "its superblock");
    impl_->file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  if (impl_->file < 0) {
    const auto f = library_failure();
    if (f.checksum) throw InputError("checksum mismatch in the superblock of file '" + path + "': the file is damaged");
    throw InputError(path + ": not a readable HDF5 file (" + f.why + ")");
  }
}

H5Reader::H5Reader(const H5Writer& w) : impl_(std::make_unique<Impl>()), path_(w.path()) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t id = w.impl_->file->getId();
  hsize_t size = 0;
  if (H5Fflush(id, H5F_SCOPE_GLOBAL) < 0 || H5Fget_filesize(id, &size) < 0)
    throw RunError(path_ + ": cannot flush the file to read it (" + library_failure().why + ")");
  impl_->file_size = static_cast<double>(size);
  impl_->memory = memory_limit(ResourceLimits{});
  impl_->heaps_checked = true;  // the file being written here, not one from elsewhere
  impl_->file = H5Freopen(id);  // another handle of the same open file
  if (impl_->file < 0) throw RunError(path_ + ": cannot open the file being written (" + library_failure().why + ")");
}

H5Reader::~H5Reader() = default;

namespace {
[[noreturn]] void refuse(const std::string& file, const std::string& kind, const std::string& object,
                         const std::string& what) {
  const auto f = library_failure();
  if (f.checksum)
    throw InputError("checksum mismatch in " + kind + " '" + object + "' of file '" + file + "': the file is damaged (" +
                     f.why + ")");
  throw InputError(file + ": " + what + " (" + f.why + ")");
}
}  // namespace

bool H5Reader::has(const std::string& path) const {
  // H5Lexists fails on a missing intermediate group: check each prefix. On a damaged file the
  // library fails instead of answering: bad input, named.
  CrashGuard guard(path_, path);
  std::string cur;
  for (const auto& p : split_path(path)) {
    cur += "/" + p;
    const htri_t e = H5Lexists(impl_->file, cur.c_str(), H5P_DEFAULT);
    if (e < 0) refuse(path_, "object", cur, "damaged file: cannot look up '" + cur + "'");
    if (e == 0) return false;
  }
  return true;
}

namespace {
std::string fmt_count(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", n);
  return buf;
}

// Values a dataspace holds; refuses a dataspace the file could not hold or memory could not take.
std::size_t checked_count(hid_t space, std::size_t element_size, double stored_ratio, const H5Reader& r,
                          double file_size, double memory, const std::string& object,
                          std::vector<std::size_t>* dims) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0 || rank > H5S_MAX_RANK) refuse(r.path(), "dataset", object, "cannot read the shape of '" + object + "'");
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space, d.data(), nullptr) < 0)
    refuse(r.path(), "dataset", object, "cannot read the shape of '" + object + "'");
  double n = H5Sget_simple_extent_type(space) == H5S_NULL ? 0.0 : 1.0;
  for (auto x : d) n *= static_cast<double>(x);
  const double bytes = n * static_cast<double>(element_size);
  // The file holds the values (compressed at most ~1000:1, deflate's limit) and memory must hold them.
  if (bytes > file_size * stored_ratio + 4096.0 || bytes > memory)
    throw InputError(r.path() + ": '" + object + "' claims " + fmt_count(n) + " values (" + bytes_text(bytes) + ") in a file of " + bytes_text(file_size) +
                     (bytes > memory ? " with " + bytes_text(memory) + " of memory" : std::string()) +
                     ": the file is damaged");
  if (dims) dims->assign(d.begin(), d.end());
  return static_cast<std::size_t>(n);
}

// deflate and the other compressors: the file may hold fewer bytes than the values.
double stored_ratio(hid_t ds) {
  Hid dcpl(H5Dget_create_plist(ds), H5Pclose);
  if (!dcpl) return 1.0;
  const int nf = H5Pget_nfilters(dcpl.id);
  for (int i = 0; i < nf; ++i) {
    unsigned flags = 0;
    std::size_t nelmts = 0;
    const H5Z_filter_t id = H5Pget_filter2(dcpl.id, static_cast<unsigned>(i), &flags, &nelmts, nullptr, 0, nullptr, nullptr);
    if (id != H5Z_FILTER_FLETCHER32 && id != H5Z_FILTER_SHUFFLE) return 1100.0;
  }
  return 1.0;
}

template <class T>
std::vector<T> read_numeric(const H5Reader& r, hid_t file, double file_size, double memory, const std::string& path,
                            hid_t mem_type, std::vector<std::size_t>* dims) {
  Hid ds(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds) refuse(r.path(), "dataset", path, "cannot open dataset '" + path + "'");
  Hid type(H5Dget_type(ds.id), H5Tclose);
  if (!type) refuse(r.path(), "dataset", path, "cannot read the type of dataset '" + path + "'");
  const H5T_class_t cls = H5Tget_class(type.id);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    throw InputError(r.path() + ": dataset '" + path + "' is not numeric");
  Hid space(H5Dget_space(ds.id), H5Sclose);
  if (!space) refuse(r.path(), "dataset", path, "cannot read the shape of dataset '" + path + "'");
  const std::size_t n = checked_count(space.id, std::max(H5Tget_size(type.id), sizeof(T)), stored_ratio(ds.id), r,
                                      file_size, memory, path, dims);
  std::vector<T> out(n);
  if (n && H5Dread(ds.id, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    refuse(r.path(), "dataset", path, "cannot read dataset '" + path + "'");
  return out;
}
}  // namespace

std::vector<double> H5Reader::read_double(const std::string& path, std::vector<std::size_t>* dims) const {
  CrashGuard guard(path_, path);
  return read_numeric<double>(*this, impl_->file, impl_->file_size, impl_->memory, path, H5T_NATIVE_DOUBLE, dims);
}

std::vector<std::int64_t> H5Reader::read_int(const std::string& path, std::vector<std::size_t>* dims) const {
  CrashGuard guard(path_, path);
  return read_numeric<std::int64_t>(*this, impl_->file, impl_->file_size, impl_->memory, path, H5T_NATIVE_INT64, dims);
}

void H5Reader::check_heaps() const {
  if (impl_->heaps_checked) return;
  if (const std::string why = check_global_heaps(path_); !why.empty())
    throw InputError(path_ + ": damaged file: " + why);
  impl_->heaps_checked = true;
}

std::vector<std::string> H5Reader::read_strings(const std::string& path) const {
  CrashGuard guard(path_, path);
  Hid ds(H5Dopen2(impl_->file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds) refuse(path_, "dataset", path, "cannot open dataset '" + path + "'");
  Hid ftype(H5Dget_type(ds.id), H5Tclose);
  if (!ftype) refuse(path_, "dataset", path, "cannot read the type of dataset '" + path + "'");
  if (H5Tget_class(ftype.id) != H5T_STRING) throw InputError(path_ + ": dataset '" + path + "' is not text");
  Hid space(H5Dget_space(ds.id), H5Sclose);
  if (!space) refuse(path_, "dataset", path, "cannot read the shape of dataset '" + path + "'");
  const H5T_cset_t cset = H5Tget_cset(ftype.id);  // read in the file's character set
  std::vector<std::string> out;
  if (H5Tis_variable_str(ftype.id) > 0) {
    const std::size_t n = checked_count(space.id, 16, 1.0, *this, impl_->file_size, impl_->memory, path, nullptr);
    check_heaps();
    Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.id, H5T_VARIABLE);
    H5Tset_cset(type.id, cset);
    std::vector<char*> ptrs(n, nullptr);
    herr_t err = 0;
    {
      CrashGuard guard(path_, path, "a variable-length string: the global heap has no checksum");
      if (n) err = H5Dread(ds.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data());
    }
    if (err < 0) refuse(path_, "dataset", path, "cannot read strings '" + path + "'");
    for (auto* p : ptrs) out.emplace_back(p ? p : "");
    H5Dvlen_reclaim(type.id, space.id, H5P_DEFAULT, ptrs.data());
  } else {  // fixed-length strings (granwave since #25; h5py for numpy 'S' arrays)
    const std::size_t len = H5Tget_size(ftype.id);
    const std::size_t n = checked_count(space.id, std::max<std::size_t>(len, 1), stored_ratio(ds.id), *this,
                                        impl_->file_size, impl_->memory, path, nullptr);
    std::vector<char> buf(n * len);
    Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.id, len);
    H5Tset_cset(type.id, cset);
    H5Tset_strpad(type.id, H5T_STR_NULLPAD);
    if (n && H5Dread(ds.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
      refuse(path_, "dataset", path, "cannot read strings '" + path + "'");
    for (std::size_t i = 0; i < n; ++i) {
      std::string s(buf.data() + i * len, len);
      out.push_back(s.substr(0, s.find('\0')));
    }
  }
  return out;
}

bool H5Reader::has_attr(const std::string& object, const std::string& name) const {
  if (object != "/" && !has(object)) return false;
  CrashGuard guard(path_, object + (object == "/" ? "" : "/") + "@" + name);
  const htri_t e = H5Aexists_by_name(impl_->file, object.c_str(), name.c_str(), H5P_DEFAULT);
  if (e < 0) refuse(path_, "object", object, "damaged file: cannot look up attribute '" + name + "' of '" + object + "'");
  return e > 0;
}

namespace {
// An attribute opened for reading one value: refused unless its dataspace holds exactly one.
struct ScalarAttr {
  Hid obj, attr, type;
  ScalarAttr(const H5Reader& r, hid_t file, const std::string& object, const std::string& name)
      : obj(H5Oopen(file, object.empty() ? "/" : object.c_str(), H5P_DEFAULT), H5Oclose),
        attr(obj ? H5Aopen(obj.id, name.c_str(), H5P_DEFAULT) : -1, H5Aclose),
        type(attr ? H5Aget_type(attr.id) : -1, H5Tclose) {
    if (!attr) refuse(r.path(), "object", object, "no attribute '" + name + "' on '" + object + "'");
    if (!type) refuse(r.path(), "object", object, "cannot read the type of attribute '" + name + "' of '" + object + "'");
    Hid space(H5Aget_space(attr.id), H5Sclose);
    const hssize_t n = space ? H5Sget_simple_extent_npoints(space.id) : -1;
    if (n != 1)
      throw InputError(r.path() + ": attribute '" + name + "' of '" + object + "' must hold one value, not " +
                       std::to_string(n));
  }
};
}  // namespace

std::string H5Reader::attr_string(const std::string& object, const std::string& name) const {
  CrashGuard guard(path_, object + (object == "/" ? "" : "/") + "@" + name);
  ScalarAttr a(*this, impl_->file, object, name);
  if (H5Tget_class(a.type.id) != H5T_STRING)
    throw InputError(path_ + ": attribute '" + name + "' of '" + object + "' is not text");
  const H5T_cset_t cset = H5Tget_cset(a.type.id);  // HDF5 does not convert between ASCII and UTF-8
  std::string out;
  herr_t err;
  if (H5Tis_variable_str(a.type.id) > 0) {
    check_heaps();
    char* p = nullptr;
    Hid mtype(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mtype.id, H5T_VARIABLE);
    H5Tset_cset(mtype.id, cset);
    {
      CrashGuard guard(path_, object + (object == "/" ? "" : "/") + "@" + name,
                       "a variable-length string: the global heap has no checksum");
      err = H5Aread(a.attr.id, mtype.id, &p);
    }
    if (err >= 0 && p) {
      out = p;
      H5free_memory(p);
    }
  } else {  // fixed-length (granwave since #25; h5py for numpy bytes)
    const std::size_t len = H5Tget_size(a.type.id);
    if (static_cast<double>(len) > impl_->file_size)
      throw InputError(path_ + ": attribute '" + name + "' of '" + object + "' claims " + std::to_string(len) +
                       " bytes, more than the file: the file is damaged");
    std::vector<char> buf(len + 1, '\0');
    Hid mtype(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mtype.id, len);
    H5Tset_cset(mtype.id, cset);
    H5Tset_strpad(mtype.id, H5Tget_strpad(a.type.id));
    err = H5Aread(a.attr.id, mtype.id, buf.data());
    out = std::string(buf.data());
  }
  if (err < 0) refuse(path_, "attribute", name + "' of '" + object, "cannot read attribute '" + name + "' of '" + object + "' as text");
  return out;
}

double H5Reader::attr_double(const std::string& object, const std::string& name) const {
  CrashGuard guard(path_, object + (object == "/" ? "" : "/") + "@" + name);
  ScalarAttr a(*this, impl_->file, object, name);
  const H5T_class_t cls = H5Tget_class(a.type.id);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    throw InputError(path_ + ": attribute '" + name + "' of '" + object + "' is not a number");
  double v = 0;
  if (H5Aread(a.attr.id, H5T_NATIVE_DOUBLE, &v) < 0)  // converts integer attributes too
    refuse(path_, "attribute", name + "' of '" + object, "cannot read attribute '" + name + "' of '" + object + "' as a number");
  return v;
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
