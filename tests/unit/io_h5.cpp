// The HDF5 layer: what is written reads back bit for bit, through the temporary name.
#include <catch2/catch.hpp>

#include <filesystem>

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
