// Run output: one HDF5 file per run plus XDMF files that ParaView opens.
//
// Layout of <path> (all written by rank 0 with the serial HDF5 API; the caller gathers first):
//   /                          attrs strand_version, scene_file, analysis (strings), dimension (int),
//                              plus whatever setAttribute() adds
//   /bodies/<body>             attrs element_type (string), elements, nodes, coords_per_node,
//                              points_per_body (int)
//   /bodies/<body>/connectivity   int32 (pointsPerBody-1) x 2: segment k joins centerline points k, k+1
//   /frames                    attr count (int): frames written so far
//   /frames/time               double, frames: the physical time or load factor of each frame
//   /frames/<body>/centerline  double frames x pointsPerBody x 3 (2D runs: z = 0)
//   /frames/<body>/coordinates double frames x nodes x coordsPerNode
//   /frames/<body>/<field>     double frames x (pointsPerBody - 1): the layout's cell fields
//   /series/<name>             double, 1-D, chunked, unlimited; one value per writeScalarSeries() call,
//                              or 2-D rows x width, one row per writeVectorSeries() call
//   /modes/frequencies_hz      double, one per mode
//   /modes/NNNNN/<body>/{centerline,coordinates}   one group per mode
//
// Frames: one extendible dataset per body and quantity, a row per frame (the layout of PyLith's
// HDF5 output), so a frame costs a copy into the block buffer and a block one write per dataset,
// and a history is one array to a reader (h5py: f['frames/beam/coordinates'][:, -1, :2]). A body
// cannot be named `time`. <stem>.xdmf2 holds a temporal collection (one spatial collection over the
// bodies per frame: Polyline topology = the body's connectivity, XYZ geometry = row k of the
// centerline) whose DataItems are XDMF HyperSlabs of those datasets. ParaView opens .xdmf2 files
// with its XDMF (version 2) reader, which follows HyperSlabs; its Xdmf3 readers (the ones it picks
// for .xmf) do not and would show empty geometry (ParaView 5.11, checked with pvpython:
// tests/regression/paraview_open.py). <stem>_modes.xmf holds the mode shapes as a collection whose
// "time" is the mode index, plain datasets that every reader opens. Both reference the .h5 file by
// basename, so the files can be moved together.
//
// Buffering (issue 36 item 6): writeFrame, writeScalarSeries and writeVectorSeries only copy their
// data into memory on rank 0 (a frame of a 10-element beam: about 1.4 kB). A block of buffered data
// is written and committed (below) when CommitPolicy::intervalSeconds (default 2 s) have passed
// since the last commit or CommitPolicy::maxBytes (default 4 MB) are buffered, checked at each
// write; and always for the first frame (a viewer opened early sees the start), at flush(), at
// writeModes(), at close() and in the destructor (unwinding after a solver error). Each frame
// dataset and series is extended and written once per block. setAttribute() writes at once into
// the work file (below), so attributes too are published by the next commit. A frame or a series
// value costs a copy (docs/performance.md, "Output").
//
// Crash safety (issue 32 item 4): the .h5 file changes on disk only by atomic commits. HDF5 writes
// into a hidden work file next to it (.<name>.strand-work); a commit flushes (H5Fflush: the work
// file is then a consistent HDF5 file), renames the flushed file over <path> atomically and catches
// the work file up (src/io/CommittedFile.hpp). Only then is the .xdmf2 rewritten, atomically too
// (<stem>.xdmf2.tmp, then rename()). So a run that is killed at any instant, or diverges, leaves
// <path> as it was at its last commit: readable, every frame and series value up to that commit,
// and an .xdmf2 that never names missing data. A kill -9 loses what was buffered since: at most
// intervalSeconds of the run (or maxBytes of output). In-place writes with a flush per frame did not
// give that: a kill during a flush or a metadata eviction left /frames unreadable (3 of 150 kill -9
// tests). A block whose commit fails is taken back (its frames deleted, the series cut back; best
// effort) and dropped: the call throws, framesWritten() returns to the last commit on all ranks, and
// the next frame takes the first lost index.
// Costs: one more copy of what each commit wrote, and the work file (as large as the result) until
// close(); a killed run leaves it behind. Readers may open <path> during the run (it is always a
// committed state). The .xdmf2 is rewritten whole at each commit (about 1 kB per body and frame).
// File format: HDF5 1.8 (libver bounds v18), read by any HDF5 since 1.8, ParaView and h5py included.
//
// Parallel use: every method is collective over `comm` (all ranks call it); only rank 0 touches
// files, and its success or failure is broadcast so that all ranks return or throw together. Data
// arguments are read on rank 0 only. The destructor does no communication: it closes the files on
// rank 0 if close() was not called and swallows errors.
//
// Errors (thrown on all ranks):
//   strand::InputError        the file cannot be created ("cannot create output file '<path>': ..."),
//                             or a body / series / attribute name is unusable
//   std::invalid_argument     data whose sizes do not match the BodyLayout (a caller bug)
//   std::logic_error          use after close(), writeModes() twice
//   std::runtime_error        an HDF5 or file-system failure while writing ("cannot write output ...")
#pragma once
#include <mpi.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace strand::io {

