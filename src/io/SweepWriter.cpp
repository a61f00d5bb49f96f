// HDF5 + CSV output of a parameter sweep (layout in include/strand/io/SweepWriter.hpp).
#include "strand/io/SweepWriter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "CommittedFile.hpp"
#include "Hdf5.hpp"

namespace strand::io {

namespace {

using namespace h5;

std::string siblingPath(const std::string& h5Path, const std::string& suffix) {
  const std::filesystem::path p(h5Path);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

size_t modeCount(const solvers::SweepResult& r) { return r.omegaBar.empty() ? 0 : r.omegaBar[0].size(); }

// Row-major P x n copy of a per-point, per-mode table (rows shorter than n are NaN-padded).
template <class T>
std::vector<T> table(const std::vector<std::vector<T>>& t, size_t n, T pad) {
  std::vector<T> out;
  for (const auto& row : t)
    for (size_t k = 0; k < n; ++k) out.push_back(k < row.size() ? row[k] : pad);
  return out;
}

void writeHdf5(const std::string& path, const SweepInfo& info, const solvers::SweepResult& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // one commit at the end (CommittedFile.hpp): a run killed while writing leaves no half file
  Hid fapl(committedFileAccess(), H5Pclose);
  Hid file(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "cannot create file"), H5Fclose);
  const hid_t f = file.get();
  const hsize_t P = r.parameter.size(), n = modeCount(r);
  writeAttribute(f, "strand_version", info.version);
  writeAttribute(f, "scene_file", info.sceneFile);
  writeAttribute(f, "analysis", std::string("sweep"));
  writeAttribute(f, "parameter", r.parameterName);
  writeAttribute(f, "method", r.method);
  writeAttribute(f, "status", std::string(!r.failure.empty() ? "failed" : r.stopped ? "stopped" : "ok"));
  writeAttribute(f, "failure", r.failure);
  writeAttribute(f, "wall_time_s", r.seconds);
  writeAttribute(f, "points", static_cast<int>(P));
  writeAttribute(f, "modes", static_cast<int>(n));
  writeAttribute(f, "dimension", info.dimension);
  writeAttribute(f, "max_real_part", r.maxRealPart);
  if (!std::isnan(r.criticalSpeed)) writeAttribute(f, "critical_speed", r.criticalSpeed);  // +inf: none

  Hid g = group(f, "sweep");
  writeArray(g.get(), "parameter", {P}, r.parameter.data());
  writeArray(g.get(), "gamma", {P}, r.gamma.data());
  writeArray(g.get(), "omega", {P, n}, table(r.omega, n, nan).data());
  writeArray(g.get(), "omega_bar", {P, n}, table(r.omegaBar, n, nan).data());
  writeArray(g.get(), "residual", {P, n}, table(r.residual, n, nan).data());
  std::vector<int> label = table(r.label, n, -1);
  label.resize(P * n, -1);  // tracking is skipped when the mode count varied
  writeArray(g.get(), "label", {P, n}, label.data());
  // what each sorted mode is (ModeLabels.hpp): codes into the attribute kind_names (-1: none)
  std::vector<std::string> names;
  std::vector<int> kindCode(P * n, -1);
  for (size_t i = 0; i < r.kind.size() && i < P; ++i)
    for (size_t k = 0; k < r.kind[i].size() && k < n; ++k) {
      const auto it = std::find(names.begin(), names.end(), r.kind[i][k]);
      kindCode[i * n + k] = static_cast<int>(it - names.begin());
      if (it == names.end()) names.push_back(r.kind[i][k]);
    }
  writeArray(g.get(), "kind", {P, n}, kindCode.data());
  std::string joined;
  for (const std::string& s : names) joined += (joined.empty() ? "" : ",") + s;
  writeAttribute(g.get(), "kind_names", joined);
  std::vector<double> loci;
  for (const auto& l : trackedLoci(r)) loci.insert(loci.end(), l.begin(), l.end());
  writeArray(g.get(), "loci_omega_bar", {loci.empty() ? 0 : n, loci.empty() ? 0 : P}, loci.data());
  std::vector<double> mac;
  for (const auto& m : r.macNext) {
    std::vector<double> row(m);
    row.resize(n * n, nan);
    mac.insert(mac.end(), row.begin(), row.end());
  }
  writeArray(g.get(), "mac", {P > 0 ? P - 1 : 0, n, n}, mac.data());

  // shapes: every stored shape has the same length (nodes x dim of body 0)
  const hsize_t dim = static_cast<hsize_t>(info.dimension);
  hsize_t len = 0;
  for (const auto& pt : r.shapes)
    for (const auto& s : pt) len = std::max<hsize_t>(len, s.size());
  std::vector<double> shapes;
  for (const auto& pt : r.shapes)
    for (hsize_t k = 0; k < n; ++k)
      for (hsize_t j = 0; j < len; ++j) shapes.push_back(k < pt.size() && j < pt[k].size() ? pt[k][j] : nan);
  writeArray(g.get(), "shapes", {P, n, len / dim, dim}, shapes.data());

  hsize_t maxNodes = 0;
  std::vector<int> count;
  for (const auto& pt : r.nodes)
    for (hsize_t k = 0; k < n; ++k) {
      count.push_back(k < pt.size() ? static_cast<int>(pt[k].size()) : 0);
      maxNodes = std::max<hsize_t>(maxNodes, count.back());
    }
  std::vector<double> nodes;
  for (const auto& pt : r.nodes)
    for (hsize_t k = 0; k < n; ++k)
      for (hsize_t j = 0; j < maxNodes; ++j) nodes.push_back(k < pt.size() && j < pt[k].size() ? pt[k][j] : nan);
  writeArray(g.get(), "node_count", {static_cast<hsize_t>(r.nodes.size()), n}, count.data());
  writeArray(g.get(), "nodes", {static_cast<hsize_t>(r.nodes.size()), n, maxNodes}, nodes.data());

  Hid ev = group(g.get(), "events");
  const hsize_t E = r.events.size();
  std::vector<int> kind, lower, point, shift, refined;
  std::vector<double> param, gap, freq, exch, mix;
  for (const auto& e : r.events) {
    kind.push_back(e.kind == "veering" ? 0 : 1);
    lower.push_back(e.lower);
    point.push_back(e.point);
    shift.push_back(e.modeShift ? 1 : 0);
    refined.push_back(e.refined ? 1 : 0);
    param.push_back(e.parameter);
    gap.push_back(e.gap);
    freq.push_back(e.frequency);
    exch.push_back(e.exchange);
    mix.push_back(e.mixing);
  }
  writeAttribute(ev.get(), "kind_names", std::string("0 = veering, 1 = crossing"));
  writeArray(ev.get(), "kind", {E}, kind.data());
  writeArray(ev.get(), "lower", {E}, lower.data());
  writeArray(ev.get(), "point", {E}, point.data());
  writeArray(ev.get(), "parameter", {E}, param.data());
  writeArray(ev.get(), "gap", {E}, gap.data());
  writeArray(ev.get(), "omega_bar", {E}, freq.data());
  writeArray(ev.get(), "exchange", {E}, exch.data());
  writeArray(ev.get(), "mixing", {E}, mix.data());
  writeArray(ev.get(), "mode_shift", {E}, shift.data());
  writeArray(ev.get(), "refined", {E}, refined.data());
  ev.close("cannot close group '/sweep/events'");
  g.close("cannot close group '/sweep'");
  check(H5Fflush(f, H5F_SCOPE_GLOBAL), "cannot flush");
  commit(f);
  file.close("cannot close");
}

void writeCsv(const std::string& path, const std::string& eventsPath, const solvers::SweepResult& r) {
  const size_t n = modeCount(r);
  const auto loci = trackedLoci(r);
  std::ofstream csv(path);
  csv.precision(12);
  csv << "point,parameter,gamma";
  for (size_t k = 0; k < n; ++k) csv << ",omega_bar_" << k + 1;
  for (size_t l = 0; l < loci.size(); ++l) csv << ",locus_" << l + 1;
  for (size_t k = 0; k < n; ++k) csv << ",kind_" << k + 1;
  csv << "\n";
  for (size_t i = 0; i < r.parameter.size(); ++i) {
    csv << i << "," << r.parameter[i] << "," << r.gamma[i];
    for (size_t k = 0; k < n; ++k) csv << "," << (k < r.omegaBar[i].size() ? r.omegaBar[i][k] : NAN);
    for (const auto& l : loci) csv << "," << l[i];
    for (size_t k = 0; k < n; ++k) csv << "," << (i < r.kind.size() && k < r.kind[i].size() ? r.kind[i][k] : "");
    csv << "\n";
  }
  std::ofstream ev(eventsPath);
  ev.precision(12);
  ev << "kind,lower_locus,upper_locus,point,parameter,gap_bar,omega_bar,exchange,mixing,mode_shift,refined\n";
  for (const auto& e : r.events)
    ev << e.kind << "," << e.lower + 1 << "," << e.lower + 2 << "," << e.point << "," << e.parameter << "," << e.gap
       << "," << e.frequency << "," << e.exchange << "," << e.mixing << "," << (e.modeShift ? 1 : 0) << ","
       << (e.refined ? 1 : 0) << "\n";
  if (!csv.flush() || !ev.flush()) throw std::runtime_error("cannot write the CSV summary next to '" + path + "'");
}

}  // namespace

std::string sweepCsvPath(const std::string& h5Path) { return siblingPath(h5Path, ".csv"); }
std::string sweepEventsCsvPath(const std::string& h5Path) { return siblingPath(h5Path, "_events.csv"); }

std::vector<std::vector<double>> trackedLoci(const solvers::SweepResult& r) {
  const size_t n = modeCount(r), P = r.omegaBar.size();
  if (r.label.size() != P) return {};
  std::vector<std::vector<double>> loci(n, std::vector<double>(P, std::numeric_limits<double>::quiet_NaN()));
  for (size_t i = 0; i < P; ++i)
    for (size_t k = 0; k < n && k < r.label[i].size(); ++k) {
      const int l = r.label[i][k];
      if (l >= 0 && static_cast<size_t>(l) < n) loci[l][i] = r.omegaBar[i][k];
    }
  return loci;
}

void writeSweep(MPI_Comm comm, const std::string& path, const SweepInfo& info, const solvers::SweepResult& r) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string message;
  if (rank == 0) {
    QuietHdf5 quiet;
    try {
      writeHdf5(path, info, r);
      writeCsv(sweepCsvPath(path), sweepEventsCsvPath(path), r);
    } catch (const std::exception& e) {
      message = "cannot write output file '" + path + "': " + e.what();
      if (message.empty()) message = "cannot write output file";
    }
  }
  int len = static_cast<int>(message.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  if (len == 0) return;
  message.resize(len);
  MPI_Bcast(message.data(), len, MPI_CHAR, 0, comm);
  throw std::runtime_error(message);
}

}  // namespace strand::io
