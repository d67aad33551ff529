#include "io/hdf5_util.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <type_traits>

namespace weft::io::h5 {
namespace {

// How a C++ number type is stored in memory and in files.
template <class T>
hid_t native_type();
template <class T>
hid_t file_type();
template <> hid_t native_type<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t native_type<int>() { return H5T_NATIVE_INT; }
template <> hid_t native_type<int64_t>() { return H5T_NATIVE_INT64; }
template <> hid_t file_type<double>() { return H5T_IEEE_F64LE; }
template <> hid_t file_type<int>() { return H5T_STD_I32LE; }
template <> hid_t file_type<int64_t>() { return H5T_STD_I64LE; }

// HDF5 prints its error stack to stderr by default; weft reports errors itself.
void quiet() {
  static const bool done = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)done;
}

herr_t first_error(unsigned n, const H5E_error2_t* e, void* out) {
  if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
  return 0;
}

Handle property_list(hid_t cls) { return Handle(check(H5Pcreate(cls), "cannot create an HDF5 property list"), H5Pclose); }

// File access: the latest format where SWMR needs it; file locks where the file system has them (HDF5
// otherwise refuses to open files on, say, some network file systems).
Handle file_access(bool latest) {
  Handle fapl = property_list(H5P_FILE_ACCESS);
  const std::string what = "cannot set up HDF5 file access";
  if (latest) check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), what);
#if H5_VERSION_GE(1, 10, 7)
  check(H5Pset_file_locking(fapl.get(), true, true), what);
#endif
  return fapl;
}

Handle link_creation() {
  Handle lcpl = property_list(H5P_LINK_CREATE);
  check(H5Pset_create_intermediate_group(lcpl.get(), 1), "cannot set up HDF5 link creation");
  return lcpl;
}

std::string expected_string(const std::vector<long>& expect) {
  std::string s = "[";
  for (size_t i = 0; i < expect.size(); ++i)
    s += (i ? " x " : "") + (expect[i] < 0 ? std::string("N") : std::to_string(expect[i]));
  return s + "]";
}

// The stored values must be of the kind asked for: floating-point for double, integers otherwise.
template <class T>
void check_class(const File& f, const std::string& object, hid_t type) {
  const H5T_class_t want = std::is_floating_point<T>::value ? H5T_FLOAT : H5T_INTEGER;
  const H5T_class_t have = H5Tget_class(type);
  const auto kind = [](H5T_class_t c) {
    return c == H5T_FLOAT ? "floating-point numbers" : c == H5T_INTEGER ? "integers" : "non-numbers";
  };
  if (have != want) fail(f, object, std::string("holds ") + kind(have) + ", expected " + kind(want));
}