struct BodyLayout {
  std::string name;         // group name: non-empty, no '/' or ':', not "." or ".."; unique
  std::string elementType;  // e.g. "AncfCable3d"
  int elements = 0;
  int nodes = 0;
  int coordsPerNode = 0;
  int pointsPerBody = 0;  // centerline sample points, >= 2
  // Fields each frame carries along the centerline, one value per segment (pointsPerBody - 1):
  // /frames/<body>/<field>, an XDMF cell attribute (e.g. axial_force, contact_pressure).
  std::vector<std::string> cellFields;
};

struct BodyFrame {
  std::vector<double> centerline;   // pointsPerBody x 3, row-major
  std::vector<double> coordinates;  // nodes x coordsPerNode, row-major
  std::vector<std::vector<double>> cellFields;  // frames: the layout's cellFields in order; mode shapes: none
};

struct RunInfo {
  std::string sceneFile, analysis, version;
  int dimension = 3;
};

// The XDMF files an OutputWriter writes next to `h5Path`: <stem>.xdmf2 and <stem>_modes.xmf.
std::string xdmfPathFor(const std::string& h5Path);
std::string modesXdmfPathFor(const std::string& h5Path);

class OutputWriter {
public:
  // Writes the root attributes, /bodies, the empty /frames datasets and an empty <stem>.xdmf2; an existing `path` is replaced (at
  // this first commit, atomically). The caller decides whether it may be (drivers/FileSafety.hpp).
  OutputWriter(MPI_Comm comm, std::string path, RunInfo info, std::vector<BodyLayout> bodies);
  ~OutputWriter();
  OutputWriter(const OutputWriter&) = delete;
  OutputWriter& operator=(const OutputWriter&) = delete;

  // When buffered data are committed (see "Buffering" above): once `intervalSeconds` have passed
  // since the last commit, or once `maxBytes` of frame and series data are buffered, whichever
  // comes first (checked at every write). intervalSeconds = 0 commits at every write, as the
  // writer of issue 32 did per frame. Only rank 0's policy matters.
  struct CommitPolicy {
    double intervalSeconds = 2.0;
    std::size_t maxBytes = std::size_t(4) << 20;
  };
  void setCommitPolicy(const CommitPolicy& policy);  // not collective; throws std::invalid_argument for < 0 s
  CommitPolicy commitPolicy() const;

  // Appends the next frame (buffered): a row of /frames/time and of each /frames/<body> dataset;
  // `frames` has one entry per body, in layout order.
  void writeFrame(double time, const std::vector<BodyFrame>& frames);
  // Appends `value` to /series/<name> (1-D), creating the dataset on first use (buffered: one
  // dataset extension and one write per series and block).
  void writeScalarSeries(const std::string& name, double value);
  // Appends `row` to /series/<name>, a 2-D dataset of rows x width, width = the first row's size;
  // every later row must have that size (else std::invalid_argument), and a scalar series' name
  // cannot be reused. Buffered as writeScalarSeries.
  void writeVectorSeries(const std::string& name, const std::vector<double>& row);
  // Commits whatever is buffered now (e.g. before a checkpoint, or to show a viewer the latest).
  void flush();
  // Writes /modes (once per run) and <stem>_modes.xmf; shapes[m] has one entry per body. With
  // residuals (one per mode): each mode group's attribute `relative_residual`; with labels, its
  // `label` and `label_share` (solvers/ModeLabels.hpp).
  struct ModeLabelOut {
    std::string name;
    double share = 0.0;
  };
  void writeModes(const std::vector<double>& frequenciesHz,
                  const std::vector<std::vector<BodyFrame>>& shapes, const std::vector<double>& residuals = {},
                  const std::vector<ModeLabelOut>& labels = {});
  // Root-group attributes; an existing attribute of the same name is replaced.
  void setAttribute(const std::string& name, double value);
  void setAttribute(const std::string& name, const std::string& value);
  // Commits the last block and closes the file; later calls to close() do nothing, other methods throw.
  void close();

  const std::string& path() const;
  std::string xdmfPath() const;       // <stem>.xdmf2 next to path()
  std::string modesXdmfPath() const;  // <stem>_modes.xmf next to path()
  int framesWritten() const;          // same value on all ranks

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strand::io
