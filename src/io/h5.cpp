// The one translation unit that includes H5Cpp.h (it is heavy to compile).
#include "io/h5.hpp"

#include <H5Cpp.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "core/error.hpp"
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

struct H5Writer::Impl {
  std::string tmp_path;
  std::unique_ptr<H5::H5File> file;
};

H5Writer::H5Writer(std::string final_path) : impl_(std::make_unique<Impl>()), final_path_(std::move(final_path)) {
  H5::Exception::dontPrint();
  impl_->tmp_path = final_path_ + ".tmp";
  try {
    impl_->file = std::make_unique<H5::H5File>(impl_->tmp_path, H5F_ACC_TRUNC);
  } catch (const H5::Exception& e) {
    throw RunError("cannot create '" + impl_->tmp_path + "': " + e.getDetailMsg());
  }
}

H5Writer::~H5Writer() {
  if (!committed_ && impl_) {
    try {
      impl_->file->close();
    } catch (...) {
    }
    std::remove(impl_->tmp_path.c_str());
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
    throw RunError("cannot write '" + object + "' to '" + tmp_path + "': " + e.getDetailMsg());
  }
}

template <class T>
void write_numeric(H5::H5File& file, const std::string& path, const std::vector<T>& data, std::vector<std::size_t> dims,
                   const H5::PredType& type) {
  auto shape = shape_of(std::move(dims), data.size());
  ensure_groups(file, path, true);
  H5::DataSpace space(static_cast<int>(shape.size()), shape.data());
  H5::DataSet ds = file.createDataSet(path, type, space);
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
    hsize_t n = data.size();
    H5::DataSpace space(1, &n);
    H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
    type.setCset(H5T_CSET_UTF8);
    H5::DataSet ds = impl_->file->createDataSet(path, type, space);
    std::vector<const char*> ptrs;
    for (const auto& s : data) ptrs.push_back(s.c_str());
    if (!data.empty()) ds.write(ptrs.data(), type);
  });
}

void H5Writer::group(const std::string& path) {
  writing(impl_->tmp_path, path, [&] { ensure_groups(*impl_->file, path, false); });
}

void H5Writer::attr(const std::string& object, const std::string& name, const std::string& value) {
  if (object != "/" && !exists(*impl_->file, impl_->tmp_path, object)) group(object);
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  const char* p = value.c_str();
  write_attr(impl_->file->getId(), object, name, type.getId(), &p);
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
  try {
    impl_->file->close();
  } catch (const H5::Exception& e) {
    throw RunError("cannot close '" + impl_->tmp_path + "': " + e.getDetailMsg());
  }
  std::error_code ec;
  std::filesystem::rename(impl_->tmp_path, final_path_, ec);
  if (ec) throw RunError("cannot rename '" + impl_->tmp_path + "' to '" + final_path_ + "': " + ec.message());
  committed_ = true;
}

// ---------------------------------------------------------------------------------------------

struct H5Reader::Impl {
  std::unique_ptr<H5::H5File> file;
};

H5Reader::H5Reader(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  H5::Exception::dontPrint();
  if (!std::filesystem::exists(path)) throw InputError(path + ": no such file");
  try {
    impl_->file = std::make_unique<H5::H5File>(path, H5F_ACC_RDONLY);
  } catch (const H5::Exception& e) {
    throw InputError(path + ": not a readable HDF5 file (" + e.getDetailMsg() + ")");
  }
}

H5Reader::~H5Reader() = default;

bool H5Reader::has(const std::string& path) const {
  // nameExists fails on a missing intermediate group; check each prefix. On a damaged file the
  // library throws instead of answering: that is bad input, named, never an H5::Exception let out.
  std::string cur;
  try {
    for (const auto& p : split_path(path)) {
      cur += "/" + p;
      if (!impl_->file->nameExists(cur)) return false;
    }
  } catch (const H5::Exception& e) {
    throw InputError(path_ + ": damaged file: cannot look up '" + cur + "' (" + e.getDetailMsg() + ")");
  }
  return true;
}

namespace {
template <class T>
std::vector<T> read_numeric(H5::H5File& file, const std::string& file_path, const std::string& path,
                            const H5::PredType& type, std::vector<std::size_t>* dims) {
  try {
    H5::DataSet ds = file.openDataSet(path);
    H5::DataSpace space = ds.getSpace();
    int rank = space.getSimpleExtentNdims();
    std::vector<hsize_t> d(static_cast<std::size_t>(rank));
    space.getSimpleExtentDims(d.data());
    std::size_t n = 1;
    for (auto x : d) n *= x;
    std::vector<T> out(n);
    if (n) ds.read(out.data(), type);
    if (dims) dims->assign(d.begin(), d.end());
    return out;
  } catch (const H5::Exception& e) {
    throw InputError(file_path + ": cannot read dataset '" + path + "' (" + e.getDetailMsg() + ")");
  }
}
}  // namespace

