// The HDF5 layer: what is written reads back bit for bit, through the temporary name.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/h5.hpp"

using namespace granwave;

TEST_CASE("datasets and attributes round-trip, the file appears only on commit", "[io]") {
  const std::string path = (std::filesystem::temp_directory_path() / "granwave_io_roundtrip.h5").string();
  std::filesystem::remove(path);
  {
    io::H5Writer w(path);
    w.write("/a/b/values", std::vector<double>{1.5, -2.25, 3e-300, 4, 5, 6}, {2, 3});
    w.write("/ints", std::vector<std::int64_t>{-1, 0, 1LL << 40});
    w.write("/names", std::vector<std::string>{"large_steel", "aluminium", ""});
    w.attr("/", "case_name", std::string("oriented20 ü"));
    w.attr("/", "magnetisation", 0.6);
    w.attr("/a/b/values", "units", std::string("N"));
    w.attr("/a", "count", std::int64_t{42});
    CHECK(std::filesystem::exists(path + ".tmp"));
    CHECK_FALSE(std::filesystem::exists(path));
    w.commit();
  }
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  io::H5Reader r(path);
  std::vector<std::size_t> dims;
  CHECK(r.read_double("/a/b/values", &dims) == std::vector<double>{1.5, -2.25, 3e-300, 4, 5, 6});
  CHECK(dims == std::vector<std::size_t>{2, 3});
  CHECK(r.read_int("/ints") == std::vector<std::int64_t>{-1, 0, 1LL << 40});
  CHECK(r.read_strings("/names") == std::vector<std::string>{"large_steel", "aluminium", ""});
  CHECK(r.attr_string("/", "case_name") == "oriented20 ü");
  CHECK(r.attr_double("/", "magnetisation") == 0.6);
  CHECK(r.attr_string("/a/b/values", "units") == "N");
  CHECK(r.attr_double("/a", "count") == 42.0);
  CHECK(r.has("/a/b/values"));
  CHECK_FALSE(r.has("/a/c/values"));
  CHECK(r.has_attr("/", "case_name"));
  CHECK_FALSE(r.has_attr("/", "nothing"));
  CHECK_THROWS_AS(r.read_double("/missing"), InputError);
  std::filesystem::remove(path);
}

TEST_CASE("an uncommitted writer leaves nothing behind", "[io]") {
  const std::string path = (std::filesystem::temp_directory_path() / "granwave_io_abandoned.h5").string();
  {
    io::H5Writer w(path);
    w.write("/x", std::vector<double>{1, 2, 3});
  }
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST_CASE("a missing or foreign file is bad input", "[io]") {
  CHECK_THROWS_AS(io::H5Reader("/nonexistent/file.h5"), InputError);
}

namespace {
// A file with one variable-length string attribute on its root, as h5py writes a str: the string
// in the global heap, the attribute's value its length, the heap collection's address and index.
// user_block: bytes before the superblock (the file's addresses count from it).
std::string vlen_attribute_file(const std::string& file, const char* text, hsize_t user_block = 0) {
  const std::string path = (std::filesystem::temp_directory_path() / file).string();
  const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  if (user_block) H5Pset_userblock(fcpl, user_block);
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  H5Pclose(fcpl);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(f, "note", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, &text);
  H5Aclose(a), H5Sclose(space), H5Tclose(type), H5Fclose(f);
  return path;
}
std::vector<unsigned char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void put_le(unsigned char* p, std::uint64_t v, int n) {
  for (int k = 0; k < n; ++k) p[k] = static_cast<unsigned char>(v >> (8 * k));
}
// The offset of the attribute's stored value (length, collection address, index 1) in the file.
std::size_t vlen_value_at(const std::vector<unsigned char>& b, std::uint32_t length, std::uint64_t user_block = 0) {
  const std::string gcol = "GCOL";
  const auto g = std::search(b.begin(), b.end(), gcol.begin(), gcol.end());
  REQUIRE(g != b.end());
  unsigned char want[16];
  put_le(want, length, 4), put_le(want + 4, static_cast<std::uint64_t>(g - b.begin()) - user_block, 8);
  put_le(want + 12, 1, 4);
  const auto v = std::search(b.begin(), b.end(), want, want + 16);
  REQUIRE(v != b.end());
  return static_cast<std::size_t>(v - b.begin());
}
void write_bytes(const std::string& path, const std::vector<unsigned char>& b) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}
}  // namespace

