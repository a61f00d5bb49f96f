// HDF5 helpers shared by the output writers (OutputWriter, SweepWriter): RAII identifiers, error
// messages taken from the HDF5 error stack, datasets and attributes. Internal to src/io.
#pragma once
#include <hdf5.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace strand::io::h5 {
// HDF5 prints its error stack to stderr by default; we report errors ourselves. Restores the
// previous handler on scope exit.
class QuietHdf5 {
public:
  QuietHdf5() {
    if (H5Eget_auto2(H5E_DEFAULT, &func_, &data_) < 0) {
      func_ = nullptr;
      data_ = nullptr;
    }
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

inline herr_t innermostError(unsigned n, const H5E_error2_t* err, void* out) {
  if (n == 0 && err && err->desc) *static_cast<std::string*>(out) = err->desc;
  return 0;
}

// The most specific message on the HDF5 error stack; call right after the failing call (any other
// HDF5 API call clears the stack). For failed open(2) calls HDF5 embeds "error message = '...'",
// which is what a user wants to read.
inline std::string hdf5Reason() {
  std::string desc;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermostError, &desc);
  const std::string key = "error message = '";
  auto pos = desc.find(key);
  if (pos != std::string::npos) {
    auto end = desc.find('\'', pos + key.size());
    if (end != std::string::npos) return desc.substr(pos + key.size(), end - pos - key.size());
  }
  return desc.empty() ? std::string("HDF5 error") : desc;
}

// Thrown (on rank 0 only) by check(); the collective wrapper rethrows it on all ranks as
// std::runtime_error with "cannot write output file '<path>': " in front.
struct Hdf5Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline hid_t check(hid_t id, const std::string& what) {
  if (id < 0) throw Hdf5Failure(what + ": " + hdf5Reason());
  return id;
}

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw Hdf5Failure(what + ": " + hdf5Reason());
}

// Owns one HDF5 identifier.
class Hid {
public:
  Hid() = default;
  Hid(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Hid(Hid&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Hid& operator=(Hid&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      close_ = o.close_;
    }
    return *this;
  }
  ~Hid() { reset(); }
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  // Closes and reports failure (used where a failed close loses data: datasets, the file).
  void close(const std::string& what) {
    if (id_ < 0) return;
    hid_t id = std::exchange(id_, H5I_INVALID_HID);
    check(close_(id), what);
  }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = H5I_INVALID_HID;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

inline Hid group(hid_t loc, const std::string& name) {
  return Hid(check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create group '" + name + "'"),
             H5Gclose);
}

inline Hid simpleSpace(std::initializer_list<hsize_t> dims) {
  std::vector<hsize_t> d(dims);
  return Hid(check(H5Screate_simple(static_cast<int>(d.size()), d.data(), nullptr),
                   "cannot create dataspace"),
             H5Sclose);
}

inline Hid scalarSpace() { return Hid(check(H5Screate(H5S_SCALAR), "cannot create dataspace"), H5Sclose); }

inline Hid utf8StringType() {
  Hid type(check(H5Tcopy(H5T_C_S1), "cannot create string type"), H5Tclose);
  check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create string type");
  return type;
}

// Attribute writers replace an existing attribute of the same name.
inline void deleteAttributeIfPresent(hid_t loc, const std::string& name) {
  htri_t exists = H5Aexists(loc, name.c_str());
  check(static_cast<herr_t>(exists < 0 ? -1 : 0), "cannot query attribute '" + name + "'");
  if (exists > 0) check(H5Adelete(loc, name.c_str()), "cannot replace attribute '" + name + "'");
}

inline void writeAttribute(hid_t loc, const std::string& name, hid_t fileType, hid_t memType,
                    const void* value) {
  deleteAttributeIfPresent(loc, name);
  Hid space = scalarSpace();
  Hid attr(check(H5Acreate2(loc, name.c_str(), fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "cannot create attribute '" + name + "'"),
           H5Aclose);
  check(H5Awrite(attr.get(), memType, value), "cannot write attribute '" + name + "'");
  attr.close("cannot close attribute '" + name + "'");
}

inline void writeAttribute(hid_t loc, const std::string& name, double value) {
  writeAttribute(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

inline void writeAttribute(hid_t loc, const std::string& name, int value) {
  writeAttribute(loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value);
}

inline void writeAttribute(hid_t loc, const std::string& name, const std::string& value) {
  Hid type = utf8StringType();
  const char* ptr = value.c_str();
  writeAttribute(loc, name, type.get(), type.get(), &ptr);
}

// Overwrites an existing scalar int attribute in place (no delete/create churn in the object header).
inline herr_t overwriteIntAttribute(hid_t loc, const char* name, int value) {
  hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  if (attr < 0) return -1;
  herr_t status = H5Awrite(attr, H5T_NATIVE_INT, &value);
  if (H5Aclose(attr) < 0) status = -1;
  return status;
}

inline void updateAttribute(hid_t loc, const std::string& name, int value) {
  check(overwriteIntAttribute(loc, name.c_str(), value), "cannot update attribute '" + name + "'");
}


// HDF5 file and memory types of the element types we write.
template <class T> struct H5Types;
template <> struct H5Types<double> {
  static hid_t file() { return H5T_IEEE_F64LE; }
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
};
template <> struct H5Types<int> {
  static hid_t file() { return H5T_STD_I32LE; }
  static hid_t memory() { return H5T_NATIVE_INT; }
};

// An n-dimensional dataset (row-major), written whole.
template <class T>
void writeArray(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const T* data) {
  Hid space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "cannot create dataspace"),
            H5Sclose);
  Hid dset(check(H5Dcreate2(loc, name.c_str(), H5Types<T>::file(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 "cannot create dataset '" + name + "'"),
           H5Dclose);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  if (n > 0)
    check(H5Dwrite(dset.get(), H5Types<T>::memory(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          "cannot write dataset '" + name + "'");
  dset.close("cannot close dataset '" + name + "'");
}

inline void writeMatrix(hid_t loc, const std::string& name, const double* data, hsize_t rows, hsize_t cols) {
  writeArray(loc, name, {rows, cols}, data);
}

}  // namespace strand::io::h5
