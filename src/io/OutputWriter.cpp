// HDF5 + XDMF run output (see include/strand/io/OutputWriter.hpp for the layout and the rules).
#include "strand/io/OutputWriter.hpp"

#include <hdf5.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "strand/core/Error.hpp"

#include "CommittedFile.hpp"
#include "Hdf5.hpp"

namespace strand::io {

namespace {

using namespace h5;

// Names become HDF5 link names and appear in "file.h5:/path" references in the XDMF file.
void checkName(const std::string& name, const std::string& kind) {
  if (name.empty() || name == "." || name == ".." ||
      name.find_first_of("/:") != std::string::npos)
    throw InputError("invalid " + kind + " name '" + name +
                     "' for the output file: it must be non-empty, not '.' or '..', and contain "
                     "neither '/' nor ':'");
  for (unsigned char c : name)
    if (c < 0x20) throw InputError("invalid " + kind + " name '" + name + "': control character");
}

std::string xmlEscape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string formatIndex(int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%05d", i);
  return buf;
}

std::string formatDouble(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Write-then-rename, so a reader (or a run killed mid-write) never sees a half-written file.
void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open '" + tmp + "' for writing: " + std::strerror(errno));
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write '" + tmp + "'");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + path + "': " + reason);
  }
}

std::string xdmfDocument(const std::string& collectionName, const std::string& grids) {
  std::string doc;
  doc.reserve(grids.size() + 512);
  doc += "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  doc += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  doc += "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n";
  doc += "  <Domain>\n";
  doc += "    <Grid Name=\"" + collectionName +
         "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  doc += grids;
  doc += "    </Grid>\n";
  doc += "  </Domain>\n";
  doc += "</Xdmf>\n";
  return doc;
}

// Collective error kinds, broadcast from rank 0.
enum ErrorKind : int { kOk = 0, kInput, kInvalidArgument, kLogic, kRuntime };

}  // namespace

