// requirement: the output writer produces the HDF5 layout of include/strand/io/OutputWriter.hpp
// (root attributes, /bodies, one dataset per frame and body, /series, /modes), an XDMF 3 file that
// references those datasets by the .h5 basename, a file that is readable with every frame up to the
// last commit while the run is still going (frames and series buffered and committed in blocks,
// atomic .xdmf2 rewrite per commit; issue 36 item 6), and InputError on all ranks when the file cannot
// be created. Files are checked by reopening them with the HDF5 C API.
#include <gtest/gtest.h>

#include <type_traits>
#include <hdf5.h>
#include <petscsys.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "strand/core/Error.hpp"
#include "strand/io/OutputWriter.hpp"

using namespace strand::io;
namespace fs = std::filesystem;

namespace {

int rankOf(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

// A fresh directory, the same path on every rank (created by rank 0).
std::string freshDir(const std::string& tag) {
  std::string dir;
  if (rankOf(PETSC_COMM_WORLD) == 0) {
    dir = (fs::temp_directory_path() / ("strand_output_" + tag + "_" + std::to_string(getpid()))).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  int n = static_cast<int>(dir.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  dir.resize(n);
  MPI_Bcast(dir.data(), n, MPI_CHAR, 0, PETSC_COMM_WORLD);
  return dir;
}

std::vector<BodyLayout> twoBodies() {
  return {{"main", "AncfCable3d", 2, 3, 6, 5}, {"stay", "AncfCable2d", 1, 2, 4, 3}};
}

RunInfo runInfo() { return {"scenes/test.yaml", "static", "0.1.0-test", 3}; }

// Distinct, recognisable values: frame f, body b, entry i.
double value(int f, int b, int i, int which) { return 1000.0 * f + 100.0 * b + i + 0.25 * which; }

std::vector<BodyFrame> makeFrames(const std::vector<BodyLayout>& bodies, int f) {
  std::vector<BodyFrame> out;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    BodyFrame bf;
    for (int i = 0; i < bodies[b].pointsPerBody * 3; ++i) bf.centerline.push_back(value(f, b, i, 0));
    for (int i = 0; i < bodies[b].nodes * bodies[b].coordsPerNode; ++i)
      bf.coordinates.push_back(value(f, b, i, 1));
    out.push_back(std::move(bf));
  }
  return out;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int countOf(const std::string& text, const std::string& needle) {
  int n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1)) ++n;
  return n;
}

// Tags balance, every tag closes: enough to catch broken XML generation.
bool tagsBalanced(const std::string& xml) {
  std::vector<std::string> stack;
  std::size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    const std::size_t end = xml.find('>', pos);
    if (end == std::string::npos) return false;
    std::string tag = xml.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.empty()) return false;
    if (tag[0] == '?' || tag[0] == '!') continue;
    const bool closing = tag[0] == '/';
    const bool selfClosing = tag.back() == '/';
    std::string name = tag.substr(closing ? 1 : 0);
    name = name.substr(0, name.find_first_of(" \t\n/"));
    if (closing) {
      if (stack.empty() || stack.back() != name) return false;
      stack.pop_back();
    } else if (!selfClosing) {
      stack.push_back(name);
    }
  }
  return stack.empty();
}

// --- small HDF5 readers (rank 0) ---

std::vector<hsize_t> dimsOf(hid_t file, const std::string& path) {
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << path;
  if (d < 0) return {};
  hid_t s = H5Dget_space(d);
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(s));
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  H5Sclose(s);
  H5Dclose(d);
  return dims;
}

