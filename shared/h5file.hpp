// Thin RAII wrapper over the HDF5 C API: typed datasets with Fletcher32 checksums, scalar attributes.
// Every failure becomes an rk::Error naming the file and the dataset.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rk {

class H5File {
 public:
  enum class Mode { read, create, append };
  H5File(const std::string& path, Mode mode);
  ~H5File();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  const std::string& path() const { return path_; }
  // Flushes and closes; throws if the data did not reach the file (disk full). The destructor closes
  // without checking.
  void close();

  // Datasets are 2-D (rows x cols), chunked and Fletcher32-checksummed; "a/b/c" creates groups.
  template <class T>
  void write(const std::string& name, const std::vector<T>& data, std::size_t cols = 1);
  template <class T>
  std::vector<T> read(const std::string& name, std::size_t cols = 1) const;
  bool exists(const std::string& name) const;
  void remove(const std::string& name);  // unlinks a dataset or group if present

  void set_attr(const std::string& name, std::int64_t value);
  void set_attr(const std::string& name, double value);
  void set_attr(const std::string& name, const std::string& value);
  bool has_attr(const std::string& name) const;
  std::int64_t attr_int(const std::string& name) const;
  double attr_double(const std::string& name) const;
  std::string attr_string(const std::string& name) const;

 private:
  void write_raw(const std::string& name, hid_t type, const void* data, std::size_t rows, std::size_t cols);
  std::size_t read_raw(const std::string& name, hid_t type, std::size_t elem_size, std::size_t cols,
                       std::vector<unsigned char>& out) const;
  std::string path_;
  hid_t file_ = -1;
};

}  // namespace rk