std::vector<double> H5Reader::read_double(const std::string& path, std::vector<std::size_t>* dims) const {
  return read_numeric<double>(*impl_->file, path_, path, H5::PredType::NATIVE_DOUBLE, dims);
}

std::vector<std::int64_t> H5Reader::read_int(const std::string& path, std::vector<std::size_t>* dims) const {
  return read_numeric<std::int64_t>(*impl_->file, path_, path, H5::PredType::NATIVE_INT64, dims);
}

std::vector<std::string> H5Reader::read_strings(const std::string& path) const {
  try {
    H5::DataSet ds = impl_->file->openDataSet(path);
    H5::DataSpace space = ds.getSpace();
    hsize_t n = 0;
    space.getSimpleExtentDims(&n);
    H5::DataType ftype = ds.getDataType();
    std::vector<std::string> out;
    const H5T_cset_t cset = H5Tget_cset(ftype.getId());  // read in the file's character set
    if (ftype.isVariableStr()) {
      H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
      type.setCset(cset);
      std::vector<char*> ptrs(n);
      if (n) ds.read(ptrs.data(), type);
      for (auto* p : ptrs) out.emplace_back(p ? p : "");
      H5Dvlen_reclaim(type.getId(), space.getId(), H5P_DEFAULT, ptrs.data());
    } else {  // fixed-length strings (h5py writes these for numpy 'S' arrays)
      std::size_t len = ftype.getSize();
      std::vector<char> buf(n * len);
      H5::StrType type(H5::PredType::C_S1, len);
      type.setCset(cset);
      if (n) ds.read(buf.data(), type);
      for (hsize_t i = 0; i < n; ++i) {
        std::string s(buf.data() + i * len, len);
        out.push_back(s.substr(0, s.find('\0')));
      }
    }
    return out;
  } catch (const H5::Exception& e) {
    throw InputError(path_ + ": cannot read strings '" + path + "' (" + e.getDetailMsg() + ")");
  }
}

bool H5Reader::has_attr(const std::string& object, const std::string& name) const {
  if (object != "/" && !has(object)) return false;
  return H5Aexists_by_name(impl_->file->getId(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string H5Reader::attr_string(const std::string& object, const std::string& name) const {
  ObjectHandle obj(impl_->file->getId(), object);
  hid_t a = obj.id >= 0 ? H5Aopen(obj.id, name.c_str(), H5P_DEFAULT) : -1;
  if (a < 0) throw InputError(path_ + ": no attribute '" + name + "' on '" + object + "'");
  hid_t ftype = H5Aget_type(a);
  std::string out;
  herr_t err;
  if (H5Tis_variable_str(ftype) > 0) {
    char* p = nullptr;
    hid_t mtype = H5Tcopy(H5T_C_S1);
    H5Tset_size(mtype, H5T_VARIABLE);
    H5Tset_cset(mtype, H5Tget_cset(ftype));  // HDF5 does not convert between ASCII and UTF-8
    err = H5Aread(a, mtype, &p);
    if (err >= 0 && p) { out = p; H5free_memory(p); }
    H5Tclose(mtype);
  } else {  // fixed-length (h5py writes numpy bytes this way)
    std::size_t len = H5Tget_size(ftype);
    std::vector<char> buf(len + 1, '\0');
    hid_t mtype = H5Tcopy(H5T_C_S1);
    H5Tset_size(mtype, len);
    H5Tset_cset(mtype, H5Tget_cset(ftype));
    H5Tset_strpad(mtype, H5Tget_strpad(ftype));
    err = H5Aread(a, mtype, buf.data());
    out = std::string(buf.data());
    H5Tclose(mtype);
  }
  H5Tclose(ftype);
  H5Aclose(a);
  if (err < 0) throw InputError(path_ + ": cannot read attribute '" + name + "' of '" + object + "' as text");
  return out;
}

double H5Reader::attr_double(const std::string& object, const std::string& name) const {
  ObjectHandle obj(impl_->file->getId(), object);
  hid_t a = obj.id >= 0 ? H5Aopen(obj.id, name.c_str(), H5P_DEFAULT) : -1;
  if (a < 0) throw InputError(path_ + ": no attribute '" + name + "' on '" + object + "'");
  double v = 0;
  herr_t err = H5Aread(a, H5T_NATIVE_DOUBLE, &v);  // converts integer attributes too
  H5Aclose(a);
  if (err < 0) throw InputError(path_ + ": cannot read attribute '" + name + "' of '" + object + "' as a number");
  return v;
}

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
