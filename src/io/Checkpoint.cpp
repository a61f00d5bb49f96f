// Checkpoint files (io/Checkpoint.hpp).
#include "strand/io/Checkpoint.hpp"

#include <hdf5.h>

#include <cstdio>
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

std::string readStringAttribute(hid_t loc, const char* name) {
  using namespace h5;
  Hid attr(check(H5Aopen(loc, name, H5P_DEFAULT), std::string("no attribute '") + name + "'"), H5Aclose);
  Hid type(check(H5Aget_type(attr.get()), "attribute type"), H5Tclose);
  if (H5Tis_variable_str(type.get()) > 0) {
    char* s = nullptr;
    Hid mem = utf8StringType();
    check(H5Aread(attr.get(), mem.get(), &s), std::string("cannot read attribute '") + name + "'");
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }
  const size_t n = H5Tget_size(type.get());
  std::string out(n, '\0');
  check(H5Aread(attr.get(), type.get(), out.data()), std::string("cannot read attribute '") + name + "'");
  return out.substr(0, out.find('\0'));
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

CheckpointData readCheckpoint(MPI_Comm comm, const std::string& path) {
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
        Hid attr(check(H5Aopen(file.get(), a.c_str(), H5P_DEFAULT), "attribute " + a), H5Aclose);
        double v;
        check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v), "cannot read attribute '" + a + "'");
        names.push_back(a);
        values.push_back(v);
      }
      std::vector<std::string> sets;
      hsize_t li = 0;
      check(H5Literate(file.get(), H5_INDEX_NAME, H5_ITER_INC, &li, collectDataset, &sets), "cannot list datasets");
      for (const std::string& s : sets) {
        Hid dset(check(H5Dopen2(file.get(), s.c_str(), H5P_DEFAULT), "dataset " + s), H5Dclose);
        Hid space(check(H5Dget_space(dset.get()), "dataspace of " + s), H5Sclose);
        const hssize_t n = H5Sget_simple_extent_npoints(space.get());
        std::vector<double> v(static_cast<size_t>(n));
        if (n > 0) check(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "cannot read " + s);
        d.vectors[s] = std::move(v);
      }
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