Handle open_attribute(const File& f, const std::string& object, const std::string& name) {
  if (!exists(f, object)) fail(f, object, "missing");
  if (H5Aexists_by_name(f.id(), object.c_str(), name.c_str(), H5P_DEFAULT) <= 0)
    fail(f, object, "missing attribute '" + name + "'");
  return Handle(H5Aopen_by_name(f.id(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
}

hssize_t attribute_size(const Handle& a) {
  Handle space(H5Aget_space(a.get()), H5Sclose);
  return space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
}

void write_attribute_raw(const File& f, const std::string& object, const std::string& name, hid_t ftype,
                         hid_t mtype, const Handle& space, const void* data) {
  const std::string what = f.path() + ": cannot write attribute '" + name + "' of " + object;
  Handle a(check(H5Acreate_by_name(f.id(), object.c_str(), name.c_str(), ftype, space.get(), H5P_DEFAULT,
                                   H5P_DEFAULT, H5P_DEFAULT),
                 what),
           H5Aclose);
  check(H5Awrite(a.get(), mtype, data), what);
}

}  // namespace

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

herr_t Handle::reset() {
  herr_t r = 0;
  if (id_ >= 0 && close_) r = close_(id_);
  id_ = H5I_INVALID_HID;
  return r;
}

std::string last_error() {
  std::string s;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_error, &s);
  // System call failures read "... errno = 2, error message = 'No such file or directory', ...": keep the reason.
  const std::string key = "error message = '";
  const size_t at = s.find(key);
  if (at != std::string::npos) {
    const size_t end = s.find('\'', at + key.size());
    if (end != std::string::npos) return s.substr(at + key.size(), end - at - key.size());
  }
  return s;
}

hid_t check(hid_t status, const std::string& what) {
  if (status < 0) {
    const std::string why = last_error();
    throw std::runtime_error(what + (why.empty() ? "" : ": " + why));
  }
  return status;
}

File File::open(const std::string& path) {
  quiet();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FormatError(path + ": no such file");
  const htri_t is = H5Fis_hdf5(path.c_str());
  if (is == 0) throw FormatError(path + ": not an HDF5 file");
  if (is < 0) throw FormatError(path + ": cannot read (" + last_error() + ")");
  const Handle fapl = file_access(false);
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl.get());
  if (id < 0) id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get());  // not written for SWMR
  if (id < 0) throw FormatError(path + ": cannot open (" + last_error() + ")");
  return File(Handle(id, H5Fclose), path, "");
}

File File::create(const std::string& path, bool swmr) {
  quiet();
  static std::atomic<unsigned> serial{0};
  const std::string tmp = path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(serial++);
  const Handle fapl = file_access(swmr);
  Handle id(check(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()), "cannot create " + path), H5Fclose);
  return File(std::move(id), path, tmp);
}

File::File(File&& o) noexcept : h_(std::move(o.h_)), path_(std::move(o.path_)), temporary_(std::move(o.temporary_)) {
  o.temporary_.clear();
}

File::~File() {
  h_.reset();
  if (!temporary_.empty()) std::remove(temporary_.c_str());
}

void File::publish() {
  if (temporary_.empty()) return;
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
    throw std::system_error(errno, std::generic_category(), "cannot rename " + temporary_ + " to " + path_);
  temporary_.clear();
}

void File::close() {
  if (!h_.valid()) return;
  check(H5Fflush(h_.get(), H5F_SCOPE_GLOBAL), "cannot write " + path_);
  check(h_.reset(), "cannot close " + path_);
}

void write_atomically(const std::string& path, const std::function<void(const File&)>& body) {
  File f = File::create(path, false);
  body(f);
  f.close();
  f.publish();
}

std::string format_of(const File& f) {
  return has_attribute(f, "/", "weft_format") ? read_string_attribute(f, "/", "weft_format") : std::string();
}

void check_format(const File& f, const std::string& kind, int version) {
  const std::string have = format_of(f);
  if (have != kind)
    throw FormatError(f.path() + ": not a " + kind + " file (" +
                      (have.empty() ? std::string("no weft_format attribute") : "weft_format is '" + have + "'") + ")");
  const int v = read_attribute<int>(f, "/", "format_version");
  if (v != version)
    throw FormatError(f.path() + ": format_version is " + std::to_string(v) + "; this weft reads " + kind +
                      " version " + std::to_string(version));
}

void fail(const File& f, const std::string& object, const std::string& what) {
  throw FormatError(f.path() + ": " + object + ": " + what);
}