// Whole dataset as a flat vector of T (H5T_NATIVE_DOUBLE for double, H5T_NATIVE_INT for int).
template <class T>
std::vector<T> readArray(hid_t file, const std::string& path) {
  std::vector<T> out;
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << path;
  if (d < 0) return out;
  hid_t s = H5Dget_space(d);
  out.resize(H5Sget_simple_extent_npoints(s));
  H5Sclose(s);
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  EXPECT_GE(H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << path;
  H5Dclose(d);
  return out;
}
std::vector<double> readDoubles(hid_t file, const std::string& path) { return readArray<double>(file, path); }
std::vector<int> readInts(hid_t file, const std::string& path) { return readArray<int>(file, path); }

template <class T>
T readAttr(hid_t file, const std::string& object, const std::string& name, hid_t memType) {
  T v{};
  hid_t a = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << object << " @" << name;
  if (a < 0) return v;
  EXPECT_GE(H5Aread(a, memType, &v), 0);
  H5Aclose(a);
  return v;
}

double attrDouble(hid_t f, const std::string& o, const std::string& n) {
  return readAttr<double>(f, o, n, H5T_NATIVE_DOUBLE);
}
int attrInt(hid_t f, const std::string& o, const std::string& n) {
  return readAttr<int>(f, o, n, H5T_NATIVE_INT);
}
std::string attrString(hid_t f, const std::string& o, const std::string& n) {
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  char* raw = readAttr<char*>(f, o, n, type);
  H5Tclose(type);
  std::string s = raw ? raw : "<null>";
  if (raw) H5free_memory(raw);
  return s;
}

bool exists(hid_t file, const std::string& path) { return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0; }

// Row k of a frame dataset (frames x ...): the values of frame k.
std::vector<double> readRow(hid_t file, const std::string& path, int k) {
  const std::vector<hsize_t> dims = dimsOf(file, path);
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = static_cast<hsize_t>(k);
  count[0] = 1;
  std::size_t n = 1;
  for (std::size_t i = 1; i < dims.size(); ++i) n *= dims[i];
  std::vector<double> out(n);
  hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  hid_t fs = H5Dget_space(d);
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  hid_t ms = H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, out.data()), 0) << path << " row " << k;
  H5Sclose(ms);
  H5Sclose(fs);
  H5Dclose(d);
  return out;
}

// The frames in the file: rows of /frames/time, which every frame dataset must have too.
int frameRows(hid_t file) { return static_cast<int>(dimsOf(file, "/frames/time")[0]); }

void expectFrame(hid_t file, const std::vector<BodyLayout>& bodies, int f, double time) {
  EXPECT_DOUBLE_EQ(readRow(file, "/frames/time", f)[0], time);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyLayout& L = bodies[b];
    const std::string c = "/frames/" + L.name + "/centerline", q = "/frames/" + L.name + "/coordinates";
    EXPECT_EQ(dimsOf(file, c), (std::vector<hsize_t>{hsize_t(frameRows(file)), hsize_t(L.pointsPerBody), 3}));
    EXPECT_EQ(dimsOf(file, q), (std::vector<hsize_t>{hsize_t(frameRows(file)), hsize_t(L.nodes), hsize_t(L.coordsPerNode)}));
    std::vector<double> cv = readRow(file, c, f), qv = readRow(file, q, f);
    for (std::size_t i = 0; i < cv.size(); ++i) EXPECT_EQ(cv[i], value(f, b, i, 0)) << c << "[" << f << "][" << i << "]";
    for (std::size_t i = 0; i < qv.size(); ++i) EXPECT_EQ(qv[i], value(f, b, i, 1)) << q << "[" << f << "][" << i << "]";
  }
}

}  // namespace

