#include "h5file.hpp"

#include <cstring>

#include "error.hpp"

namespace rk {
namespace {

template <class T>
hid_t h5type();
template <> hid_t h5type<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t h5type<float>() { return H5T_NATIVE_FLOAT; }
template <> hid_t h5type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <> hid_t h5type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <> hid_t h5type<std::uint8_t>() { return H5T_NATIVE_UINT8; }

struct Handle {  // closes any HDF5 object id on scope exit
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

}  // namespace

H5File::H5File(const std::string& path, Mode mode) : path_(path) {
  // No clean-up by HDF5 at exit (before the library's first call): it closes what is left open, and a
  // file whose close failed on a full disk crashed it there (a segfault in H5F__close_cb, HDF5 1.10)
  // after the error was reported; every file here is closed by its owner.
  static const bool no_atexit = H5dont_atexit() >= 0;
  (void)no_atexit;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // our messages, not HDF5's error stack
  if (mode == Mode::create) {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) throw Error(path + ": cannot create the file (directory missing or not writable?)");
  } else if (mode == Mode::append) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (file_ < 0) throw Error(path + ": cannot open the file for appending");
  } else {
    if (H5Fis_hdf5(path.c_str()) <= 0) {
      FILE* f = std::fopen(path.c_str(), "rb");
      if (!f) throw Error(path + ": file not found");
      std::fclose(f);
      throw Error(path + ": not an HDF5 file (truncated or corrupt)");
    }
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) throw Error(path + ": cannot open the HDF5 file (truncated or corrupt)");
  }
}

H5File::~H5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5File::close() {
  const bool flushed = H5Fflush(file_, H5F_SCOPE_GLOBAL) >= 0;
  const bool closed = H5Fclose(file_) >= 0;
  file_ = -1;
  if (!flushed || !closed) throw Error(path_ + ": the file could not be completed (disk full?)");
}