bool exists(const File& f, const std::string& object) {
  if (object == "/") return true;
  for (size_t at = object.find('/', 1);; at = object.find('/', at + 1)) {
    const std::string prefix = object.substr(0, at);
    if (H5Lexists(f.id(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (at == std::string::npos) return true;
  }
}

Handle open_dataset(const File& f, const std::string& name) {
  if (!exists(f, name)) fail(f, name, "missing dataset");
  Handle d(H5Dopen2(f.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) fail(f, name, "is not a dataset");
  return d;
}

std::vector<hsize_t> shape(const File& f, const Handle& dataset) {
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  char name[512] = "dataset";
  H5Iget_name(dataset.get(), name, sizeof name);
  if (rank < 0) fail(f, name, "has no simple shape");
  std::vector<hsize_t> dims(rank);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

std::string shape_string(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? " x " : "") + std::to_string(dims[i]);
  return s + "]";
}

template <class T>
std::vector<T> read(const File& f, const std::string& name, const std::vector<long>& expect, std::vector<hsize_t>* dims) {
  const Handle d = open_dataset(f, name);
  const std::vector<hsize_t> have = shape(f, d);
  bool ok = have.size() == expect.size();
  for (size_t i = 0; ok && i < have.size(); ++i) ok = expect[i] < 0 || hsize_t(expect[i]) == have[i];
  if (!ok) fail(f, name, "has shape " + shape_string(have) + ", expected " + expected_string(expect));
  const Handle type(H5Dget_type(d.get()), H5Tclose);
  check_class<T>(f, name, type.get());
  size_t count = 1;
  for (hsize_t n : have) count *= size_t(n);
  std::vector<T> v(count);
  if (count > 0 && H5Dread(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    fail(f, name, "cannot be read (" + last_error() + ")");
  if (dims) *dims = have;
  return v;
}

template <class T>
std::vector<T> read_rows(const File& f, const Handle& dataset, hsize_t first, hsize_t count) {
  char name[512] = "dataset";
  H5Iget_name(dataset.get(), name, sizeof name);
  std::vector<hsize_t> dims = shape(f, dataset);
  if (dims.empty() || first + count > dims[0])
    fail(f, name, "has no rows " + std::to_string(first) + " to " + std::to_string(first + count) + " (shape " +
                      shape_string(dims) + ")");
  const Handle type(H5Dget_type(dataset.get()), H5Tclose);
  check_class<T>(f, name, type.get());
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = first;
  dims[0] = count;
  size_t n = 1;
  for (hsize_t d : dims) n *= size_t(d);
  std::vector<T> v(n);
  if (n == 0) return v;
  const Handle file_space(H5Dget_space(dataset.get()), H5Sclose);
  const Handle mem_space(H5Screate_simple(int(dims.size()), dims.data(), nullptr), H5Sclose);
  if (!file_space.valid() || !mem_space.valid() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, dims.data(), nullptr) < 0 ||
      H5Dread(dataset.get(), native_type<T>(), mem_space.get(), file_space.get(), H5P_DEFAULT, v.data()) < 0)
    fail(f, name, "cannot read rows " + std::to_string(first) + " to " + std::to_string(first + count) + " (" +
                      last_error() + ")");
  return v;
}

template <class T>
T read_attribute(const File& f, const std::string& object, const std::string& name) {
  const Handle a = open_attribute(f, object, name);
  const Handle type(H5Aget_type(a.get()), H5Tclose);
  check_class<T>(f, object + " attribute '" + name + "'", type.get());
  if (attribute_size(a) != 1) fail(f, object, "attribute '" + name + "' is not a single value");
  T value{};
  if (H5Aread(a.get(), native_type<T>(), &value) < 0) fail(f, object, "cannot read attribute '" + name + "'");
  return value;
}

std::string read_string_attribute(const File& f, const std::string& object, const std::string& name) {
  const Handle a = open_attribute(f, object, name);
  const Handle type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || attribute_size(a) != 1)
    fail(f, object, "attribute '" + name + "' is not a string");
  const std::string what = "cannot read attribute '" + name + "'";
  if (H5Tis_variable_str(type.get()) > 0) {
    char* s = nullptr;
    if (H5Aread(a.get(), type.get(), &s) < 0) fail(f, object, what);
    std::string r = s ? s : "";
    H5free_memory(s);
    return r;
  }
  std::vector<char> buf(H5Tget_size(type.get()) + 1, 0);
  if (H5Aread(a.get(), type.get(), buf.data()) < 0) fail(f, object, what);
  return std::string(buf.data());
}

std::vector<double> read_vector_attribute(const File& f, const std::string& object, const std::string& name,
                                          size_t size) {
  const Handle a = open_attribute(f, object, name);
  const Handle type(H5Aget_type(a.get()), H5Tclose);
  check_class<double>(f, object + " attribute '" + name + "'", type.get());
  if (attribute_size(a) != hssize_t(size))
    fail(f, object, "attribute '" + name + "' has " + std::to_string(attribute_size(a)) + " values, expected " +
                        std::to_string(size));
  std::vector<double> v(size);
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, v.data()) < 0) fail(f, object, "cannot read attribute '" + name + "'");
  return v;
}

bool has_attribute(const File& f, const std::string& object, const std::string& name) {
  return exists(f, object) && H5Aexists_by_name(f.id(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

void create_group(const File& f, const std::string& name) {
  const Handle lcpl = link_creation();
  Handle(check(H5Gcreate2(f.id(), name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
               f.path() + ": cannot create group " + name),
         H5Gclose);
}

template <class T>
void write(const File& f, const std::string& name, const T* data, const std::vector<hsize_t>& dims) {
  const std::string what = f.path() + ": cannot write " + name;
  const Handle lcpl = link_creation();
  const Handle space(check(H5Screate_simple(int(dims.size()), dims.data(), nullptr), what), H5Sclose);
  const Handle d(check(H5Dcreate2(f.id(), name.c_str(), file_type<T>(), space.get(), lcpl.get(), H5P_DEFAULT,
                                  H5P_DEFAULT),
                       what),
                 H5Dclose);
  size_t count = 1;
  for (hsize_t n : dims) count *= size_t(n);
  if (count > 0) check(H5Dwrite(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data), what);
}

template <class T>
void write_attribute(const File& f, const std::string& object, const std::string& name, T value) {
  const Handle space(check(H5Screate(H5S_SCALAR), f.path() + ": cannot write " + object), H5Sclose);
  write_attribute_raw(f, object, name, file_type<T>(), native_type<T>(), space, &value);
}

void write_attribute(const File& f, const std::string& object, const std::string& name, const std::string& value) {
  const std::string what = f.path() + ": cannot write " + object;
  const Handle type(check(H5Tcopy(H5T_C_S1), what), H5Tclose);
  check(H5Tset_size(type.get(), H5T_VARIABLE), what);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), what);
  const Handle space(check(H5Screate(H5S_SCALAR), what), H5Sclose);
  const char* s = value.c_str();
  write_attribute_raw(f, object, name, type.get(), type.get(), space, &s);
}

void write_attribute(const File& f, const std::string& object, const std::string& name, const char* value) {
  write_attribute(f, object, name, std::string(value));
}

void write_vector_attribute(const File& f, const std::string& object, const std::string& name,
                            const std::vector<double>& values) {
  const hsize_t n = values.size();
  const Handle space(check(H5Screate_simple(1, &n, nullptr), f.path() + ": cannot write " + object), H5Sclose);
  write_attribute_raw(f, object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space, values.data());
}

#define WEFT_H5_INSTANTIATE(T)                                                                                   \
  template std::vector<T> read<T>(const File&, const std::string&, const std::vector<long>&, std::vector<hsize_t>*); \
  template std::vector<T> read_rows<T>(const File&, const Handle&, hsize_t, hsize_t);                           \
  template T read_attribute<T>(const File&, const std::string&, const std::string&);                            \
  template void write<T>(const File&, const std::string&, const T*, const std::vector<hsize_t>&);              \
  template void write_attribute<T>(const File&, const std::string&, const std::string&, T);
WEFT_H5_INSTANTIATE(double)
WEFT_H5_INSTANTIATE(int)
WEFT_H5_INSTANTIATE(int64_t)
#undef WEFT_H5_INSTANTIATE

}  // namespace weft::io::h5
