// Reading HDF5 files from anywhere (io/h5.hpp, docs/design.md §2.3): every size checked before
// anything is allocated, checksums named, a crash inside the library turned into exit 2.
#include "io/h5.hpp"

#include <H5Cpp.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "core/error.hpp"
#include "core/resources.hpp"
#include "core/version.hpp"

#include "io/h5_internal.hpp"

namespace granwave::io {

using detail::library_failure, detail::split_path;

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

// A global heap's objects: (collection address, index) -> size in bytes.
using HeapObjects = std::map<std::pair<std::uint64_t, std::uint64_t>, std::uint64_t>;

// "" when every collection ("GCOL", version 1; data/SCHEMA.md cites the format) is consistent;
// its objects into `objects`.
std::string check_global_heaps(const std::string& path, HeapObjects& objects) {
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
        if (idx > 0) objects[{at, idx}] = osize;
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

// ---- a variable-length attribute's stored value, before the library reads it ----
// A scalar variable-length string is stored as its length (4 bytes), its global heap object's
// collection address (8) and index (4). HDF5 1.10 allocates and fills that length before it looks
// at the heap, so a damaged length makes a small file cost gigabytes (libFuzzer: 1.8 GB for a
// 236 kB trace), then copies the whole heap object into it, so a length short of the object's size
// writes past the library's buffer (libFuzzer, under ASan). So the attribute message is found in the object header (file format version 0
// superblocks' headers: version 1, no signature; version 2, "OHDR", and its "OCHK" continuation
// blocks) and its value checked against the heap walked above. Attributes in dense storage (a
// fractal heap) are not looked for: the read then goes ahead as before, under the crash guard.

bool read_at(std::FILE* fp, std::uint64_t at, std::size_t n, unsigned char* out) {
  return std::fseek(fp, static_cast<long>(at), SEEK_SET) == 0 && std::fread(out, 1, n, fp) == n;
}

// The first 16 bytes of the value of attribute `name` of the object whose header is at `header`;
// `base`: where the file's addresses count from (its superblock's offset).
std::optional<std::array<unsigned char, 16>> attribute_value(const std::string& path, std::uint64_t base,
                                                             std::uint64_t header, const std::string& name) {
  header += base;
  std::FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) return std::nullopt;
  const std::uint64_t file_size = std::filesystem::file_size(path);
  std::optional<std::array<unsigned char, 16>> found;
  struct Chunk {
    std::uint64_t at, size;
  };
  std::vector<Chunk> chunks;
  unsigned char prefix[32];
  int version = 0;
  std::size_t message_head = 8;  // a message's type, size and flags before its data
  if (header < file_size && read_at(fp, header, 16, prefix)) {
    if (prefix[0] == 1) {  // version 1: the messages from byte 16, chunk 0's size at byte 8
      version = 1;
      chunks.push_back({header + 16, le(prefix + 8, 4)});
    } else if (std::memcmp(prefix, "OHDR", 4) == 0 && prefix[4] == 2 && read_at(fp, header, 32, prefix)) {
      version = 2;
      const unsigned flags = prefix[5];
      std::uint64_t at = 6 + ((flags & 0x20) ? 16 : 0) + ((flags & 0x10) ? 4 : 0);
      const int width = 1 << (flags & 3);
      const std::uint64_t size = le(prefix + at, width);
      message_head = (flags & 0x04) ? 6 : 4;  // and its creation order
      chunks.push_back({header + at + width, size});
    }
  }
  for (std::size_t k = 0; k < chunks.size() && k < 64 && !found; ++k) {
    const Chunk chunk = chunks[k];
    if (chunk.size > file_size || chunk.at > file_size - chunk.size) break;
    std::vector<unsigned char> b(chunk.size);
    if (!read_at(fp, chunk.at, b.size(), b.data())) break;
    for (std::size_t p = 0; p + message_head <= b.size();) {
      const unsigned type = version == 1 ? static_cast<unsigned>(le(&b[p], 2)) : b[p];
      const std::size_t size = static_cast<std::size_t>(version == 1 ? le(&b[p + 2], 2) : le(&b[p + 1], 2));
      const unsigned flags = version == 1 ? b[p + 4] : b[p + 3];
      const std::size_t data = p + message_head;
      if (size > b.size() - data) break;
      if (type == 0x10 && size >= 16) {  // continuation: its chunk
        const std::uint64_t at = base + le(&b[data], 8), length = le(&b[data + 8], 8);
        if (version == 1) chunks.push_back({at, length});
        else if (length >= 8) chunks.push_back({at + 4, length - 8});  // "OCHK" ... checksum
      } else if (type == 0x0C && !(flags & 0x02) && size >= 8) {  // an attribute, not shared
        const unsigned av = b[data];
        const std::size_t name_size = le(&b[data + 2], 2), dt_size = le(&b[data + 4], 2), ds_size = le(&b[data + 6], 2);
        auto padded = [av](std::size_t n) { return av == 1 ? (n + 7) / 8 * 8 : n; };
        const std::size_t name_at = data + (av >= 3 ? 9 : 8);
        const std::size_t value_at = name_at + padded(name_size) + padded(dt_size) + padded(ds_size);
        if (av >= 1 && av <= 3 && name_size == name.size() + 1 && name_at + name_size <= data + size &&
            std::memcmp(&b[name_at], name.data(), name.size()) == 0 && value_at + 16 <= data + size) {
          found.emplace();
          std::memcpy(found->data(), &b[value_at], 16);
          break;
        }
      }
      p = data + size;
    }
  }
  std::fclose(fp);
  return found;
}

// "" when a stored variable-length string (length, collection address, index) is held by its heap
// object, else what is wrong. Collection 0 is a null string. The library copies the whole object into
// a buffer of the stored length (rounded up to 4 kB): a length other than the object's size is refused.
std::string unheld_string(const unsigned char* stored, const HeapObjects& heap, std::uint64_t base) {
  const std::uint64_t length = le(stored, 4), collection = le(stored + 4, 8);
  if (collection == 0) return "";
  const auto held = heap.find({base + collection, le(stored + 12, 4)});
  if (held != heap.end() && held->second == length) return "";
  return "claims a string of " + std::to_string(length) + " bytes, " +
         (held == heap.end() ? std::string("in no object of the global heap")
                             : "where its global heap object holds " + std::to_string(held->second));
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
  HeapObjects heap_objects;          // the global heap's objects, once checked (check_heaps)
  bool heap_objects_known = false;   // not for a file being written here
  std::uint64_t address_base = 0;    // the file's addresses count from its superblock, after a user block
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
  if (const std::string why = check_global_heaps(path_, impl_->heap_objects); !why.empty())
    throw InputError(path_ + ": damaged file: " + why);
  impl_->heaps_checked = impl_->heap_objects_known = true;
  Hid plist(H5Fget_create_plist(impl_->file), H5Pclose);
  hsize_t user_block = 0;
  if (plist && H5Pget_userblock(plist.id, &user_block) >= 0) impl_->address_base = user_block;
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
    // A contiguous dataset's stored strings, each checked as an attribute's is (h5py's layout; a
    // chunked or compact one is read as before, under the crash guard). H5Dget_offset counts from the
    // file's first byte, the stored heap addresses from the superblock (after a user block).
    const haddr_t offset = H5Dget_offset(ds.id);
    if (impl_->heap_objects_known && n && offset != HADDR_UNDEF && H5Dget_storage_size(ds.id) == n * 16) {
      std::vector<unsigned char> stored(n * 16);
      std::FILE* fp = std::fopen(path_.c_str(), "rb");
      const bool read = fp && read_at(fp, offset, stored.size(), stored.data());  // from the file's start
      if (fp) std::fclose(fp);
      if (!read) throw InputError(path_ + ": damaged file: dataset '" + path + "' lies past the end of the file");
      for (std::size_t k = 0; k < n; ++k)
        if (const std::string why = unheld_string(&stored[16 * k], impl_->heap_objects, impl_->address_base); !why.empty())
          throw InputError(path_ + ": damaged file: dataset '" + path + "' element " + std::to_string(k) + " " + why);
    }
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
    H5O_info_t info;
    const std::uint64_t base = impl_->address_base;
    if (impl_->heap_objects_known && H5Oget_info2(a.obj.id, &info, H5O_INFO_BASIC) >= 0)
      if (const auto value = attribute_value(path_, base, info.addr, name)) {  // its length against its heap object
        if (const std::string why = unheld_string(value->data(), impl_->heap_objects, base); !why.empty())
          throw InputError(path_ + ": damaged file: attribute '" + name + "' of '" + object + "' " + why);
      }
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

}  // namespace granwave::io