struct OutputWriter::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  std::string path;
  std::string xdmfPath, modesXdmfPath;
  std::string h5Ref;  // the .h5 basename, XML-escaped, as used in DataItem references
  RunInfo info;
  std::vector<BodyLayout> bodies;
  bool closed = false;
  bool modesWritten = false;
  int frames = 0;

  // rank 0 only
  Hid file, framesGroup;
  struct Series {
    Hid dset;
    hsize_t size = 0;
  };
  std::map<std::string, Series> series;
  std::string frameGrids;  // cached XDMF text of every frame written so far

  // Runs `work` on rank 0 and makes every rank return or throw the same way.
  template <class F>
  void collective(const char* action, F&& work) {
    int kind = kOk;
    std::string message;
    if (rank == 0) {
      QuietHdf5 quiet;
      try {
        work();
      } catch (const InputError& e) {
        kind = kInput;
        message = e.what();
      } catch (const std::invalid_argument& e) {
        kind = kInvalidArgument;
        message = e.what();
      } catch (const std::logic_error& e) {
        kind = kLogic;
        message = e.what();
      } catch (const std::exception& e) {
        kind = kRuntime;
        message = "cannot " + std::string(action) + " output file '" + path + "': " + e.what();
      } catch (...) {
        kind = kRuntime;
        message = "cannot " + std::string(action) + " output file '" + path + "': unknown error";
      }
    }
    int head[2] = {kind, static_cast<int>(message.size())};
    MPI_Bcast(head, 2, MPI_INT, 0, comm);
    if (head[0] == kOk) return;
    message.resize(static_cast<std::size_t>(head[1]));
    if (head[1] > 0) MPI_Bcast(message.data(), head[1], MPI_CHAR, 0, comm);
    switch (head[0]) {
      case kInput: throw InputError(message);
      case kInvalidArgument: throw std::invalid_argument(message);
      case kLogic: throw std::logic_error(message);
      default: throw std::runtime_error(message);
    }
  }

  void requireOpen(const char* method) const {
    if (closed)
      throw std::logic_error(std::string("OutputWriter::") + method + " called after close() on '" +
                             path + "'");
  }

  void checkFrames(const std::vector<BodyFrame>& data, const std::string& what) const {
    if (data.size() != bodies.size())
      throw std::invalid_argument("OutputWriter: " + what + " has " + std::to_string(data.size()) +
                                  " bodies, the layout has " + std::to_string(bodies.size()));
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const BodyLayout& L = bodies[b];
      const std::size_t nc = static_cast<std::size_t>(L.pointsPerBody) * 3;
      const std::size_t nq = static_cast<std::size_t>(L.nodes) * L.coordsPerNode;
      if (data[b].centerline.size() != nc)
        throw std::invalid_argument("OutputWriter: " + what + ", body '" + L.name + "': centerline has " +
                                    std::to_string(data[b].centerline.size()) + " values, expected " +
                                    std::to_string(nc) + " (pointsPerBody x 3)");
      if (data[b].coordinates.size() != nq)
        throw std::invalid_argument("OutputWriter: " + what + ", body '" + L.name + "': coordinates has " +
                                    std::to_string(data[b].coordinates.size()) + " values, expected " +
                                    std::to_string(nq) + " (nodes x coordsPerNode)");
    }
  }

  // /<parent>/<body>/{centerline,coordinates} for every body.
  void writeBodies(hid_t parent, const std::vector<BodyFrame>& data) const {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const BodyLayout& L = bodies[b];
      Hid g = group(parent, L.name);
      writeMatrix(g.get(), "centerline", data[b].centerline.data(),
                  static_cast<hsize_t>(L.pointsPerBody), 3);
      writeMatrix(g.get(), "coordinates", data[b].coordinates.data(), static_cast<hsize_t>(L.nodes),
                  static_cast<hsize_t>(L.coordsPerNode));
    }
  }

  // One spatial collection over the bodies, whose centerlines live under `h5Group`.
  std::string spatialGrid(const std::string& name, double time, const std::string& h5Group,
                          const std::string& extra) const {
    std::ostringstream x;
    x << "      <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << formatDouble(time) << "\"/>\n";
    x << extra;
    for (const BodyLayout& L : bodies) {
      const std::string body = xmlEscape(L.name);
      const int segments = L.pointsPerBody - 1;
      x << "        <Grid Name=\"" << body << "\" GridType=\"Uniform\">\n";
      x << "          <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\""
        << segments << "\">\n";
      x << "            <DataItem Dimensions=\"" << segments
        << " 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5Ref << ":/bodies/" << body
        << "/connectivity</DataItem>\n";
      x << "          </Topology>\n";
      x << "          <Geometry GeometryType=\"XYZ\">\n";
      x << "            <DataItem Dimensions=\"" << L.pointsPerBody
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5Ref << ":" << h5Group
        << "/" << body << "/centerline</DataItem>\n";
      x << "          </Geometry>\n";
      x << "        </Grid>\n";
    }
    x << "      </Grid>\n";
    return x.str();
  }

  void create() {
    std::set<std::string> names;
    for (const BodyLayout& L : bodies) {
      checkName(L.name, "body");
      if (!names.insert(L.name).second)
        throw InputError("cannot create output file '" + path + "': duplicate body name '" + L.name + "'");
      if (L.elements < 1 || L.nodes < 1 || L.coordsPerNode < 1 || L.pointsPerBody < 2)
        throw std::invalid_argument("OutputWriter: body '" + L.name +
                                    "' needs elements, nodes, coordsPerNode >= 1 and pointsPerBody >= 2");
    }

    // written through the committing driver: the result changes only by atomic commits
    // (CommittedFile.hpp), so a killed run leaves the file of its last commit
    Hid fapl(committedFileAccess(), H5Pclose);
    hid_t fid = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
    if (fid < 0) throw InputError("cannot create output file '" + path + "': " + hdf5Reason());
    file = Hid(fid, H5Fclose);

    try {
      const hid_t root = file.get();
      writeAttribute(root, "strand_version", info.version);
      writeAttribute(root, "scene_file", info.sceneFile);
      writeAttribute(root, "analysis", info.analysis);
      writeAttribute(root, "dimension", info.dimension);

      Hid bodiesGroup = group(root, "bodies");
      for (const BodyLayout& L : bodies) {
        Hid g = group(bodiesGroup.get(), L.name);
        writeAttribute(g.get(), "element_type", L.elementType);
        writeAttribute(g.get(), "elements", L.elements);
        writeAttribute(g.get(), "nodes", L.nodes);
        writeAttribute(g.get(), "coords_per_node", L.coordsPerNode);
        writeAttribute(g.get(), "points_per_body", L.pointsPerBody);
        const int segments = L.pointsPerBody - 1;
        std::vector<int> conn(2 * static_cast<std::size_t>(segments));
        for (int k = 0; k < segments; ++k) {
          conn[2 * k] = k;
          conn[2 * k + 1] = k + 1;
        }
        Hid space = simpleSpace({static_cast<hsize_t>(segments), 2});
        Hid dset(check(H5Dcreate2(g.get(), "connectivity", H5T_STD_I32LE, space.get(), H5P_DEFAULT,
                                  H5P_DEFAULT, H5P_DEFAULT),
                       "cannot create dataset 'connectivity'"),
                 H5Dclose);
        check(H5Dwrite(dset.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, conn.data()),
              "cannot write dataset 'connectivity'");
        dset.close("cannot close dataset 'connectivity'");
      }
      framesGroup = group(root, "frames");
      writeAttribute(framesGroup.get(), "count", 0);
      Hid seriesGroup = group(root, "series");
      check(H5Fflush(root, H5F_SCOPE_GLOBAL), "cannot flush");
      commit(root);
      // An empty (valid) collection now, so a run that dies before its first frame still leaves
      // a consistent pair, and an unwritable .xmf location is reported at creation.
      writeFileAtomically(xdmfPath, xdmfDocument("frames", ""));
    } catch (const std::exception& e) {
      framesGroup.reset();
      file.reset();
      std::string reason = e.what();
      throw InputError("cannot create output file '" + path + "': " + reason);
    }
  }

  void writeFrame(double time, const std::vector<BodyFrame>& data) {
    requireOpen("writeFrame");
    checkFrames(data, "frame " + std::to_string(frames));
    const std::string name = formatIndex(frames);
    const std::string grid = spatialGrid("frame_" + name, time, "/frames/" + name, "");
    try {
      {
        Hid g = group(framesGroup.get(), name);
        writeAttribute(g.get(), "time", time);
        writeBodies(g.get(), data);
      }
      updateAttribute(framesGroup.get(), "count", frames + 1);
      check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
      commit(file.get());
      // The .xmf only ever names data that is already committed.
      writeFileAtomically(xdmfPath, xdmfDocument("frames", frameGrids + grid));
    } catch (...) {
      // Best effort: leave the file as it was before this frame, so that the .xmf (still the old
      // one) and /frames agree and a later frame can take this index.
      H5Ldelete(framesGroup.get(), name.c_str(), H5P_DEFAULT);
      overwriteIntAttribute(framesGroup.get(), "count", frames);
      H5Fflush(file.get(), H5F_SCOPE_GLOBAL);
      throw;
    }
    frameGrids += grid;
  }

  void writeSeries(const std::string& name, double value) {
    requireOpen("writeScalarSeries");
    checkName(name, "series");
    auto it = series.find(name);
    if (it == series.end()) {
      hsize_t dims[1] = {0}, maxDims[1] = {H5S_UNLIMITED}, chunk[1] = {512};
      Hid space(check(H5Screate_simple(1, dims, maxDims), "cannot create dataspace"), H5Sclose);
      Hid dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "cannot create property list"), H5Pclose);
      check(H5Pset_chunk(dcpl.get(), 1, chunk), "cannot set chunking");
      const std::string dpath = "/series/" + name;
      Series s;
      s.dset = Hid(check(H5Dcreate2(file.get(), dpath.c_str(), H5T_IEEE_F64LE, space.get(),
                                    H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                         "cannot create dataset '" + dpath + "'"),
                   H5Dclose);
      it = series.emplace(name, std::move(s)).first;
    }
    Series& s = it->second;
    const std::string dpath = "/series/" + name;
    hsize_t newSize[1] = {s.size + 1};
    check(H5Dset_extent(s.dset.get(), newSize), "cannot extend dataset '" + dpath + "'");
    Hid fspace(check(H5Dget_space(s.dset.get()), "cannot get dataspace of '" + dpath + "'"), H5Sclose);
    hsize_t start[1] = {s.size}, count[1] = {1};
    check(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
          "cannot select in '" + dpath + "'");
    Hid mspace = simpleSpace({1});
    check(H5Dwrite(s.dset.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT, &value),
          "cannot write dataset '" + dpath + "'");
    s.size += 1;
  }

  void writeModes(const std::vector<double>& freqs, const std::vector<std::vector<BodyFrame>>& shapes,
                  const std::vector<double>& residuals, const std::vector<OutputWriter::ModeLabelOut>& labels) {
    requireOpen("writeModes");
    if (modesWritten) throw std::logic_error("OutputWriter::writeModes called twice on '" + path + "'");
    if (freqs.size() != shapes.size())
      throw std::invalid_argument("OutputWriter::writeModes: " + std::to_string(freqs.size()) +
                                  " frequencies but " + std::to_string(shapes.size()) + " mode shapes");
    for (std::size_t m = 0; m < shapes.size(); ++m) checkFrames(shapes[m], "mode " + std::to_string(m));
    if (!residuals.empty() && residuals.size() != freqs.size())
      throw std::invalid_argument("OutputWriter::writeModes: " + std::to_string(freqs.size()) + " frequencies but " +
                                  std::to_string(residuals.size()) + " residuals");

    std::string grids;
    try {
      Hid modes = group(file.get(), "modes");
      Hid space = simpleSpace({static_cast<hsize_t>(freqs.size())});
      Hid dset(check(H5Dcreate2(modes.get(), "frequencies_hz", H5T_IEEE_F64LE, space.get(),
                                H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     "cannot create dataset '/modes/frequencies_hz'"),
               H5Dclose);
      if (!freqs.empty())
        check(H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, freqs.data()),
              "cannot write dataset '/modes/frequencies_hz'");
      dset.close("cannot close dataset '/modes/frequencies_hz'");
      writeAttribute(modes.get(), "count", static_cast<int>(freqs.size()));
      for (std::size_t m = 0; m < shapes.size(); ++m) {
        const std::string name = formatIndex(static_cast<int>(m));
        Hid g = group(modes.get(), name);
        writeAttribute(g.get(), "frequency_hz", freqs[m]);
        if (!residuals.empty()) writeAttribute(g.get(), "relative_residual", residuals[m]);
        if (m < labels.size()) {
          writeAttribute(g.get(), "label", labels[m].name);
          writeAttribute(g.get(), "label_share", labels[m].share);
        }
        writeBodies(g.get(), shapes[m]);
        // ParaView steps through the modes as "time" = mode index; the frequency rides along.
        grids += spatialGrid("mode_" + name, static_cast<double>(m), "/modes/" + name,
                             "        <Information Name=\"frequency_hz\" Value=\"" +
                                 formatDouble(freqs[m]) + "\"/>\n");
      }
      modes.close("cannot close group '/modes'");
      check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
      commit(file.get());
      writeFileAtomically(modesXdmfPath, xdmfDocument("modes", grids));
    } catch (...) {
      H5Ldelete(file.get(), "modes", H5P_DEFAULT);  // best effort: allow a retry
      H5Fflush(file.get(), H5F_SCOPE_GLOBAL);
      throw;
    }
    modesWritten = true;
  }

  void setAttribute(const std::string& name, double value) {
    requireOpen("setAttribute");
    checkName(name, "attribute");
    writeAttribute(file.get(), name, value);
  }

  void setAttribute(const std::string& name, const std::string& value) {
    requireOpen("setAttribute");
    checkName(name, "attribute");
    writeAttribute(file.get(), name, value);
  }

  // rank 0: close everything, reporting the first failure after trying all of it.
  void closeFiles() {
    std::string firstError;
    auto attempt = [&](auto&& f) {
      try {
        f();
      } catch (const std::exception& e) {
        if (firstError.empty()) firstError = e.what();
      }
    };
    for (auto& [name, s] : series) attempt([&] { s.dset.close("cannot close dataset '/series/" + name + "'"); });
    series.clear();
    attempt([&] { framesGroup.close("cannot close group '/frames'"); });
    if (file) {
      bool flushed = false;
      attempt([&] {
        check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
        flushed = true;
      });
      if (flushed) attempt([&] { commit(file.get()); });
      attempt([&] { file.close("cannot close"); });
    }
    if (!firstError.empty()) throw Hdf5Failure(firstError);
  }
};

