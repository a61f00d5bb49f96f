// HDF5 + XDMF run output (see include/strand/io/OutputWriter.hpp for the layout and the rules).
#include "strand/io/OutputWriter.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "strand/core/Error.hpp"

#include "CommittedFile.hpp"
#include "Hdf5.hpp"
#include "RowDataset.hpp"

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
// The text is the concatenation of `parts`.
void writeFileAtomically(const std::string& path, const std::vector<const std::string*>& parts) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open '" + tmp + "' for writing: " + std::strerror(errno));
    for (const std::string* p : parts) out.write(p->data(), static_cast<std::streamsize>(p->size()));
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

// An XDMF document: a temporal collection of the spatial collections in `grids` (concatenated).
void writeXdmf(const std::string& path, const std::string& collectionName,
               std::initializer_list<const std::string*> grids) {
  const std::string head = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
                           "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                           "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
                           "  <Domain>\n"
                           "    <Grid Name=\"" + collectionName + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string tail = "    </Grid>\n  </Domain>\n</Xdmf>\n";
  std::vector<const std::string*> parts{&head};
  parts.insert(parts.end(), grids.begin(), grids.end());
  parts.push_back(&tail);
  writeFileAtomically(path, parts);
}

// Collective error kinds, broadcast from rank 0.
enum ErrorKind : int { kOk = 0, kInput, kInvalidArgument, kLogic, kRuntime };

}  // namespace

