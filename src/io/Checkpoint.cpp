// Checkpoint files (io/Checkpoint.hpp).
#include "strand/io/Checkpoint.hpp"

#include <hdf5.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "Hdf5.hpp"
#include "strand/core/Error.hpp"

namespace strand::io {

namespace {

constexpr const char* kFormat = "strand-checkpoint 1";

// Broadcast of a string from rank 0.
void broadcast(MPI_Comm comm, std::string& s) {
  int n = static_cast<int>(s.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  s.resize(n);
  MPI_Bcast(s.data(), n, MPI_CHAR, 0, comm);
}

// Attributes and datasets are checked for type and shape before they are read: a file is input,
// and H5Aread writes as many values as the attribute holds (an array read into one double
// overflowed the stack, issue 32 item 1).
enum class Kind { Number, String };

std::string describeAttribute(hid_t attr) {
  using namespace h5;
  Hid space(check(H5Aget_space(attr), "attribute dataspace"), H5Sclose);
  Hid type(check(H5Aget_type(attr), "attribute type"), H5Tclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  const H5T_class_t cls = H5Tget_class(type.get());
  const std::string what = cls == H5T_STRING ? "string" : cls == H5T_FLOAT || cls == H5T_INTEGER ? "number" : "value";
  if (H5Sget_simple_extent_type(space.get()) == H5S_SCALAR) return "one " + what;
  return "an array of " + std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

// Opens attribute `name` and checks that it holds exactly one value of the given kind.
h5::Hid openAttribute(hid_t loc, const std::string& name, Kind kind) {
  using namespace h5;
  Hid attr(check(H5Aopen(loc, name.c_str(), H5P_DEFAULT), "no attribute '" + name + "'"), H5Aclose);
  Hid space(check(H5Aget_space(attr.get()), "dataspace of attribute '" + name + "'"), H5Sclose);
  Hid type(check(H5Aget_type(attr.get()), "type of attribute '" + name + "'"), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  const bool one = H5Sget_simple_extent_type(space.get()) == H5S_SCALAR;
  const bool fits = kind == Kind::String ? cls == H5T_STRING : cls == H5T_FLOAT || cls == H5T_INTEGER;
  if (!one || !fits)
    throw std::runtime_error("attribute '" + name + "' must be one " + (kind == Kind::String ? "string" : "number") +
                             " (got " + describeAttribute(attr.get()) + ")");
  return attr;
}

constexpr size_t kMaxStringAttribute = 1 << 16;  // a scene path or an integrator signature

std::string readStringAttribute(hid_t loc, const char* name) {
  using namespace h5;
  Hid attr = openAttribute(loc, name, Kind::String);
  Hid type(check(H5Aget_type(attr.get()), "attribute type"), H5Tclose);
  if (H5Tis_variable_str(type.get()) > 0) {
    char* s = nullptr;
    Hid mem = utf8StringType();
    check(H5Aread(attr.get(), mem.get(), &s), std::string("cannot read attribute '") + name + "'");
    std::string out = s ? std::string(s, strnlen(s, kMaxStringAttribute)) : "";
    H5free_memory(s);
    return out;
  }
  const size_t n = H5Tget_size(type.get());
  if (n == 0 || n > kMaxStringAttribute)
    throw std::runtime_error(std::string("attribute '") + name + "' is a string of " + std::to_string(n) + " bytes");
  std::string out(n, '\0');
  check(H5Aread(attr.get(), type.get(), out.data()), std::string("cannot read attribute '") + name + "'");
  return out.substr(0, out.find('\0'));
}

double readNumberAttribute(hid_t loc, const std::string& name) {
  using namespace h5;
  Hid attr = openAttribute(loc, name, Kind::Number);
  double v = 0.0;
  check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v), "cannot read attribute '" + name + "'");
  return v;
}

// A 1-D dataset of numbers with at most maxValues entries, read as doubles.
std::vector<double> readVector(hid_t file, const std::string& name, size_t maxValues) {
  using namespace h5;
  H5O_info_t info;
  check(H5Oget_info_by_name(file, name.c_str(), &info, H5P_DEFAULT), "object /" + name);
  if (info.type != H5O_TYPE_DATASET) throw std::runtime_error("/" + name + " is not a dataset");
  Hid dset(check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "dataset " + name), H5Dclose);
  Hid space(check(H5Dget_space(dset.get()), "dataspace of " + name), H5Sclose);
  Hid type(check(H5Dget_type(dset.get()), "type of " + name), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw std::runtime_error("/" + name + " does not hold numbers");
  if (H5Sget_simple_extent_ndims(space.get()) != 1) throw std::runtime_error("/" + name + " is not a 1-D dataset");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0 || static_cast<size_t>(n) > maxValues)
    throw std::runtime_error("/" + name + " has " + std::to_string(n) + " values, more than the " +
                             std::to_string(maxValues) + " this model has");
  std::vector<double> v(static_cast<size_t>(n));
  if (n > 0) check(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "cannot read " + name);
  return v;
}

herr_t collectName(hid_t, const char* name, const H5A_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

herr_t collectDataset(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

}  // namespace

void writeCheckpoint(MPI_Comm comm, const std::string& path, const CheckpointData& data) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0) {
    try {
      using namespace h5;
      const std::string tmp = path + ".tmp";
      {
        Hid file(check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "cannot create '" + tmp + "'"),
                 H5Fclose);
        writeAttribute(file.get(), "format", std::string(kFormat));
        writeAttribute(file.get(), "scene", data.scene);
        writeAttribute(file.get(), "integrator", data.integrator);
        for (const auto& [name, value] : data.scalars) writeAttribute(file.get(), name, value);
        for (const auto& [name, v] : data.vectors)
          writeArray(file.get(), name, {static_cast<hsize_t>(v.size())}, v.data());
        file.close("cannot close '" + tmp + "'");
      }
      std::filesystem::rename(tmp, path);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  broadcast(comm, error);
  if (!error.empty()) throw std::runtime_error("checkpoint '" + path + "': " + error);
}

CheckpointData readCheckpoint(MPI_Comm comm, const std::string& path, size_t maxValues) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  CheckpointData d;
  std::string error;
  std::vector<std::string> names;
  std::vector<double> values;
  if (rank == 0) {
    try {
      using namespace h5;
      if (!std::filesystem::exists(path)) throw std::runtime_error("no such file");
      Hid file(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "not an HDF5 file"), H5Fclose);
      if (H5Aexists(file.get(), "format") <= 0 || readStringAttribute(file.get(), "format") != kFormat)
        throw std::runtime_error(std::string("not a Strand checkpoint (attribute format != '") + kFormat + "')");
      d.scene = readStringAttribute(file.get(), "scene");
      d.integrator = readStringAttribute(file.get(), "integrator");
      std::vector<std::string> attrs;
      hsize_t idx = 0;
      check(H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collectName, &attrs), "cannot list attributes");
      for (const std::string& a : attrs) {
        if (a == "format" || a == "scene" || a == "integrator") continue;
        names.push_back(a);
        values.push_back(readNumberAttribute(file.get(), a));
      }
      std::vector<std::string> sets;
      hsize_t li = 0;
      check(H5Literate(file.get(), H5_INDEX_NAME, H5_ITER_INC, &li, collectDataset, &sets), "cannot list datasets");
      for (const std::string& s : sets) d.vectors[s] = readVector(file.get(), s, maxValues);
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "unreadable";
    }
  }
  broadcast(comm, error);
  if (!error.empty()) throw InputError(path + ": -restart: " + error);
  broadcast(comm, d.scene);
  broadcast(comm, d.integrator);
  int n = static_cast<int>(names.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  names.resize(n);
  values.resize(n);
  for (std::string& s : names) broadcast(comm, s);
  MPI_Bcast(values.data(), n, MPI_DOUBLE, 0, comm);
  for (int i = 0; i < n; ++i) d.scalars[names[i]] = values[i];
  return d;
}

}  // namespace strand::io