TEST(OutputWriter, WritesFramesSeriesModesAndXdmf) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("full");
  const std::string path = dir + "/run.h5";
  const auto bodies = twoBodies();
  const double times[3] = {0.0, 0.5, 1.0};
  {
    OutputWriter w(comm, path, runInfo(), bodies);
    EXPECT_EQ(w.path(), path);
    EXPECT_EQ(w.xdmfPath(), dir + "/run.xdmf2");
    EXPECT_EQ(w.modesXdmfPath(), dir + "/run_modes.xmf");
    for (int f = 0; f < 3; ++f) {
      w.writeFrame(times[f], makeFrames(bodies, f));
      w.writeScalarSeries("load_factor", times[f]);
      w.writeScalarSeries("newton_iterations", 3.0 + f);
    }
    for (int k = 0; k < 700; ++k) w.writeScalarSeries("residual_norm", 1.0 / (k + 1));  // > one chunk
    EXPECT_EQ(w.framesWritten(), 3);
    w.writeModes({1.5, 4.25}, {makeFrames(bodies, 10), makeFrames(bodies, 11)});
    w.setAttribute("converged", "no");
    w.setAttribute("converged", "yes");  // replaces
    w.setAttribute("wall_time_s", 12.5);
    w.close();
    w.close();  // idempotent
  }
  if (rankOf(comm) != 0) return;

  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_EQ(attrString(file, "/", "strand_version"), "0.1.0-test");
  EXPECT_EQ(attrString(file, "/", "scene_file"), "scenes/test.yaml");
  EXPECT_EQ(attrString(file, "/", "analysis"), "static");
  EXPECT_EQ(attrInt(file, "/", "dimension"), 3);
  EXPECT_EQ(attrString(file, "/", "converged"), "yes");
  EXPECT_EQ(attrDouble(file, "/", "wall_time_s"), 12.5);

  // bodies
  EXPECT_EQ(attrString(file, "/bodies/main", "element_type"), "AncfCable3d");
  EXPECT_EQ(attrInt(file, "/bodies/main", "elements"), 2);
  EXPECT_EQ(attrInt(file, "/bodies/main", "nodes"), 3);
  EXPECT_EQ(attrInt(file, "/bodies/main", "coords_per_node"), 6);
  EXPECT_EQ(attrString(file, "/bodies/stay", "element_type"), "AncfCable2d");
  EXPECT_EQ(attrInt(file, "/bodies/stay", "coords_per_node"), 4);
  EXPECT_EQ(dimsOf(file, "/bodies/main/connectivity"), (std::vector<hsize_t>{4, 2}));
  EXPECT_EQ(readInts(file, "/bodies/main/connectivity"), (std::vector<int>{0, 1, 1, 2, 2, 3, 3, 4}));
  EXPECT_EQ(readInts(file, "/bodies/stay/connectivity"), (std::vector<int>{0, 1, 1, 2}));

  // frames
  EXPECT_EQ(attrInt(file, "/frames", "count"), 3);
  EXPECT_EQ(frameRows(file), 3);
  for (int f = 0; f < 3; ++f) expectFrame(file, bodies, f, times[f]);

  // series: 1-D, chunked, unlimited
  EXPECT_EQ(readDoubles(file, "/series/load_factor"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(readDoubles(file, "/series/newton_iterations"), (std::vector<double>{3, 4, 5}));
  const std::vector<double> res = readDoubles(file, "/series/residual_norm");
  ASSERT_EQ(res.size(), 700u);
  EXPECT_EQ(res[0], 1.0);
  EXPECT_EQ(res[699], 1.0 / 700);
  {
    hid_t d = H5Dopen2(file, "/series/residual_norm", H5P_DEFAULT);
    hid_t s = H5Dget_space(d);
    hsize_t dims[1], maxDims[1];
    EXPECT_EQ(H5Sget_simple_extent_ndims(s), 1);
    H5Sget_simple_extent_dims(s, dims, maxDims);
    EXPECT_EQ(maxDims[0], H5S_UNLIMITED);
    hid_t p = H5Dget_create_plist(d);
    EXPECT_EQ(H5Pget_layout(p), H5D_CHUNKED);
    H5Pclose(p);
    H5Sclose(s);
    H5Dclose(d);
  }

  // modes
  EXPECT_EQ(readDoubles(file, "/modes/frequencies_hz"), (std::vector<double>{1.5, 4.25}));
  EXPECT_EQ(readDoubles(file, "/modes/00001/stay/centerline"),
            makeFrames(bodies, 11)[1].centerline);
  EXPECT_EQ(readDoubles(file, "/modes/00000/main/coordinates"), makeFrames(bodies, 10)[0].coordinates);
  EXPECT_EQ(attrDouble(file, "/modes/00001", "frequency_hz"), 4.25);
  EXPECT_GE(H5Fclose(file), 0);

  // XDMF: temporal collection of spatial collections, relative references, well formed
  const std::string xmf = readText(dir + "/run.xdmf2");
  EXPECT_TRUE(tagsBalanced(xmf));
  EXPECT_NE(xmf.find("Version=\"3.0\""), std::string::npos);
  EXPECT_NE(xmf.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(countOf(xmf, "CollectionType=\"Spatial\""), 3);
  EXPECT_EQ(countOf(xmf, "<Time Value="), 3);
  EXPECT_NE(xmf.find("<Time Value=\"0.5\"/>"), std::string::npos);
  EXPECT_EQ(countOf(xmf, "TopologyType=\"Polyline\" NodesPerElement=\"2\""), 6);
  EXPECT_EQ(countOf(xmf, "GeometryType=\"XYZ\""), 6);
  EXPECT_NE(xmf.find(">run.h5:/bodies/main/connectivity<"), std::string::npos);
  // frame k: row k of /frames/<body>/centerline, an XDMF HyperSlab of a dataset declared with k + 1 rows
  EXPECT_NE(xmf.find("<DataItem Dimensions=\"3 3\" Format=\"XML\">2 0 0 1 1 1 1 5 3</DataItem>\n"
                     "              <DataItem Dimensions=\"3 5 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                     "run.h5:/frames/main/centerline</DataItem>"),
            std::string::npos);
  EXPECT_NE(xmf.find(">0 0 0 1 1 1 1 3 3</DataItem>\n              <DataItem Dimensions=\"1 3 3\" NumberType=\"Float\" "
                     "Precision=\"8\" Format=\"HDF\">run.h5:/frames/stay/centerline<"),
            std::string::npos);
  EXPECT_EQ(countOf(xmf, "ItemType=\"HyperSlab\""), 6);
  EXPECT_NE(xmf.find("Dimensions=\"5 3\""), std::string::npos);
  EXPECT_NE(xmf.find("Dimensions=\"4 2\""), std::string::npos);
  EXPECT_EQ(xmf.find(dir), std::string::npos) << "references must be relative";
  EXPECT_FALSE(fs::exists(dir + "/run.xdmf2.tmp"));

  const std::string modes = readText(dir + "/run_modes.xmf");
  EXPECT_TRUE(tagsBalanced(modes));
  EXPECT_EQ(countOf(modes, "CollectionType=\"Spatial\""), 2);
  EXPECT_NE(modes.find(">run.h5:/modes/00001/stay/centerline<"), std::string::npos);
  EXPECT_NE(modes.find("Value=\"4.25\""), std::string::npos);
  fs::remove_all(dir);
}

// A run killed after frame 1 leaves a consistent pair: snapshot the files while the writer is open
// (what is on disk at that instant is what a SIGKILL would leave) and read the snapshot. With a
// commit interval of 0, every write commits (the writer of issue 32).
TEST(OutputWriter, FileIsReadableAfterEachFrame) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("crash");
  const std::string path = dir + "/live.h5";
  const auto bodies = twoBodies();
  OutputWriter w(comm, path, runInfo(), bodies);
  w.setCommitPolicy({0.0, std::size_t(4) << 20});
  if (rankOf(comm) == 0) {
    const std::string empty = readText(dir + "/live.xdmf2");
    EXPECT_TRUE(tagsBalanced(empty));
    EXPECT_EQ(countOf(empty, "<Grid "), 1);  // the (empty) temporal collection
  }
  w.writeFrame(0.1, makeFrames(bodies, 0));
  w.writeScalarSeries("residual_norm", 1e-3);
  w.writeFrame(0.2, makeFrames(bodies, 1));
  if (rankOf(comm) == 0) {
    fs::copy_file(path, dir + "/snapshot.h5");
    const std::string xmf = readText(dir + "/live.xdmf2");
    EXPECT_TRUE(tagsBalanced(xmf));
    EXPECT_EQ(countOf(xmf, "CollectionType=\"Spatial\""), 2);
    EXPECT_NE(xmf.find(">1 0 0 1 1 1 1 3 3<"), std::string::npos);
    EXPECT_NE(xmf.find("live.h5:/frames/stay/centerline"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir + "/live.xdmf2.tmp"));

    hid_t file = H5Fopen((dir + "/snapshot.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 2);
    expectFrame(file, bodies, 0, 0.1);
    expectFrame(file, bodies, 1, 0.2);
    EXPECT_EQ(readDoubles(file, "/series/residual_norm"), (std::vector<double>{1e-3}));
    H5Fclose(file);
  }
  w.close();
  if (rankOf(comm) == 0) fs::remove_all(dir);
}

TEST(OutputWriter, MissingDirectoryThrowsInputErrorOnAllRanks) {
  const std::string path = "/nonexistent_strand_dir/sub/run.h5";
  try {
    OutputWriter w(PETSC_COMM_WORLD, path, runInfo(), twoBodies());
    FAIL() << "no exception";
  } catch (const strand::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cannot create output file '" + path + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
}

TEST(OutputWriter, RejectsBadNamesAndSizes) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("bad");
  auto bodies = twoBodies();
  bodies[1].name = "a/b";
  EXPECT_THROW(OutputWriter(comm, dir + "/a.h5", runInfo(), bodies), strand::InputError);
  bodies[1].name = "main";
  EXPECT_THROW(OutputWriter(comm, dir + "/b.h5", runInfo(), bodies), strand::InputError);

  bodies = twoBodies();
  OutputWriter w(comm, dir + "/c.h5", runInfo(), bodies);
  auto frames = makeFrames(bodies, 0);
  frames[1].coordinates.pop_back();
  EXPECT_THROW(w.writeFrame(0.0, frames), std::invalid_argument);
  EXPECT_THROW(w.writeFrame(0.0, {}), std::invalid_argument);
  EXPECT_EQ(w.framesWritten(), 0);
  w.writeFrame(0.0, makeFrames(bodies, 0));  // still usable, and this is frame 00000
  EXPECT_EQ(w.framesWritten(), 1);
  EXPECT_THROW(w.writeScalarSeries("a:b", 1.0), strand::InputError);
  EXPECT_THROW(w.writeModes({1.0}, {}), std::invalid_argument);
  w.close();
  EXPECT_THROW(w.writeFrame(1.0, makeFrames(bodies, 1)), std::logic_error);
  EXPECT_THROW(w.setAttribute("x", 1.0), std::logic_error);
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen((dir + "/c.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 1);
    expectFrame(file, bodies, 0, 0.0);
    H5Fclose(file);
    fs::remove_all(dir);
  }
}

// A write failure (here: the .xdmf2 cannot be rewritten) throws std::runtime_error on all ranks and
// rolls the frame back, so the file and the .xdmf2 stay consistent and the next frame takes its index.
TEST(OutputWriter, WriteFailureRollsBackTheFrame) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("fail");
  const auto bodies = twoBodies();
  OutputWriter w(comm, dir + "/e.h5", runInfo(), bodies);
  if (rankOf(comm) == 0) fs::create_directory(dir + "/e.xdmf2.tmp");  // blocks the atomic rewrite
  try {
    w.writeFrame(1.0, makeFrames(bodies, 5));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write output file '" + dir + "/e.h5'"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(w.framesWritten(), 0);
  if (rankOf(comm) == 0) fs::remove(dir + "/e.xdmf2.tmp");
  w.writeFrame(2.0, makeFrames(bodies, 0));
  w.close();
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen((dir + "/e.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 1);
    expectFrame(file, bodies, 0, 2.0);
    EXPECT_EQ(frameRows(file), 1);
    H5Fclose(file);
    EXPECT_EQ(countOf(readText(dir + "/e.xdmf2"), "CollectionType=\"Spatial\""), 1);
    fs::remove_all(dir);
  }
}

// The destructor closes a writer that was never closed (e.g. unwinding after a SolveError).
TEST(OutputWriter, DestructorCloses) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("dtor");
  const auto bodies = twoBodies();
  {
    OutputWriter w(comm, dir + "/d.h5", runInfo(), bodies);
    w.writeFrame(2.0, makeFrames(bodies, 0));
    w.writeScalarSeries("load_factor", 2.0);
  }
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen((dir + "/d.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    expectFrame(file, bodies, 0, 2.0);
    EXPECT_EQ(readDoubles(file, "/series/load_factor"), (std::vector<double>{2.0}));
    H5Fclose(file);
    fs::remove_all(dir);
  }
}

namespace {

// A policy that never commits by itself: only the first frame, flush() and close() do.
OutputWriter::CommitPolicy never() { return {1e9, std::size_t(1) << 40}; }

// A copy of `path` as it is on disk now: what a kill -9 at this instant would leave (rank 0).
std::string snapshot(const std::string& path, const std::string& name) {
  const std::string copy = fs::path(path).parent_path() / name;
  fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
  return copy;
}

std::string workPath(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".strand-work")).string();
}

}  // namespace

// Issue 36 item 6: frames, scalar and vector series written in blocks read back identical; until a
// commit, the file on disk (what a kill leaves) keeps the previous commit: the first frame alone,
// with its .xdmf2 naming that one frame; after close() everything is there.
TEST(OutputWriter, FramesWrittenInBlocksReadBackIdentical) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("blocks");
  const std::string path = dir + "/b.h5";
  const auto bodies = twoBodies();
  const int n = 40;
  {
    OutputWriter w(comm, path, runInfo(), bodies);
    w.setCommitPolicy(never());
    EXPECT_EQ(w.commitPolicy().intervalSeconds, 1e9);
    for (int f = 0; f < n; ++f) {
      w.writeFrame(0.1 * f, makeFrames(bodies, f));
      w.writeScalarSeries("time", 0.1 * f);
      w.writeVectorSeries("tip", {1.0 * f, 2.0 * f, 3.0 * f});
    }
    EXPECT_EQ(w.framesWritten(), n);
    w.setAttribute("note", "blocks");
    if (rankOf(comm) == 0) {
      const std::string copy = snapshot(path, "early.h5");
      EXPECT_EQ(countOf(readText(dir + "/b.xdmf2"), "CollectionType=\"Spatial\""), 1);
      hid_t file = H5Fopen(copy.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      ASSERT_GE(file, 0);
      EXPECT_EQ(attrInt(file, "/frames", "count"), 1);  // the first frame is committed at once
      expectFrame(file, bodies, 0, 0.0);
      EXPECT_EQ(frameRows(file), 1);
      EXPECT_FALSE(exists(file, "/series/time"));
      EXPECT_LE(H5Aexists(file, "note"), 0);
      H5Fclose(file);
    }
    w.close();
  }
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), n);
    for (int f = 0; f < n; ++f) expectFrame(file, bodies, f, 0.1 * f);
    std::vector<double> times, tip;
    for (int f = 0; f < n; ++f) {
      times.push_back(0.1 * f);
      tip.insert(tip.end(), {1.0 * f, 2.0 * f, 3.0 * f});
    }
    EXPECT_EQ(readDoubles(file, "/series/time"), times);
    EXPECT_EQ(dimsOf(file, "/series/tip"), (std::vector<hsize_t>{hsize_t(n), 3}));
    EXPECT_EQ(readDoubles(file, "/series/tip"), tip);
    EXPECT_EQ(attrString(file, "/", "note"), "blocks");
    H5Fclose(file);
    const std::string xmf = readText(dir + "/b.xdmf2");
    EXPECT_TRUE(tagsBalanced(xmf));
    EXPECT_EQ(countOf(xmf, "CollectionType=\"Spatial\""), n);
    EXPECT_NE(xmf.find(">39 0 0 1 1 1 1 3 3</DataItem>\n              <DataItem Dimensions=\"40 3 3\""), std::string::npos);
    EXPECT_FALSE(fs::exists(workPath(path)));
    fs::remove_all(dir);
  }
}

// Commits by size and by flush(): blocks appended to the same datasets, several commits per file.
TEST(OutputWriter, CommitsWhenTheBufferFillsAndOnFlush) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("size");
  const std::string path = dir + "/s.h5";
  const auto bodies = twoBodies();
  OutputWriter w(comm, path, runInfo(), bodies);
  // a frame of twoBodies() is 15 + 18 + 9 + 8 = 50 doubles, 400 bytes: a commit every third frame
  w.setCommitPolicy({1e9, 1000});
  for (int f = 0; f < 7; ++f) w.writeFrame(1.0 * f, makeFrames(bodies, f));
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen(snapshot(path, "seven.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 7);  // 1, then 2 blocks of 3
    for (int f = 0; f < 7; ++f) expectFrame(file, bodies, f, 1.0 * f);
    H5Fclose(file);
  }
  w.writeFrame(7.0, makeFrames(bodies, 7));
  for (int k = 0; k < 5; ++k) w.writeScalarSeries("x", k);
  w.flush();
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen(snapshot(path, "flushed.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 8);
    expectFrame(file, bodies, 7, 7.0);
    EXPECT_EQ(readDoubles(file, "/series/x"), (std::vector<double>{0, 1, 2, 3, 4}));
    H5Fclose(file);
    EXPECT_EQ(countOf(readText(dir + "/s.xdmf2"), "CollectionType=\"Spatial\""), 8);
  }
  for (int k = 5; k < 8; ++k) w.writeScalarSeries("x", k);
  w.close();
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(readDoubles(file, "/series/x"), (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7}));
    H5Fclose(file);
    fs::remove_all(dir);
  }
}