bool H5File::exists(const std::string& name) const {
  // Walk the path so that a missing intermediate group is not an error.
  std::size_t pos = 0;
  while ((pos = name.find('/', pos + 1)) != std::string::npos)
    if (H5Lexists(file_, name.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

void H5File::remove(const std::string& name) {
  if (exists(name) && H5Ldelete(file_, name.c_str(), H5P_DEFAULT) < 0) throw Error(path_ + ": cannot remove '" + name + "'");
}

void H5File::write_raw(const std::string& name, hid_t type, const void* data, std::size_t rows,
                       std::size_t cols) {
  hsize_t dims[2] = {rows, cols};
  Handle space{H5Screate_simple(2, dims, nullptr), H5Sclose};
  Handle lcpl{H5Pcreate(H5P_LINK_CREATE), H5Pclose};
  H5Pset_create_intermediate_group(lcpl.id, 1);
  Handle dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
  if (rows > 0 && cols > 0) {
    hsize_t chunk[2] = {std::min<hsize_t>(rows, std::max<hsize_t>(1, 65536 / cols)), cols};
    H5Pset_chunk(dcpl.id, 2, chunk);
    H5Pset_fletcher32(dcpl.id);
  }
  Handle set{H5Dcreate2(file_, name.c_str(), type, space.id, lcpl.id, dcpl.id, H5P_DEFAULT), H5Dclose};
  if (set.id < 0) throw Error(path_ + ": cannot create dataset '" + name + "'");
  if (rows > 0 && cols > 0 && H5Dwrite(set.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw Error(path_ + ": cannot write dataset '" + name + "' (disk full?)");
}

std::size_t H5File::read_raw(const std::string& name, hid_t type, std::size_t elem_size, std::size_t cols,
                             std::vector<unsigned char>& out) const {
  if (!exists(name)) throw Error(path_ + ": dataset '" + name + "' is missing");
  Handle set{H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (set.id < 0) throw Error(path_ + ": cannot open dataset '" + name + "' (corrupt file?)");
  Handle space{H5Dget_space(set.id), H5Sclose};
  hsize_t dims[2] = {0, 0};
  int rank = H5Sget_simple_extent_ndims(space.id);
  if (rank != 2) throw Error(path_ + ": dataset '" + name + "' has the wrong shape");
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  if (dims[0] > 0 && dims[1] != cols)
    throw Error(path_ + ": dataset '" + name + "' has " + std::to_string(dims[1]) + " columns, expected " +
                std::to_string(cols));
  hsize_t file_size = 0;
  H5Fget_filesize(file_, &file_size);
  if (dims[1] != 0 && dims[0] > file_size / (dims[1] * elem_size))  // uncompressed: it must fit in the file
    throw Error(path_ + ": dataset '" + name + "' claims more data than the file holds (corrupt file)");
  if (dims[0] * dims[1] > 0) {  // rkforge stores data chunked with Fletcher32: anything else is corrupt or foreign
    Handle dcpl{H5Dget_create_plist(set.id), H5Pclose};
    bool checksummed = false;
    for (int k = 0; k < H5Pget_nfilters(dcpl.id); ++k) {
      unsigned flags = 0;
      std::size_t nelmts = 0;
      unsigned values[4];
      checksummed |= H5Pget_filter2(dcpl.id, unsigned(k), &flags, &nelmts, values, 0, nullptr, nullptr) == H5Z_FILTER_FLETCHER32;
    }
    if (H5Pget_layout(dcpl.id) != H5D_CHUNKED || !checksummed ||
        H5Dget_storage_size(set.id) < dims[0] * dims[1] * elem_size)
      throw Error(path_ + ": dataset '" + name + "' is not stored as rkforge writes it (corrupt file)");
  }
  out.resize(dims[0] * dims[1] * elem_size);
  if (dims[0] > 0 && H5Dread(set.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw Error(path_ + ": dataset '" + name + "' cannot be read: checksum mismatch or truncated file");
  return dims[0] * dims[1];
}

template <class T>
void H5File::write(const std::string& name, const std::vector<T>& data, std::size_t cols) {
  if (cols == 0 || data.size() % cols != 0)
    throw Error(path_ + ": dataset '" + name + "' size is not a multiple of its columns");
  write_raw(name, h5type<T>(), data.data(), data.size() / cols, cols);
}

template <class T>
std::vector<T> H5File::read(const std::string& name, std::size_t cols) const {
  std::vector<unsigned char> bytes;
  std::size_t n = read_raw(name, h5type<T>(), sizeof(T), cols, bytes);
  std::vector<T> out(n);
  if (n) std::memcpy(out.data(), bytes.data(), n * sizeof(T));
  return out;
}

#define RK_H5_INSTANTIATE(T)                                                                       \
  template void H5File::write<T>(const std::string&, const std::vector<T>&, std::size_t);         \
  template std::vector<T> H5File::read<T>(const std::string&, std::size_t) const;
RK_H5_INSTANTIATE(double)
RK_H5_INSTANTIATE(float)
RK_H5_INSTANTIATE(std::int64_t)
RK_H5_INSTANTIATE(std::int32_t)
RK_H5_INSTANTIATE(std::uint8_t)
#undef RK_H5_INSTANTIATE

namespace {
void set_attr_raw(hid_t file, const std::string& path, const std::string& name, hid_t type,
                  const void* value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  if (H5Aexists(file, name.c_str()) > 0) H5Adelete(file, name.c_str());
  Handle attr{H5Acreate2(file, name.c_str(), type, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (attr.id < 0 || H5Awrite(attr.id, type, value) < 0)
    throw Error(path + ": cannot write attribute '" + name + "'");
}
Handle open_attr(hid_t file, const std::string& path, const std::string& name) {
  if (H5Aexists(file, name.c_str()) <= 0) throw Error(path + ": attribute '" + name + "' is missing");
  Handle attr{H5Aopen(file, name.c_str(), H5P_DEFAULT), H5Aclose};
  if (attr.id < 0) throw Error(path + ": attribute '" + name + "' cannot be read");
  return attr;
}
}  // namespace

void H5File::set_attr(const std::string& name, std::int64_t value) {
  set_attr_raw(file_, path_, name, H5T_NATIVE_INT64, &value);
}
void H5File::set_attr(const std::string& name, double value) {
  set_attr_raw(file_, path_, name, H5T_NATIVE_DOUBLE, &value);
}
void H5File::set_attr(const std::string& name, const std::string& value) {
  Handle type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, value.size() + 1);
  set_attr_raw(file_, path_, name, type.id, value.c_str());
}
bool H5File::has_attr(const std::string& name) const { return H5Aexists(file_, name.c_str()) > 0; }
std::int64_t H5File::attr_int(const std::string& name) const {
  Handle attr = open_attr(file_, path_, name);
  std::int64_t v = 0;
  if (H5Aread(attr.id, H5T_NATIVE_INT64, &v) < 0) throw Error(path_ + ": attribute '" + name + "' is not an integer");
  return v;
}
double H5File::attr_double(const std::string& name) const {
  Handle attr = open_attr(file_, path_, name);
  double v = 0;
  if (H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) < 0) throw Error(path_ + ": attribute '" + name + "' is not a number");
  return v;
}
std::string H5File::attr_string(const std::string& name) const {
  Handle attr = open_attr(file_, path_, name);
  Handle type{H5Aget_type(attr.id), H5Tclose};
  if (H5Tget_class(type.id) != H5T_STRING) throw Error(path_ + ": attribute '" + name + "' is not a string");
  std::string v(H5Tget_size(type.id), '\0');
  Handle mem{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mem.id, v.size());
  if (H5Aread(attr.id, mem.id, v.data()) < 0) throw Error(path_ + ": attribute '" + name + "' cannot be read");
  v.resize(std::strlen(v.c_str()));
  return v;
}

}  // namespace rk