struct OutputWriter::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::string path;
  std::string xdmfPath, modesXdmfPath;
  std::string h5Ref;  // the .h5 basename, XML-escaped, as used in DataItem references
  RunInfo info;
  std::vector<BodyLayout> bodies;
  bool closed = false;
  bool modesWritten = false;
  int frames = 0;  // frames accepted (committed + buffered); on the other ranks a copy of rank 0's
  CommitPolicy policy;

  // rank 0 only
  Hid file, framesGroup;
  struct Series {
    RowDataset data;  // created by the first commit that has values for it
    int width = 0;    // 0: scalar (1-D dataset), else the row width of a 2-D dataset
  };
  std::map<std::string, Series> series;
  Series* lastSeries = nullptr;  // the last series looked up (a run appends to a handful, in turn)
  std::string lastSeriesName;
  // /frames/time and, per body, /frames/<body>/{centerline, coordinates, <cell fields>}: one row
  // per frame (see "Frames" in OutputWriter.hpp)
  struct BodyFrames {
    RowDataset centerline, coordinates;
    std::vector<RowDataset> fields;
  };
  RowDataset frameTimes;  // its buffer: the times of frames committedFrames, committedFrames + 1, ...
  std::vector<BodyFrames> frameData;
  int committedFrames = 0;
  std::size_t pendingBytes = 0;
  bool pendingSeries = false;
  std::chrono::steady_clock::time_point lastCommit = std::chrono::steady_clock::now();
  std::string frameGrids;  // cached XDMF text of every committed frame

  // Runs `work` on rank 0 and makes every rank return or throw the same way.
  template <class F>
  void collective(const char* action, F&& work) {
    int kind = kOk;
    std::string message;
    if (rank == 0) {
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
    int head[3] = {kind, static_cast<int>(message.size()), frames};
    if (size > 1) {  // one rank: no broadcast (a run makes dozens of these calls per step)
      MPI_Bcast(head, 3, MPI_INT, 0, comm);
      frames = head[2];  // a failed block takes its frames back: framesWritten() agrees on all ranks
    }
    if (head[0] == kOk) return;
    message.resize(static_cast<std::size_t>(head[1]));
    if (head[1] > 0 && size > 1) MPI_Bcast(message.data(), head[1], MPI_CHAR, 0, comm);
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

  // withFields: a frame (the layout's cell fields), else a mode shape (none)
  void checkFrames(const std::vector<BodyFrame>& data, const std::string& what, bool withFields) const {
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
      if (withFields && data[b].cellFields.size() != L.cellFields.size())
        throw std::invalid_argument("OutputWriter: " + what + ", body '" + L.name + "': " +
                                    std::to_string(data[b].cellFields.size()) + " cell fields, the layout has " +
                                    std::to_string(L.cellFields.size()));
      if (!withFields && !data[b].cellFields.empty())
        throw std::invalid_argument("OutputWriter: " + what + ", body '" + L.name + "': mode shapes carry no cell fields");
      for (const std::vector<double>& f : data[b].cellFields)
        if (f.size() != static_cast<std::size_t>(L.pointsPerBody - 1))
          throw std::invalid_argument("OutputWriter: " + what + ", body '" + L.name + "': a cell field has " +
                                      std::to_string(f.size()) + " values, expected " +
                                      std::to_string(L.pointsPerBody - 1) + " (pointsPerBody - 1)");
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

  // The DataItem of a body's dataset `dataset` (centerline, coordinates or a cell field) whose
  // shape is `dims`, indented for spatialGrid.
  using DataItemFor = std::function<std::string(const std::string& body, const std::string& dataset, const std::string& dims)>;

  // A whole dataset /<group>/<body>/<dataset> (a mode shape).
  DataItemFor wholeDataset(const std::string& h5Group) const {
    return [this, h5Group](const std::string& body, const std::string& dataset, const std::string& dims) {
      return "            <DataItem Dimensions=\"" + dims + "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5Ref +
             ":" + h5Group + "/" + body + "/" + dataset + "</DataItem>\n";
    };
  }

  // Row k of /frames/<body>/<dataset>: an XDMF HyperSlab (start k, count 1 along the frames). The
  // dataset is declared with k + 1 rows, which it has from frame k on, so frame k's text never
  // changes as the run goes on.
  DataItemFor frameRow(int k) const {
    return [this, k](const std::string& body, const std::string& dataset, const std::string& dims) {
      const bool matrix = dims.find(' ') != std::string::npos;
      const std::string selection = matrix ? std::to_string(k) + " 0 0 1 1 1 1 " + dims : std::to_string(k) + " 0 1 1 1 " + dims;
      return "            <DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + dims + "\">\n"
             "              <DataItem Dimensions=\"" + std::string(matrix ? "3 3" : "3 2") + "\" Format=\"XML\">" + selection +
             "</DataItem>\n"
             "              <DataItem Dimensions=\"" + std::to_string(k + 1) + " " + dims +
             "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5Ref + ":/frames/" + body + "/" + dataset +
             "</DataItem>\n"
             "            </DataItem>\n";
    };
  }

  // One spatial collection over the bodies: each a polyline through its centerline.
  std::string spatialGrid(const std::string& name, double time, const std::string& extra, bool withFields,
                          const DataItemFor& item) const {
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
      x << item(body, "centerline", std::to_string(L.pointsPerBody) + " 3");
      x << "          </Geometry>\n";
      for (const std::string& f : withFields ? L.cellFields : std::vector<std::string>{}) {
        x << "          <Attribute Name=\"" << xmlEscape(f) << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
        x << item(body, xmlEscape(f), std::to_string(segments));
        x << "          </Attribute>\n";
      }
      x << "        </Grid>\n";
    }
    x << "      </Grid>\n";
    return x.str();
  }

  void create() {
    QuietHdf5 quiet;
    std::set<std::string> names;
    for (const BodyLayout& L : bodies) {
      checkName(L.name, "body");
      if (L.name == "time")
        throw InputError("cannot create output file '" + path + "': a body cannot be named 'time' (/frames/time holds the frame times)");
      if (!names.insert(L.name).second)
        throw InputError("cannot create output file '" + path + "': duplicate body name '" + L.name + "'");
      if (L.elements < 1 || L.nodes < 1 || L.coordsPerNode < 1 || L.pointsPerBody < 2)
        throw std::invalid_argument("OutputWriter: body '" + L.name +
                                    "' needs elements, nodes, coordsPerNode >= 1 and pointsPerBody >= 2");
      for (const std::string& f : L.cellFields) {
        checkName(f, "cell field");
        if (f == "centerline" || f == "coordinates")
          throw std::invalid_argument("OutputWriter: body '" + L.name + "': cell field '" + f + "' clashes with a dataset");
      }
    }

    // written through the committing driver: the result changes only by atomic commits
    // (CommittedFile.hpp), so a killed run leaves the file of its last commit
    Hid fapl(committedFileAccess(), H5Pclose);
    // HDF5 1.8's file format: groups keep their links in their object header (a frame is one
    // object header per group and dataset, no B-tree and heap per group), several times cheaper
    // to write than the 1.6 format; readers since HDF5 1.8 (2008) open it (ParaView, h5py)
    check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "cannot set the file format");
    // Metadata and small raw data allocated from 1 MB blocks: the free-space bookkeeping of the
    // default 2 kB blocks costs more than the frame's own writes
    check(H5Pset_meta_block_size(fapl.get(), 1 << 20), "cannot set the metadata block size");
    check(H5Pset_small_data_block_size(fapl.get(), 1 << 20), "cannot set the small-data block size");
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
      // chunks of 64 kB (at least a frame): a few per block and dataset for a small model
      constexpr std::size_t kChunk = 64 << 10;
      frameTimes.create(framesGroup.get(), "time", {}, 8 << 10);
      frameData.resize(bodies.size());
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyLayout& L = bodies[b];
        Hid g = group(framesGroup.get(), L.name);
        frameData[b].centerline.create(g.get(), "centerline", {static_cast<hsize_t>(L.pointsPerBody), 3}, kChunk);
        frameData[b].coordinates.create(g.get(), "coordinates",
                                        {static_cast<hsize_t>(L.nodes), static_cast<hsize_t>(L.coordsPerNode)}, kChunk);
        frameData[b].fields.resize(L.cellFields.size());
        for (std::size_t f = 0; f < L.cellFields.size(); ++f)
          frameData[b].fields[f].create(g.get(), L.cellFields[f], {static_cast<hsize_t>(L.pointsPerBody - 1)}, kChunk);
      }
      Hid seriesGroup = group(root, "series");
      check(H5Fflush(root, H5F_SCOPE_GLOBAL), "cannot flush");
      commit(root);
      // An empty (valid) collection now, so a run that dies before its first frame still leaves
      // a consistent pair, and an unwritable .xmf location is reported at creation.
      writeXdmf(xdmfPath, "frames", {});
      lastCommit = std::chrono::steady_clock::now();
    } catch (const std::exception& e) {
      frameTimes = RowDataset();
      frameData.clear();
      framesGroup.reset();
      file.reset();
      std::string reason = e.what();
      throw InputError("cannot create output file '" + path + "': " + reason);
    }
  }

  // Buffers the frame; the next commit writes it.
  void writeFrame(double time, const std::vector<BodyFrame>& data) {
    requireOpen("writeFrame");
    checkFrames(data, "frame " + std::to_string(frames), true);
    frameTimes.buffer(&time, 1);
    for (std::size_t b = 0; b < data.size(); ++b) {
      const BodyFrame& f = data[b];
      frameData[b].centerline.buffer(f.centerline.data(), f.centerline.size());
      frameData[b].coordinates.buffer(f.coordinates.data(), f.coordinates.size());
      pendingBytes += 8 * (f.centerline.size() + f.coordinates.size());
      for (std::size_t k = 0; k < f.cellFields.size(); ++k) {
        frameData[b].fields[k].buffer(f.cellFields[k].data(), f.cellFields[k].size());
        pendingBytes += 8 * f.cellFields[k].size();
      }
    }
    ++frames;
    // the first frame is committed at once: a file that a viewer opens early shows the start
    if (committedFrames == 0 || commitDue()) commitBlock();
  }

  Series& seriesFor(const std::string& name, int width, const char* method) {
    if (lastSeries && name == lastSeriesName) {
      if (lastSeries->width != width) widthMismatch(name, lastSeries->width, width, method);
      return *lastSeries;
    }
    auto it = series.find(name);
    if (it == series.end()) {
      checkName(name, "series");
      it = series.emplace(name, Series{}).first;
      it->second.width = width;
    } else if (it->second.width != width) {
      widthMismatch(name, it->second.width, width, method);
    }
    lastSeries = &it->second;
    lastSeriesName = name;
    return it->second;
  }

  [[noreturn]] void widthMismatch(const std::string& name, int had, int got, const char* method) const {
    auto shape = [](int w) { return w == 0 ? std::string("scalar") : "rows of " + std::to_string(w); };
    throw std::invalid_argument(std::string("OutputWriter::") + method + ": series '" + name + "' holds " + shape(had) +
                                ", not " + shape(got));
  }

  // Buffers one value (width 0) or one row; the next commit appends the block to the dataset.
  void appendSeries(const std::string& name, const double* values, std::size_t n, int width, const char* method) {
    requireOpen(method);
    Series& s = seriesFor(name, width, method);
    s.data.buffer(values, n);
    pendingBytes += 8 * n;
    pendingSeries = true;
    if (commitDue()) commitBlock();
  }

  bool commitDue() const {
    if (pendingBytes >= policy.maxBytes) return true;
    const auto now = std::chrono::steady_clock::now();
    return std::chrono::duration<double>(now - lastCommit).count() >= policy.intervalSeconds;
  }

  // Every frame dataset, for `f`.
  template <class F>
  void forFrameDatasets(F&& f) {
    f(frameTimes);
    for (BodyFrames& b : frameData) {
      f(b.centerline);
      f(b.coordinates);
      for (RowDataset& d : b.fields) f(d);
    }
  }

  // Writes the buffered frames and series values (one extent change and one write per dataset),
  // flushes and commits; then the .xdmf2 names the new frames. On failure, the block is taken back
  // (the datasets cut back to their committed rows, best effort) and dropped, so that the file and
  // the .xdmf2 stay consistent and the next frame takes the first index of the lost block; the
  // exception propagates.
  void commitBlock() {
    QuietHdf5 quiet;
    const int first = committedFrames;
    const std::vector<double>& times = frameTimes.pending();  // kept until committed() or rollback()
    const int n = static_cast<int>(times.size());
    std::string grids;
    try {
      if (n > 0) {
        forFrameDatasets([](RowDataset& d) { d.write(); });
        updateAttribute(framesGroup.get(), "count", first + n);
        for (int k = 0; k < n; ++k)
          grids += spatialGrid("frame_" + formatIndex(first + k), times[k], "", true, frameRow(first + k));
      }
      for (auto& [name, s] : series) {
        if (s.data.pendingValues() == 0) continue;
        if (!s.data.created())  // chunks of 8 kB: a few per block, whatever the row width
          s.data.create(file.get(), "/series/" + name,
                        s.width == 0 ? std::vector<hsize_t>{} : std::vector<hsize_t>{static_cast<hsize_t>(s.width)}, 8 << 10);
        s.data.write();
      }
      check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
      commit(file.get());
      // The .xdmf2 only ever names data that is already committed.
      if (n > 0) writeXdmf(xdmfPath, "frames", {&frameGrids, &grids});
    } catch (...) {
      forFrameDatasets([](RowDataset& d) { d.rollback(); });
      overwriteIntAttribute(framesGroup.get(), "count", first);
      for (auto& [name, s] : series) s.data.rollback();
      H5Fflush(file.get(), H5F_SCOPE_GLOBAL);
      dropPending();
      frames = committedFrames;
      throw;
    }
    committedFrames += n;
    frameGrids += grids;
    forFrameDatasets([](RowDataset& d) { d.committed(); });
    for (auto& [name, s] : series) s.data.committed();
    dropPending();
  }

  void dropPending() {
    pendingBytes = 0;
    pendingSeries = false;
    lastCommit = std::chrono::steady_clock::now();
  }

  void writeModes(const std::vector<double>& freqs, const std::vector<std::vector<BodyFrame>>& shapes,
                  const std::vector<double>& residuals, const std::vector<OutputWriter::ModeLabelOut>& labels) {
    requireOpen("writeModes");
    if (modesWritten) throw std::logic_error("OutputWriter::writeModes called twice on '" + path + "'");
    if (freqs.size() != shapes.size())
      throw std::invalid_argument("OutputWriter::writeModes: " + std::to_string(freqs.size()) +
                                  " frequencies but " + std::to_string(shapes.size()) + " mode shapes");
    for (std::size_t m = 0; m < shapes.size(); ++m) checkFrames(shapes[m], "mode " + std::to_string(m), false);
    if (!residuals.empty() && residuals.size() != freqs.size())
      throw std::invalid_argument("OutputWriter::writeModes: " + std::to_string(freqs.size()) + " frequencies but " +
                                  std::to_string(residuals.size()) + " residuals");

    QuietHdf5 quiet;
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
        grids += spatialGrid("mode_" + name, static_cast<double>(m),
                             "        <Information Name=\"frequency_hz\" Value=\"" + formatDouble(freqs[m]) + "\"/>\n",
                             false, wholeDataset("/modes/" + name));
      }
      modes.close("cannot close group '/modes'");
      commitBlock();  // with whatever is buffered
      writeXdmf(modesXdmfPath, "modes", {&grids});
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
    QuietHdf5 quiet;
    writeAttribute(file.get(), name, value);  // into the work file: published by the next commit
  }

  void setAttribute(const std::string& name, const std::string& value) {
    requireOpen("setAttribute");
    checkName(name, "attribute");
    QuietHdf5 quiet;
    writeAttribute(file.get(), name, value);  // into the work file: published by the next commit
  }

  // rank 0: close everything, reporting the first failure after trying all of it.
  void closeFiles() {
    QuietHdf5 quiet;
    std::string firstError;
    auto attempt = [&](auto&& f) {
      try {
        f();
      } catch (const std::exception& e) {
        if (firstError.empty()) firstError = e.what();
      }
    };
    // the last block (and attributes set since the last commit): committed before anything closes
    bool committed = false;
    if (file && framesGroup) attempt([&] {
        commitBlock();
        committed = true;
      });
    for (auto& [name, s] : series) attempt([&] { s.data.close(); });
    series.clear();
    forFrameDatasets([&](RowDataset& d) { attempt([&] { d.close(); }); });
    frameData.clear();
    lastSeries = nullptr;
    attempt([&] { framesGroup.close("cannot close group '/frames'"); });
    if (file) {
      if (!committed) {  // a failed block was taken back: publish the rest
        bool flushed = false;
        attempt([&] {
          check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "cannot flush");
          flushed = true;
        });
        if (flushed) attempt([&] { commit(file.get()); });
      }
      attempt([&] { file.close("cannot close"); });
    }
    if (!firstError.empty()) throw Hdf5Failure(firstError);
  }
};