// A crash (here: the writer is never closed nor destroyed, as after a kill -9) leaves the file of
// the last commit: readable, every frame and series value committed then, an .xdmf2 naming just
// those frames; what was buffered since is lost.
TEST(OutputWriter, AWriterNeverClosedLeavesTheLastCommit) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("leak");
  const std::string path = dir + "/k.h5";
  const auto bodies = twoBodies();
  auto* w = new OutputWriter(comm, path, runInfo(), bodies);
  w->setCommitPolicy(never());
  for (int f = 0; f < 10; ++f) {
    w->writeFrame(0.5 * f, makeFrames(bodies, f));
    w->writeScalarSeries("energy", 10.0 * f);
  }
  w->flush();
  for (int f = 10; f < 25; ++f) {
    w->writeFrame(0.5 * f, makeFrames(bodies, f));
    w->writeScalarSeries("energy", 10.0 * f);
  }
  EXPECT_EQ(w->framesWritten(), 25);
  // `w` is leaked on purpose: no destructor, no close (HDF5 closes the work file at exit)
  if (rankOf(comm) == 0) {
    const std::string xmf = readText(dir + "/k.xdmf2");
    EXPECT_TRUE(tagsBalanced(xmf));
    EXPECT_EQ(countOf(xmf, "CollectionType=\"Spatial\""), 10);
    hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 10);
    for (int f = 0; f < 10; ++f) expectFrame(file, bodies, f, 0.5 * f);
    EXPECT_EQ(frameRows(file), 10);
    std::vector<double> e;
    for (int f = 0; f < 10; ++f) e.push_back(10.0 * f);
    EXPECT_EQ(readDoubles(file, "/series/energy"), e);
    H5Fclose(file);
    fs::remove_all(dir);  // the leaked writer's work file goes too (HDF5 closes it at exit)
  }
}