TEST_CASE("a variable-length string attribute whose stored length or heap reference is damaged is refused before it is read", "[io]") {
  // HDF5 1.10 allocates and fills the stored length before it reads the heap object: a damaged
  // length made a 236 kB trace cost 1.8 GB (a libFuzzer finding). The reader checks the attribute's
  // stored value against the global heap it walked.
  const char* text = "granwave 0.1";
  const std::string path = vlen_attribute_file("granwave_io_vlen_attr.h5", text);
  CHECK(io::H5Reader(path).attr_string("/", "note") == text);  // sound: read as before
  const std::vector<unsigned char> sound = bytes_of(path);
  const std::size_t at = vlen_value_at(sound, 12);
  std::vector<unsigned char> b = sound;
  put_le(&b[at], 0x6d656d25u, 4);  // the finding's length
  write_bytes(path, b);
  CHECK_THROWS_WITH(io::H5Reader(path).attr_string("/", "note"),
                    Catch::Contains("attribute 'note' of '/' claims a string of 1835363621 bytes, where its global "
                                    "heap object holds 12") && Catch::Contains(path));
  b = sound;
  put_le(&b[at + 4], sound.size() + 98, 8);  // the collection's address damaged: no heap there
  write_bytes(path, b);
  CHECK_THROWS_WITH(io::H5Reader(path).attr_string("/", "note"),
                    Catch::Contains("claims a string of 12 bytes, in no object of the global heap"));
  // A user block before the superblock: the addresses count from the superblock.
  const std::string with_block = vlen_attribute_file("granwave_io_vlen_attr_ub.h5", text, 512);
  CHECK(io::H5Reader(with_block).attr_string("/", "note") == text);
  b = bytes_of(with_block);
  put_le(&b[vlen_value_at(b, 12, 512)], 13, 4);  // one byte more than the heap object holds
  write_bytes(with_block, b);
  CHECK_THROWS_WITH(io::H5Reader(with_block).attr_string("/", "note"),
                    Catch::Contains("claims a string of 13 bytes, where its global heap object holds 12"));
  // A length short of its object: the library copies the whole object into a buffer of the stored
  // length rounded up to 4 kB, so a reference moved to a larger object wrote past it (libFuzzer,
  // ASan: the trace's code_version pointed at a longer string of the same file).
  b = sound;
  put_le(&b[at], 11, 4);
  write_bytes(path, b);
  CHECK_THROWS_WITH(io::H5Reader(path).attr_string("/", "note"),
                    Catch::Contains("claims a string of 11 bytes, where its global heap object holds 12"));
  const std::string two = (std::filesystem::temp_directory_path() / "granwave_io_vlen_two.h5").string();
  {
    const std::string long_text(9000, 'x');
    const char* long_ptr = long_text.c_str();
    const hid_t f = H5Fcreate(two.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t space = H5Screate(H5S_SCALAR);
    for (const auto& [name, value] : {std::pair{"note", &text}, std::pair{"long", &long_ptr}}) {
      const hid_t a = H5Acreate2(f, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
      H5Awrite(a, type, value);
      H5Aclose(a);
    }
    H5Sclose(space), H5Tclose(type), H5Fclose(f);
  }
  CHECK(io::H5Reader(two).attr_string("/", "long").size() == 9000);
  b = bytes_of(two);
  // The long string's reference: the 12 bytes after its length (9000) that name a GCOL in the file.
  std::size_t long_at = 0;
  for (std::size_t k = 0; k + 16 <= b.size() && !long_at; ++k) {
    std::uint64_t len = 0, col = 0;
    for (int i = 3; i >= 0; --i) len = (len << 8) | b[k + i];
    for (int i = 7; i >= 0; --i) col = (col << 8) | b[k + 4 + i];
    if (len == 9000 && col + 4 <= b.size() && std::memcmp(&b[col], "GCOL", 4) == 0) long_at = k;
  }
  REQUIRE(long_at != 0);
  const std::size_t note_at = vlen_value_at(b, 12);
  REQUIRE(note_at != long_at);
  std::copy(b.begin() + long_at + 4, b.begin() + long_at + 16, b.begin() + note_at + 4);  // note -> the long object
  write_bytes(two, b);
  CHECK_THROWS_WITH(io::H5Reader(two).attr_string("/", "note"),
                    Catch::Contains("claims a string of 12 bytes, where its global heap object holds 9000"));
  std::filesystem::remove(path);
  std::filesystem::remove(with_block);
  std::filesystem::remove(two);
}

TEST_CASE("a variable-length string dataset whose stored length is damaged is refused before it is read", "[io]") {
  // h5py's layout (contiguous): each element is stored as an attribute's value is, and checked the same way.
  for (const hsize_t user_block : {hsize_t{0}, hsize_t{512}}) {
    const std::string path = (std::filesystem::temp_directory_path() / "granwave_io_vlen_ds.h5").string();
    const char* names[3] = {"steel", "aluminium", "glass"};
    {
      const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
      if (user_block) H5Pset_userblock(fcpl, user_block);
      const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
      const hid_t type = H5Tcopy(H5T_C_S1);
      H5Tset_size(type, H5T_VARIABLE);
      const hsize_t three = 3;
      const hid_t space = H5Screate_simple(1, &three, nullptr);
      const hid_t ds = H5Dcreate2(f, "/material_names", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, names);
      H5Dclose(ds), H5Sclose(space), H5Tclose(type), H5Fclose(f), H5Pclose(fcpl);
    }
    CHECK(io::H5Reader(path).read_strings("/material_names") == std::vector<std::string>{"steel", "aluminium", "glass"});
    std::vector<unsigned char> b = bytes_of(path);
    // Element 1 ("aluminium"): its length, 9, then the collection's address (the library numbers the
    // objects in its own order).
    const std::string gcol = "GCOL";
    const auto g = static_cast<std::uint64_t>(std::search(b.begin(), b.end(), gcol.begin(), gcol.end()) - b.begin());
    unsigned char want[12];
    put_le(want, 9, 4), put_le(want + 4, g - user_block, 8);
    const auto at = std::search(b.begin(), b.end(), want, want + 12);
    REQUIRE(at != b.end());
    put_le(&*at, 4, 4);  // 4 of its 9 bytes
    write_bytes(path, b);
    CHECK_THROWS_WITH(io::H5Reader(path).read_strings("/material_names"),
                      Catch::Contains("dataset '/material_names' element 1 claims a string of 4 bytes, where its "
                                      "global heap object holds 9") && Catch::Contains(path));
    std::filesystem::remove(path);
  }
}