std::string xdmfPathFor(const std::string& h5Path) {
  const std::filesystem::path p(h5Path);
  return (p.parent_path() / (p.stem().string() + ".xdmf2")).string();
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
  MPI_Comm_size(comm, &I.size);
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
}

void OutputWriter::writeScalarSeries(const std::string& name, double value) {
  impl_->collective("write", [&] { impl_->appendSeries(name, &value, 1, 0, "writeScalarSeries"); });
}

void OutputWriter::writeVectorSeries(const std::string& name, const std::vector<double>& row) {
  impl_->collective("write", [&] {
    if (row.empty())
      throw std::invalid_argument("OutputWriter::writeVectorSeries: series '" + name + "': an empty row");
    impl_->appendSeries(name, row.data(), row.size(), static_cast<int>(row.size()), "writeVectorSeries");
  });
}

void OutputWriter::flush() {
  impl_->collective("write", [&] {
    impl_->requireOpen("flush");
    impl_->commitBlock();
  });
}

void OutputWriter::setCommitPolicy(const CommitPolicy& policy) {
  if (!(policy.intervalSeconds >= 0.0))
    throw std::invalid_argument("OutputWriter::setCommitPolicy: the interval must be >= 0 s");
  impl_->policy = policy;
}

OutputWriter::CommitPolicy OutputWriter::commitPolicy() const { return impl_->policy; }

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