std::string xdmfPathFor(const std::string& h5Path) {
  const std::filesystem::path p(h5Path);
  return (p.parent_path() / (p.stem().string() + ".xmf")).string();
}

std::string modesXdmfPathFor(const std::string& h5Path) {
  const std::filesystem::path p(h5Path);
  return (p.parent_path() / (p.stem().string() + "_modes.xmf")).string();
}

OutputWriter::OutputWriter(MPI_Comm comm, std::string path, RunInfo info, std::vector<BodyLayout> bodies)
    : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.comm = comm;
  MPI_Comm_rank(comm, &I.rank);
  I.path = std::move(path);
  I.info = std::move(info);
  I.bodies = std::move(bodies);
  I.xdmfPath = xdmfPathFor(I.path);
  I.modesXdmfPath = modesXdmfPathFor(I.path);
  I.h5Ref = xmlEscape(std::filesystem::path(I.path).filename().string());
  I.collective("create", [&] {
    if (I.path.empty()) throw InputError("cannot create output file '': empty file name");
    I.create();
  });
}

OutputWriter::~OutputWriter() {
  // No communication here: the destructor may run during unwinding on some ranks only.
  if (!impl_ || impl_->closed || impl_->rank != 0) return;
  QuietHdf5 quiet;
  try {
    impl_->closeFiles();
  } catch (...) {
  }
}