// A block whose commit fails is taken back whole: framesWritten() returns to the last commit on
// all ranks, the file and the .xdmf2 keep that commit, and the next frame takes the first lost index.
TEST(OutputWriter, AFailedBlockIsTakenBack) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("failblock");
  const std::string path = dir + "/f.h5";
  const auto bodies = twoBodies();
  OutputWriter w(comm, path, runInfo(), bodies);
  w.setCommitPolicy(never());
  w.writeFrame(0.0, makeFrames(bodies, 0));  // committed at once
  w.writeScalarSeries("x", 0.0);
  w.flush();
  for (int f = 1; f < 4; ++f) {
    w.writeFrame(1.0 * f, makeFrames(bodies, 9));
    w.writeScalarSeries("x", 99.0);
  }
  EXPECT_EQ(w.framesWritten(), 4);
  if (rankOf(comm) == 0) fs::create_directory(dir + "/f.xdmf2.tmp");  // blocks the .xdmf2 rewrite
  EXPECT_THROW(w.flush(), std::runtime_error);
  EXPECT_EQ(w.framesWritten(), 1);
  if (rankOf(comm) == 0) fs::remove(dir + "/f.xdmf2.tmp");
  w.writeFrame(1.0, makeFrames(bodies, 1));
  w.writeScalarSeries("x", 1.0);
  w.close();
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(attrInt(file, "/frames", "count"), 2);
    expectFrame(file, bodies, 0, 0.0);
    expectFrame(file, bodies, 1, 1.0);
    EXPECT_EQ(frameRows(file), 2);
    EXPECT_EQ(readDoubles(file, "/series/x"), (std::vector<double>{0.0, 1.0}));
    H5Fclose(file);
    EXPECT_EQ(countOf(readText(dir + "/f.xdmf2"), "CollectionType=\"Spatial\""), 2);
    fs::remove_all(dir);
  }
}

