// requirement (issue 32 item 1): a checkpoint is input. io::readCheckpoint checks the type and the
// shape of every attribute and dataset before it reads it, and refuses anything else with an
// InputError that names the file and the attribute: an attribute that is an array where one number
// is read (before: H5Aread wrote the whole array into one double, a stack-buffer overflow that
// AddressSanitizer reported in H5Aread and that crashed the run), a string where a number is read,
// a format string that is an array, a dataset that is not 1-D or holds more values than the model.
// The files are made with writeCheckpoint and then damaged with the HDF5 C API.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <petscsys.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "strand/core/Error.hpp"
#include "strand/io/Checkpoint.hpp"

using namespace strand::io;
namespace fs = std::filesystem;

namespace {

int rankOf() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

// A checkpoint path, the same on every rank (the process id of rank 0).
std::string checkpointPath(const std::string& tag) {
  int pid = static_cast<int>(getpid());
  MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  return (fs::temp_directory_path() / ("strand_ckpt_" + tag + "_" + std::to_string(pid) + ".h5")).string();
}

void writeGood(const std::string& path) {
  CheckpointData c;
  c.scene = "scene.yaml";
  c.integrator = "generalized_alpha";
  c.scalars = {{"time", 0.5}, {"step", 500}, {"dt", 1e-3}, {"coordinates", 4}};
  c.vectors["X"] = {1, 2, 3, 4};
  c.vectors["V"] = {0, 0, 0, 0};
  writeCheckpoint(PETSC_COMM_WORLD, path, c);
}

// Runs `edit` on the open file (rank 0 only), between two barriers.
template <class F>
void damage(const std::string& path, F&& edit) {
  if (rankOf() == 0) {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    edit(f);
    H5Fclose(f);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
}

void replaceAttribute(hid_t f, const char* name, hid_t type, std::vector<hsize_t> dims, const void* values) {
  H5Adelete(f, name);
  const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t a = H5Acreate2(f, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, values);
  H5Aclose(a);
  H5Sclose(space);
}

// The message of the InputError readCheckpoint throws ("" if it does not throw).
std::string refusal(const std::string& path, size_t maxValues = 4) {
  try {
    readCheckpoint(PETSC_COMM_WORLD, path, maxValues);
  } catch (const strand::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Checkpoint, ReadsBackWhatItWrote) {
  const std::string path = checkpointPath("good");
  writeGood(path);
  const CheckpointData d = readCheckpoint(PETSC_COMM_WORLD, path, 4);
  EXPECT_EQ(d.integrator, "generalized_alpha");
  EXPECT_EQ(d.scalars.at("step"), 500.0);
  if (rankOf() == 0) {
    EXPECT_EQ(d.vectors.at("X"), (std::vector<double>{1, 2, 3, 4}));
  }
  if (rankOf() == 0) fs::remove(path);
}

TEST(Checkpoint, AnArrayAttributeIsRefusedNotReadIntoOneNumber) {
  const std::string path = checkpointPath("array");
  writeGood(path);
  const std::vector<double> many(4096, 7.0);  // 32 kB into an 8-byte double before the fix
  damage(path, [&](hid_t f) { replaceAttribute(f, "time", H5T_NATIVE_DOUBLE, {many.size()}, many.data()); });
  const std::string why = refusal(path);
  EXPECT_NE(why.find(path + ": -restart: attribute 'time' must be one number (got an array of 4096 numbers)"),
            std::string::npos)
      << why;
  if (rankOf() == 0) fs::remove(path);
}

TEST(Checkpoint, AStringWhereANumberIsReadAndAnArrayOfFormatStringsAreRefused) {
  const std::string path = checkpointPath("string");
  writeGood(path);
  damage(path, [&](hid_t f) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 8);
    replaceAttribute(f, "step", type, {}, "12345678");
    H5Tclose(type);
  });
  std::string why = refusal(path);
  EXPECT_NE(why.find("attribute 'step' must be one number (got one string)"), std::string::npos) << why;
  writeGood(path);
  damage(path, [&](hid_t f) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 32);
    std::vector<char> text(32 * 64, 'x');
    replaceAttribute(f, "format", type, {64}, text.data());
    H5Tclose(type);
  });
  why = refusal(path);
  EXPECT_NE(why.find("attribute 'format' must be one string (got an array of 64 strings)"), std::string::npos) << why;
  if (rankOf() == 0) fs::remove(path);
}

TEST(Checkpoint, DatasetsMustBeOneDimensionalAndNoLargerThanTheModel) {
  const std::string path = checkpointPath("dataset");
  writeGood(path);
  std::string why = refusal(path, 3);
  EXPECT_NE(why.find("/V has 4 values, more than the 3 this model has"), std::string::npos) << why;
  damage(path, [&](hid_t f) {
    H5Ldelete(f, "X", H5P_DEFAULT);
    const hsize_t dims[2] = {2, 2};
    const double v[4] = {1, 2, 3, 4};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t d = H5Dcreate2(f, "X", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(d);
    H5Sclose(space);
  });
  why = refusal(path);
  EXPECT_NE(why.find("/X is not a 1-D dataset"), std::string::npos) << why;
  if (rankOf() == 0) fs::remove(path);
}
