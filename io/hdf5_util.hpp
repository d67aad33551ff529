// What the HDF5 scene and cache files share: identifiers that close themselves, files opened for reading or
// created for writing, and whole-dataset and attribute access with checked shapes. Reading failures throw
// FormatError naming the file and the dataset or attribute; writing failures throw std::runtime_error naming
// the file, with HDF5's own reason.
#pragma once
#include "io/trimesh.hpp"

#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace weft::io::h5 {

// An HDF5 identifier, closed with its kind's close function when the handle goes.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  herr_t reset();  // closes now; returns the close function's status (0 when there was nothing to close)

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

// HDF5's innermost error description from the current error stack ("" when there is none).
std::string last_error();

// Throws std::runtime_error("<what>: <last_error()>") when `status` is negative; returns it otherwise.
hid_t check(hid_t status, const std::string& what);

// An open file and its name, for messages.
class File {
 public:
  // For reading: missing files and non-HDF5 files throw FormatError. Files created for single-writer /
  // multiple-reader access open in SWMR read mode, so a cache can be read while (or after) a run writes it.
  static File open(const std::string& path);
  // A new file under a temporary name in the folder of `path`; publish() gives it that name, and a File
  // destroyed before then removes it. `swmr` uses the latest file format, as SWMR writing needs.
  static File create(const std::string& path, bool swmr);
  File(File&& o) noexcept;
  File& operator=(File&&) = delete;
  ~File();
  hid_t id() const { return h_.get(); }
  const std::string& path() const { return path_; }
  void publish();  // renames the temporary file to path(); it may stay open
  void close();    // flushes and closes, throwing on failure (the destructor cannot report)

 private:
  File(Handle h, std::string path, std::string temporary)
      : h_(std::move(h)), path_(std::move(path)), temporary_(std::move(temporary)) {}
  Handle h_;
  std::string path_, temporary_;  // temporary_: empty once published, or for files opened for reading
};

// FormatError("<file>: <object>: <what>").
[[noreturn]] void fail(const File& f, const std::string& object, const std::string& what);

bool exists(const File& f, const std::string& object);  // "/a/b/c": every link on the way exists
Handle open_dataset(const File& f, const std::string& name);  // FormatError "missing dataset" when absent
std::vector<hsize_t> shape(const File& f, const Handle& dataset);
std::string shape_string(const std::vector<hsize_t>& dims);   // "[4 x 3]"

// A whole dataset of numbers (double, int or int64_t) whose shape must match `expect`, -1 matching any
// extent; a floating-point dataset for double, an integer one otherwise. `dims` receives the actual shape.
template <class T>
std::vector<T> read(const File& f, const std::string& name, const std::vector<long>& expect,
                    std::vector<hsize_t>* dims = nullptr);
// Rows [first, first + count) along the first dimension of a dataset of rank >= 1.
template <class T>
std::vector<T> read_rows(const File& f, const Handle& dataset, hsize_t first, hsize_t count);

template <class T>
T read_attribute(const File& f, const std::string& object, const std::string& name);
std::string read_string_attribute(const File& f, const std::string& object, const std::string& name);
std::vector<double> read_vector_attribute(const File& f, const std::string& object, const std::string& name,
                                          size_t size);
bool has_attribute(const File& f, const std::string& object, const std::string& name);

// Writing creates intermediate groups; data is stored little-endian, doubles as IEEE binary64 (exactly).
void create_group(const File& f, const std::string& name);
template <class T>
void write(const File& f, const std::string& name, const T* data, const std::vector<hsize_t>& dims);
template <class T>
void write_attribute(const File& f, const std::string& object, const std::string& name, T value);
void write_attribute(const File& f, const std::string& object, const std::string& name, const std::string& value);
void write_attribute(const File& f, const std::string& object, const std::string& name, const char* value);
void write_vector_attribute(const File& f, const std::string& object, const std::string& name,
                            const std::vector<double>& values);

// weft's files name their kind and version in root attributes `weft_format` and `format_version`.
std::string format_of(const File& f);  // weft_format, or "" when the file has none
// FormatError unless the file is of this kind and version.
void check_format(const File& f, const std::string& kind, int version);

// Writes a new HDF5 file through `body` under a temporary name, renamed into place once complete and closed,
// so a failure leaves no file behind.
void write_atomically(const std::string& path, const std::function<void(const File&)>& body);

}  // namespace weft::io::h5