TEST(OutputWriter, VectorSeriesKeepTheirWidth) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("vector");
  OutputWriter w(comm, dir + "/v.h5", runInfo(), twoBodies());
  w.writeVectorSeries("p", {1.0, 2.0});
  EXPECT_THROW(w.writeVectorSeries("p", {1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(w.writeScalarSeries("p", 1.0), std::invalid_argument);
  EXPECT_THROW(w.writeVectorSeries("q", {}), std::invalid_argument);
  w.writeScalarSeries("s", 1.0);
  EXPECT_THROW(w.writeVectorSeries("s", {1.0}), std::invalid_argument);
  EXPECT_THROW(w.writeVectorSeries("a/b", {1.0}), strand::InputError);
  EXPECT_THROW(w.setCommitPolicy({-1.0, 10}), std::invalid_argument);
  w.writeVectorSeries("p", {3.0, 4.0});
  w.close();
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen((dir + "/v.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(dimsOf(file, "/series/p"), (std::vector<hsize_t>{2, 2}));
    EXPECT_EQ(readDoubles(file, "/series/p"), (std::vector<double>{1, 2, 3, 4}));
    EXPECT_EQ(readDoubles(file, "/series/s"), (std::vector<double>{1.0}));
    H5Fclose(file);
    fs::remove_all(dir);
  }
}

// Cell fields (BodyLayout::cellFields): one value per centerline segment, written as
// /frames/<body>/<field> (a row per frame) and named in the .xdmf2 as a cell attribute of the body's polyline;
// mode shapes carry none; a wrong count or size, or a name that clashes, is refused.
TEST(OutputWriter, CellFieldsAreWrittenPerSegmentAndNamedInTheXdmf) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const std::string dir = freshDir("cells");
  auto bodies = twoBodies();
  bodies[0].cellFields = {"axial_force", "contact_state"};
  auto withFields = [&](int f) {
    auto frames = makeFrames(bodies, f);
    for (std::size_t k = 0; k < bodies[0].cellFields.size(); ++k) {
      std::vector<double> v;
      for (int i = 0; i < bodies[0].pointsPerBody - 1; ++i) v.push_back(value(f, 0, i, 2 + static_cast<int>(k)));
      frames[0].cellFields.push_back(v);
    }
    return frames;
  };
  {
    OutputWriter w(comm, dir + "/f.h5", runInfo(), bodies);
    EXPECT_THROW(w.writeFrame(0.0, makeFrames(bodies, 0)), std::invalid_argument);  // fields missing
    auto wrong = withFields(0);
    wrong[0].cellFields[1].pop_back();
    EXPECT_THROW(w.writeFrame(0.0, wrong), std::invalid_argument);
    w.writeFrame(0.0, withFields(0));
    w.writeFrame(0.5, withFields(1));
    EXPECT_THROW(w.writeModes({1.0}, {withFields(2)}), std::invalid_argument);  // shapes carry none
    w.writeModes({1.0}, {makeFrames(bodies, 2)});
    w.close();
  }
  auto clash = twoBodies();
  clash[1].cellFields = {"centerline"};
  EXPECT_THROW(OutputWriter(comm, dir + "/g.h5", runInfo(), clash), std::invalid_argument);
  if (rankOf(comm) == 0) {
    hid_t file = H5Fopen((dir + "/f.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    EXPECT_EQ(readRow(file, "/frames/main/contact_state", 1), withFields(1)[0].cellFields[1]);
    EXPECT_EQ(readRow(file, "/frames/main/axial_force", 0), withFields(0)[0].cellFields[0]);
    H5Fclose(file);
    const std::string xmf = readText(dir + "/f.xdmf2");
    EXPECT_NE(xmf.find("<Attribute Name=\"axial_force\" AttributeType=\"Scalar\" Center=\"Cell\">"), std::string::npos);
    EXPECT_NE(xmf.find(">1 0 1 1 1 4</DataItem>\n              <DataItem Dimensions=\"2 4\" NumberType=\"Float\" Precision=\"8\" "
                       "Format=\"HDF\">f.h5:/frames/main/contact_state</DataItem>"),
              std::string::npos);
    EXPECT_EQ(xmf.find("/stay/axial_force"), std::string::npos);
    EXPECT_EQ(readText(dir + "/f_modes.xmf").find("Attribute"), std::string::npos);
    fs::remove_all(dir);
  }
}
