// What the writer and the reader of HDF5 files share (io/h5.cpp, io/h5_read.cpp); included by those two only.
#pragma once
#include <H5Cpp.h>

#include <memory>
#include <string>
#include <vector>

#include "io/h5.hpp"

namespace granwave::io {

namespace detail {

// The parts of an object path ("/a/b" -> a, b).
std::vector<std::string> split_path(const std::string& path);

// The innermost description on the HDF5 error stack (the most specific), and whether any entry
// reports a checksum failure (Fletcher-32 on raw data, Jenkins lookup3 on metadata). Clears it.
struct LibraryFailure {
  std::string why;
  bool checksum = false;
};
LibraryFailure library_failure();

}  // namespace detail

struct H5Writer::Impl {
  std::string tmp_path;
  std::unique_ptr<H5::H5File> file;
  bool in_memory = false;
};

}  // namespace granwave::io