void OutputWriter::writeFrame(double time, const std::vector<BodyFrame>& frames) {
  impl_->collective("write", [&] { impl_->writeFrame(time, frames); });
  ++impl_->frames;
}

void OutputWriter::writeScalarSeries(const std::string& name, double value) {
  impl_->collective("write", [&] { impl_->writeSeries(name, value); });
}

void OutputWriter::writeModes(const std::vector<double>& frequenciesHz,
                              const std::vector<std::vector<BodyFrame>>& shapes, const std::vector<double>& residuals,
                              const std::vector<ModeLabelOut>& labels) {
  impl_->collective("write", [&] { impl_->writeModes(frequenciesHz, shapes, residuals, labels); });
  impl_->modesWritten = true;
}

void OutputWriter::setAttribute(const std::string& name, double value) {
  impl_->collective("write", [&] { impl_->setAttribute(name, value); });
}

void OutputWriter::setAttribute(const std::string& name, const std::string& value) {
  impl_->collective("write", [&] { impl_->setAttribute(name, value); });
}

void OutputWriter::close() {
  if (impl_->closed) return;
  impl_->closed = true;  // even if closing fails: the handles are gone either way
  impl_->collective("close", [&] { impl_->closeFiles(); });
}

const std::string& OutputWriter::path() const { return impl_->path; }
std::string OutputWriter::xdmfPath() const { return impl_->xdmfPath; }
std::string OutputWriter::modesXdmfPath() const { return impl_->modesXdmfPath; }
int OutputWriter::framesWritten() const { return impl_->frames; }

}  // namespace strand::io
