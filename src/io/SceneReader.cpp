// YAML scene -> model::SceneDescription. The format is documented key by key in
// docs/scene-reference.md; keep the two in step.
//
// Every value is read through a Field: the YAML node plus its dotted key path and line, so that
// each check can throw "<file>:<line>: <key>: <reason>" without passing places around by hand.
#include "strand/io/SceneReader.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "strand/core/Error.hpp"
#include "strand/elements/ElementRegistry.hpp"
#include "strand/model/InitialGeometry.hpp"

namespace strand::io {
namespace {

namespace fs = std::filesystem;
using model::BodyDesc;
using model::GeometryDesc;
using model::GeometryKind;
using model::NodeRef;
using model::SourceMark;
using model::Vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRelTol = 1e-12;  // "zero" for lengths and angles, relative to the coordinates
// Input files are read whole into memory: bounded. yaml-cpp keeps a few hundred bytes per scalar,
// so a 16 MB scene can take a few GB; a CSV row costs 24 bytes per point.
constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t(16) << 20;
constexpr std::uintmax_t kMaxPolylineBytes = std::uintmax_t(256) << 20;

// ------------------------------------------------------------------------------------------------
// Text and vector helpers

std::string fmt(double v, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// The kinds with material coordinates (ALE), for messages.
std::string aleKindNames() {
  std::vector<std::string> names;
  for (int k = 0; k < elements::kindCount(); ++k)
    if (elements::kindInfo(k).materialBlock() >= 0) names.push_back(elements::kindInfo(k).name);
  return join(names);
}

// The length of the UTF-8 sequence that starts at s[i] (1-4), or 0 if it is not valid UTF-8
// (overlong forms, surrogates and code points above U+10FFFF included).
size_t utf8Length(const std::string& s, size_t i) {
  const auto byte = [&](size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
  const unsigned c = byte(i);
  const auto cont = [&](size_t k) { return (byte(k) & 0xC0u) == 0x80u; };
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const unsigned c1 = byte(i + 1);
    if ((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 > 0x9F)) return 0;  // overlong, surrogate
    return cont(i + 1) && cont(i + 2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const unsigned c1 = byte(i + 1);
    if ((c == 0xF0 && c1 < 0x90) || (c == 0xF4 && c1 > 0x8F)) return 0;  // overlong, > U+10FFFF
    return cont(i + 1) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  }
  return 0;
}

// Empty when `s` is UTF-8 text without control characters, else the reason.
std::string textProblem(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const size_t n = utf8Length(s, i);
    char b[96];
    if (n == 0) {
      std::snprintf(b, sizeof b, "not UTF-8 text (byte 0x%02x at offset %zu)", static_cast<unsigned char>(s[i]), i);
      return b;
    }
    if (n == 1 && (static_cast<unsigned char>(s[i]) < 0x20 || s[i] == 0x7f)) {
      std::snprintf(b, sizeof b, "control character 0x%02x at offset %zu", static_cast<unsigned char>(s[i]), i);
      return b;
    }
    i += n;
  }
  return "";
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// A value as a message may show it: bytes that are not UTF-8 text or are control characters become
// \xNN, and anything beyond `max` characters is cut ("... (N bytes)"): an error message must not
// echo a 2 MB value (issue 32 item 10).
std::string printable(const std::string& s, size_t max = 60) {
  std::string out;
  size_t i = 0;
  while (i < s.size() && out.size() < max) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8Length(s, i);
    if (n == 0 || c < 0x20 || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      out += b;
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  if (i < s.size()) out += "... (" + std::to_string(s.size()) + " bytes)";
  return out;
}

// What a node holds, for "expected X (got Y)" messages.
std::string describe(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list";
  return "'" + printable(n.Scalar(), 40) + "'";
}

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

// True when the segment a-b has no length compared with the size of its coordinates.
bool zeroLength(const Vec3& a, const Vec3& b) {
  return norm(sub(b, a)) <= kRelTol * std::max(norm(a), norm(b));
}

// True when the unit vector `dir` is parallel to the (non-zero) chord a-b.
bool parallelToChord(const Vec3& dir, const Vec3& a, const Vec3& b) {
  const Vec3 chord = sub(b, a);
  return norm(cross(dir, scaled(chord, 1.0 / norm(chord)))) < 1e-9;
}

// Empty when `v` is a valid vector for a `dim`-dimensional scene, else the reason: exactly 3
// numbers in 3D; 2 or 3 numbers in 2D, the third one 0 (2D scenes live in the xy plane).
std::string vectorProblem(const std::vector<double>& v, int dim) {
  const std::string got = " (got " + std::to_string(v.size()) + ")";
  if (dim == 3 && v.size() != 3) return "expected 3 numbers" + got;
  if (dim == 2 && (v.size() < 2 || v.size() > 3)) return "expected 2 or 3 numbers" + got;
  if (v.size() == 3 && dim == 2 && v[2] != 0.0)
    return "the third number must be 0 in a 2D scene (got " + fmt(v[2]) + ")";
  return "";
}

Vec3 toVec3(const std::vector<double>& v) { return {v[0], v[1], v.size() > 2 ? v[2] : 0.0}; }

[[noreturn]] void failAt(const SourceMark& mark, const std::string& reason) {
  constexpr size_t kMax = 2000;  // the longest list of allowed keys is far shorter
  throw InputError(mark.where() + ": " + (reason.size() > kMax ? reason.substr(0, kMax) + "... (cut)" : reason));
}

// 1-based line of a node, or `fallback` when yaml-cpp does not know it.
int lineOf(const YAML::Node& n, int fallback) {
  if (!n.IsDefined()) return fallback;
  const int line = n.Mark().line;
  return line >= 0 ? line + 1 : fallback;
}

// ------------------------------------------------------------------------------------------------
// Field: a scene value with its place

class Field {
public:
  // `file` must outlive the Field. `line` is 1-based: where the key is, or for a missing key
  // where its parent is.
  Field(YAML::Node node, std::string key, const std::string& file, int line)
      : node_(std::move(node)), key_(std::move(key)), file_(&file), line_(line) {}

  bool present() const { return node_.IsDefined() && !node_.IsNull(); }
  bool isList() const { return present() && node_.IsSequence(); }
  bool isMap() const { return present() && node_.IsMap(); }
  bool isScalar(const char* text) const { return present() && node_.IsScalar() && node_.Scalar() == text; }
  const std::string& key() const { return key_; }
  int line() const { return line_; }
  SourceMark mark() const { return {*file_, line_, key_.empty() ? "(root)" : key_}; }
  [[noreturn]] void fail(const std::string& reason) const { failAt(mark(), reason); }

  // Checks that this is a map whose keys are all in `allowed`, each given once.
  void expectMap(const std::vector<std::string>& allowed) const {
    requireMap();
    std::map<std::string, int> seen;  // key -> line
    for (const auto& kv : node_) {
      const int line = lineOf(kv.first, line_);
      if (!kv.first.IsScalar()) failAt({*file_, line, mark().key}, "keys must be plain names");
      const std::string name = kv.first.Scalar();
      const Field here(kv.second, childKey(name), *file_, line);
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
        here.fail("unknown key; allowed: " + join(allowed));
      if (const auto [it, fresh] = seen.emplace(name, line); !fresh)
        here.fail("duplicate key (first given on line " + std::to_string(it->second) + ")");
    }
  }

  // The value under `name` in this map; a missing key gives a Field that is not present().
  Field child(const std::string& name) const {
    requireMap();
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == name)
        return Field(kv.second, childKey(name), *file_, lineOf(kv.first, line_));
    return Field(YAML::Node(), childKey(name), *file_, line_);
  }

  // The entries of this list.
  std::vector<Field> items() const {
    requirePresent();
    if (!node_.IsSequence()) fail("expected a list (got " + describe(node_) + ")");
    std::vector<Field> out;
    for (const auto& item : node_) {
      const std::string key = key_ + "[" + std::to_string(out.size()) + "]";
      out.emplace_back(item, key, *file_, lineOf(item, line_));
    }
    return out;
  }

  double number() const {
    const double v = scalarAs<double>("a number");
    if (!std::isfinite(v)) fail("must be a finite number (got " + describe(node_) + ")");
    return v;
  }
  // A decimal integer: yaml-cpp reads YAML 1.1's 010 as octal 8 and 0x10 as 16; a scene is
  // decimal, and a leading zero is refused rather than guessed (issue 32 item 10).
  long integer(const char* what = "an integer") const {
    const std::string t = scalarAs<std::string>(what);
    const std::string expected = std::string("expected ") + what + " (got " + describe(node_) + ")";
    const size_t sign = !t.empty() && (t[0] == '+' || t[0] == '-') ? 1 : 0;
    if (t.size() > sign + 1 && t[sign] == '0' && std::isdigit(static_cast<unsigned char>(t[sign + 1])))
      fail(expected + ": a leading 0 (YAML 1.1 reads " + printable(t, 20) + " as an octal number); write it without");
    long v = 0;
    const char* begin = t.data() + (sign == 1 && t[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(begin, t.data() + t.size(), v, 10);
    if (t.size() == sign || ec != std::errc() || end != t.data() + t.size()) fail(expected);
    return v;
  }
  bool boolean() const { return scalarAs<bool>("true or false"); }
  // Any text value: UTF-8 without control characters (names become HDF5 groups and XML, issue 32
  // item 10).
  std::string text() const {
    std::string t = scalarAs<std::string>("a string");
    if (const std::string problem = textProblem(t); !problem.empty()) fail(problem);
    return t;
  }

private:
  std::string childKey(const std::string& name) const {
    const std::string shown = printable(name, 60);
    return key_.empty() ? shown : key_ + "." + shown;
  }
  void requirePresent() const {
    if (!present()) fail("missing required value");
  }
  void requireMap() const {
    requirePresent();
    if (!node_.IsMap()) fail("expected a map (got " + describe(node_) + ")");
  }
  template <class T>
  T scalarAs(const char* what) const {
    requirePresent();
    const std::string expected = std::string("expected ") + what + " (got " + describe(node_) + ")";
    if (!node_.IsScalar()) fail(expected);
    try {
      return node_.as<T>();
    } catch (const YAML::Exception&) {
      fail(expected);
    }
  }

  YAML::Node node_;
  std::string key_;
  const std::string* file_;
  int line_;
};

// ------------------------------------------------------------------------------------------------
// Checked values

double requirePositive(const Field& f) {
  const double v = f.number();
  if (!(v > 0.0)) f.fail("must be positive (got " + fmt(v) + ")");
  return v;
}

double requireNonNegative(const Field& f) {
  const double v = f.number();
  if (v < 0.0) f.fail("must not be negative (got " + fmt(v) + ")");
  return v;
}

int requireIntInRange(const Field& f, long lo, long hi) {
  const long v = f.integer();
  if (v < lo || v > hi) {
    const std::string range = hi == INT_MAX  ? "at least " + std::to_string(lo)
                              : hi == lo + 1 ? std::to_string(lo) + " or " + std::to_string(hi)
                                             : std::to_string(lo) + ".." + std::to_string(hi);
    f.fail("must be " + range + " (got " + std::to_string(v) + ")");
  }
  return static_cast<int>(v);
}

int requireIntAtLeast(const Field& f, long lo) { return requireIntInRange(f, lo, INT_MAX); }

// The entry of `table` (anything with a `name` member) named by the string in `f`.
template <class Table>
const auto& pick(const Field& f, const char* what, const Table& table) {
  const std::string s = f.text();
  std::vector<std::string> names;
  for (const auto& entry : table) {
    if (s == entry.name) return entry;
    names.emplace_back(entry.name);
  }
  f.fail("unknown " + std::string(what) + " '" + printable(s) + "'; allowed: " + join(names));
}

// A position, force or direction (see vectorProblem).
Vec3 readVector(const Field& f, int dim) {
  std::vector<double> v;
  for (const Field& item : f.items()) v.push_back(item.number());
  if (const std::string problem = vectorProblem(v, dim); !problem.empty()) f.fail(problem);
  return toVec3(v);
}

// A non-zero vector, returned with unit length.
Vec3 readDirection(const Field& f, int dim) {
  const Vec3 v = readVector(f, dim);
  const double n = norm(v);
  if (n == 0.0) f.fail("must not be the zero vector");
  return scaled(v, 1.0 / n);
}

// A moment: 3 numbers in 3D. A 2D moment acts about z: a number Mz, or [0, 0, Mz].
Vec3 readMoment(const Field& f, int dim) {
  if (dim == 3) return readVector(f, 3);
  if (f.present() && !f.isList()) return {0.0, 0.0, f.number()};
  std::vector<double> v;
  for (const Field& item : f.items()) v.push_back(item.number());
  if (v.size() != 3 || v[0] != 0.0 || v[1] != 0.0)
    f.fail("a 2D moment acts about z: give a number Mz or [0, 0, Mz]");
  return toVec3(v);
}

// A time function (model/TimeFunction.hpp): a number (constant) or a map with `function`.
model::TimeFunction readTimeFunction(const Field& f) {
  using K = model::TimeFunction::Kind;
  model::TimeFunction tf;
  if (f.present() && !f.isList() && !f.isMap()) {
    tf.value = f.number();
    return tf;
  }
  const std::string kind = f.child("function").text();
  if (kind == "constant") {
    f.expectMap({"function", "value"});
    tf.value = f.child("value").number();
  } else if (kind == "linear") {
    f.expectMap({"function", "rate"});
    tf.kind = K::Linear;
    tf.rate = f.child("rate").number();
  } else if (kind == "ramp" || kind == "cosine_ramp") {
    f.expectMap({"function", "start", "end", "value"});
    tf.kind = kind == "ramp" ? K::Ramp : K::CosineRamp;
    tf.start = f.child("start").present() ? requireNonNegative(f.child("start")) : 0.0;
    tf.end = f.child("end").number();
    if (!(tf.end > tf.start)) f.child("end").fail("must be later than start (" + fmt(tf.start) + " s)");
    tf.value = f.child("value").number();
  } else if (kind == "sine") {
    f.expectMap({"function", "amplitude", "frequency", "phase"});
    tf.kind = K::Sine;
    tf.amplitude = f.child("amplitude").number();
    tf.frequency = requirePositive(f.child("frequency"));
    if (const Field ph = f.child("phase"); ph.present()) tf.phase = ph.number();
  } else if (kind == "spin_up") {
    f.expectMap({"function", "omega", "duration"});
    tf.kind = K::SpinUp;
    tf.omega = f.child("omega").number();
    tf.duration = requirePositive(f.child("duration"));
  } else if (kind == "table") {
    f.expectMap({"function", "time", "value"});
    tf.kind = K::Table;
    for (const Field& t : f.child("time").items()) tf.times.push_back(t.number());
    for (const Field& v : f.child("value").items()) tf.values.push_back(v.number());
    if (tf.times.size() < 2) f.child("time").fail("needs at least 2 points");
    if (tf.values.size() != tf.times.size())
      f.child("value").fail("needs one value per time (" + std::to_string(tf.times.size()) + ", got " +
                            std::to_string(tf.values.size()) + ")");
    for (size_t i = 1; i < tf.times.size(); ++i)
      if (!(tf.times[i] > tf.times[i - 1])) f.child("time").fail("times must increase (entry " + std::to_string(i) + ")");
  } else {
    f.child("function").fail("unknown time function '" + printable(kind) + "'; allowed: constant, linear, ramp, cosine_ramp, sine, spin_up, table");
  }
  return tf;
}

// ------------------------------------------------------------------------------------------------
// Choices

template <class E>
struct Choice {
  const char* name;
  E value;
};

const char* const kNoConstrainedModes =
    "modal analysis of rigid bodies and joints is not supported yet (analysis: modes and strand modes); use static "
    "or dynamic";

const Choice<model::Analysis> kAnalyses[] = {{"static", model::Analysis::Static},
                                             {"modes", model::Analysis::Modes},
                                             {"dynamic", model::Analysis::Dynamic}};

const Choice<model::Integrator> kIntegrators[] = {{"generalized_alpha", model::Integrator::GeneralizedAlpha},
                                                  {"newmark", model::Integrator::Newmark},
                                                  {"hht", model::Integrator::Hht},
                                                  {"bdf", model::Integrator::Bdf},
                                                  {"rk4", model::Integrator::Rk4},
                                                  {"abm4", model::Integrator::Abm4}};

const Choice<model::DynamicsDesc::ConstraintForm> kConstraintForms[] = {
    {"ggl", model::DynamicsDesc::ConstraintForm::Ggl}, {"index3", model::DynamicsDesc::ConstraintForm::Index3}};
const Choice<model::JointType> kJointTypes[] = {{"pin", model::JointType::Pin},
                                                 {"revolute", model::JointType::Pin},
                                                 {"spherical", model::JointType::Pin},
                                                 {"distance", model::JointType::Distance},
                                                 {"clamp", model::JointType::Clamp}};
const Choice<model::SupportType> kSupportTypes[] = {{"clamped", model::SupportType::Clamped},
                                                    {"clamped_unstretched", model::SupportType::ClampedUnstretched},
                                                    {"pinned", model::SupportType::Pinned},
                                                    {"fixed", model::SupportType::Fixed},
                                                    {"sliding", model::SupportType::Sliding}};

const Choice<model::ModalMethod> kModalMethods[] = {{"auto", model::ModalMethod::Auto},
                                                    {"eps", model::ModalMethod::Eps},
                                                    {"pep", model::ModalMethod::Pep},
                                                    {"projected", model::ModalMethod::Projected}};

const Choice<model::SweepParameter> kSweepParameters[] = {{"gamma", model::SweepParameter::Gamma},
                                                          {"omega", model::SweepParameter::Omega},
                                                          {"mass_ratio", model::SweepParameter::MassRatio},
                                                          {"mass_location", model::SweepParameter::MassLocation},
                                                          {"transport_speed", model::SweepParameter::TransportSpeed}};

const Choice<bool> kStressFree[] = {{"straight", false}, {"initial", true}};

// hub_beam (seed 001): coupling and deformation methods; each method allows only its own keys under
// hub_beam.discretization (plus `method`).
const Choice<model::HubBeamCoupling> kHubBeamCouplings[] = {{"first_order", model::HubBeamCoupling::FirstOrder},
                                                            {"zero_order", model::HubBeamCoupling::ZeroOrder}};

const Choice<bool> kRpimSupports[] = {{"cell", true}, {"point", false}};

struct HubBeamMethodInfo {
  const char* name;
  model::HubBeamMethod value;
  std::vector<std::string> keys;
};
const HubBeamMethodInfo kHubBeamMethods[] = {
    {"fem", model::HubBeamMethod::Fem, {"elements"}},
    {"modes", model::HubBeamMethod::AssumedModes, {"axial_modes", "bending_modes"}},
    {"rpim", model::HubBeamMethod::Rpim, {"nodes", "alpha_c", "q", "alpha_s", "gauss_points", "support"}},
};

// hub_beam.beam: all required, positive.
struct HubBeamKey {
  const char* name;
  double model::HubBeamDesc::*field;
};
const HubBeamKey kHubBeamBeamKeys[] = {{"length", &model::HubBeamDesc::length},
                                       {"E", &model::HubBeamDesc::E},
                                       {"A", &model::HubBeamDesc::A},
                                       {"I", &model::HubBeamDesc::I},
                                       {"rho", &model::HubBeamDesc::rho}};

// Top-level keys of the cable scenes that a hub_beam scene has no use for.
const char* const kNotInHubBeamScenes[] = {"bodies", "rigid_bodies", "joints", "supports", "junctions", "loads",
                                           "rotation", "sweep", "modes", "static", "discretization", "probes"};

// ------------------------------------------------------------------------------------------------
// Geometry

struct Context {
  std::string file;   // for messages
  fs::path sceneDir;  // polyline CSV files are relative to it
  int dim = 3;
  std::vector<std::string>* inputs = nullptr;  // SceneDescription::inputFiles: every file read
  const std::vector<model::PulleyDesc>* pulleys = nullptr;  // what a wrap path turns around
};

void readLine(const Field& f, const Context& ctx, GeometryDesc& g) {
  g.start = readVector(f.child("start"), ctx.dim);
  g.end = readVector(f.child("end"), ctx.dim);
  if (zeroLength(g.start, g.end)) f.child("end").fail("must differ from start (zero length)");
}

void readArc(const Field& f, const Context& ctx, GeometryDesc& g) {
  g.center = readVector(f.child("center"), ctx.dim);
  g.radius = requirePositive(f.child("radius"));
  g.startAngle = f.child("start_angle").number();
  g.endAngle = f.child("end_angle").number();
  const double sweep = std::abs(g.endAngle - g.startAngle);
  const double scale = std::max({1.0, std::abs(g.startAngle), std::abs(g.endAngle)});
  if (sweep <= kRelTol * scale) f.child("end_angle").fail("must differ from start_angle (zero-length arc)");
  if (sweep > 2.0 * kPi * (1.0 + kRelTol))
    f.child("end_angle")
        .fail("the arc turns more than once (|end_angle - start_angle| = " + fmt(sweep) + " > 2*pi)");
  if (const Field normal = f.child("normal"); normal.present()) {
    if (ctx.dim != 3) normal.fail("only allowed when dimension is 3 (2D arcs lie in the xy plane)");
    g.normal = readDirection(normal, 3);
  }
}

// Polyline points from a CSV file: rows "x,y" or "x,y,z"; '#' starts a comment; blank lines are
// skipped. Returns the 1-based CSV line of each point.
std::vector<int> readPolylineCsv(const Field& f, const Context& ctx, std::vector<Vec3>& points) {
  fs::path path = f.text();
  if (path.is_relative()) path = ctx.sceneDir / path;
  std::ifstream in(path);
  if (!in || fs::is_directory(path)) f.fail("cannot open polyline file '" + path.string() + "'");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) f.fail("'" + path.string() + "' is not a regular file");
  if (const auto size = fs::file_size(path, ec); ec || size > kMaxPolylineBytes)
    f.fail("'" + path.string() + "' has " + std::to_string(size) + " bytes, more than a polyline file may have (" +
           std::to_string(kMaxPolylineBytes >> 20) + " MB)");
  if (ctx.inputs) ctx.inputs->push_back(path.string());
  std::vector<int> lines;
  std::string row;
  for (int lineNo = 1; std::getline(in, row); ++lineNo) {
    row = trim(row.substr(0, row.find('#')));
    if (row.empty()) continue;
    const std::string where = "'" + path.string() + "' line " + std::to_string(lineNo) + ": ";
    std::vector<double> v;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',');) {
      cell = trim(cell);
      double x = 0.0;
      const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
      if (cell.empty() || ec != std::errc() || end != cell.data() + cell.size() || !std::isfinite(x))
        f.fail(where + "expected comma-separated numbers x,y or x,y,z (got '" + printable(row) + "')");
      v.push_back(x);
    }
    if (const std::string problem = vectorProblem(v, ctx.dim); !problem.empty()) f.fail(where + problem);
    points.push_back(toVec3(v));
    lines.push_back(lineNo);
  }
  return lines;
}

void readPolyline(const Field& f, const Context& ctx, GeometryDesc& g) {
  const Field points = f.child("points"), file = f.child("file");
  if (points.present() && file.present()) file.fail("give either points or file, not both");
  if (file.present()) {
    const std::vector<int> lines = readPolylineCsv(file, ctx, g.points);
    if (g.points.size() < 2)
      file.fail("needs at least 2 points (got " + std::to_string(g.points.size()) + ")");
    for (size_t i = 0; i + 1 < g.points.size(); ++i)
      if (zeroLength(g.points[i], g.points[i + 1]))
        file.fail("zero-length segment between lines " + std::to_string(lines[i]) + " and " +
                  std::to_string(lines[i + 1]) + " of the file");
    return;
  }
  if (!points.present()) points.fail("missing required value (give points or file)");
  const std::vector<Field> items = points.items();
  if (items.size() < 2) points.fail("needs at least 2 points (got " + std::to_string(items.size()) + ")");
  for (const Field& item : items) g.points.push_back(readVector(item, ctx.dim));
  for (size_t i = 0; i + 1 < g.points.size(); ++i)
    if (zeroLength(g.points[i], g.points[i + 1]))
      items[i + 1].fail("zero-length segment (same point as " + items[i].key() + ")");
}

void readCatenary(const Field& f, const Context& ctx, GeometryDesc& g) {
  g.start = readVector(f.child("start"), ctx.dim);
  g.end = readVector(f.child("end"), ctx.dim);
  if (zeroLength(g.start, g.end)) f.child("end").fail("must differ from start (zero span)");
  const Field length = f.child("length");
  g.length = requirePositive(length);
  const double span = norm(sub(g.end, g.start));
  if (g.length <= span)
    length.fail("must exceed the distance between start and end (length " + fmt(g.length, 10) +
                " <= distance " + fmt(span, 10) + ")");
  if (const Field sag = f.child("sag_direction"); sag.present()) {
    g.sagDirection = readDirection(sag, ctx.dim);
    if (parallelToChord(g.sagDirection, g.start, g.end))
      sag.fail("must not be parallel to the line from start to end");
  }
}

// wrap (2D): start, end, around: [{pulley, sense: cw | ccw, turns}], offset (the path's distance
// from each pulley's surface: half the belt's height).
void readWrap(const Field& f, const Context& ctx, GeometryDesc& g) {
  if (ctx.dim != 2) f.child("kind").fail("a wrap path lies in the xy plane: only when dimension is 2");
  if (const Field c = f.child("closed"); c.present()) g.closed = c.boolean();
  if (g.closed) {
    for (const char* key : {"start", "end"})
      if (const Field k = f.child(key); k.present()) k.fail("a closed path has no ends: leave out start and end");
  } else {
    g.start = readVector(f.child("start"), ctx.dim);
    g.end = readVector(f.child("end"), ctx.dim);
  }
  double offset = 0.0;
  if (const Field o = f.child("offset"); o.present()) offset = requireNonNegative(o);
  const std::vector<Field> around = f.child("around").items();
  if (around.empty()) f.child("around").fail("needs at least one pulley");
  if (g.closed && around.size() < 2) f.child("around").fail("a closed path goes around at least two pulleys");
  for (const Field& item : around) {
    item.expectMap({"pulley", "sense", "turns"});
    const Field name = item.child("pulley");
    const std::string wanted = name.text();
    const model::PulleyDesc* pulley = nullptr;
    std::vector<std::string> names;
    for (const model::PulleyDesc& p : *ctx.pulleys) {
      if (p.name == wanted) pulley = &p;
      names.push_back(p.name);
    }
    if (!pulley)
      name.fail("no pulley named '" + printable(wanted) + "'" + (names.empty() ? " (the scene has no pulleys)" : "; pulleys: " + join(names)));
    model::WrapTurn w;
    w.center = pulley->center;
    w.radius = pulley->radius + offset;
    const Field sense = item.child("sense");
    const std::string sn = sense.text();
    if (sn != "cw" && sn != "ccw") sense.fail("expected cw or ccw (the sense in which the path goes around the pulley)");
    w.sense = sn == "ccw" ? 1 : -1;
    if (const Field t = item.child("turns"); t.present()) w.turns = requireIntInRange(t, 0, 1000);
    g.wrap.push_back(w);
  }
}

struct GeometryKindInfo {
  const char* name;
  GeometryKind value;
  std::vector<std::string> keys;  // allowed keys for this kind
  void (*read)(const Field&, const Context&, GeometryDesc&);
};
const GeometryKindInfo kGeometryKinds[] = {
    {"line", GeometryKind::Line, {"kind", "start", "end"}, readLine},
    {"arc", GeometryKind::Arc, {"kind", "center", "radius", "start_angle", "end_angle", "normal"}, readArc},
    {"polyline", GeometryKind::Polyline, {"kind", "points", "file"}, readPolyline},
    {"catenary", GeometryKind::Catenary, {"kind", "start", "end", "length", "sag_direction"}, readCatenary},
    {"wrap", GeometryKind::Wrap, {"kind", "start", "end", "around", "offset", "closed"}, readWrap},
};

GeometryDesc readGeometry(const Field& f, const Context& ctx) {
  GeometryDesc g;
  g.mark = f.mark();
  const GeometryKindInfo& kind = pick(f.child("kind"), "geometry kind", kGeometryKinds);
  f.expectMap(kind.keys);
  g.kind = kind.value;
  kind.read(f, ctx, g);
  if (g.kind == GeometryKind::Wrap) (void)model::InitialGeometry(g, ctx.dim, {});  // tangents exist (else InputError)
  return g;
}

// Length of the body's centerline in its initial shape [m].
double bodyLength(const GeometryDesc& g) {
  switch (g.kind) {
    case GeometryKind::Line: return norm(sub(g.end, g.start));
    case GeometryKind::Arc: return g.radius * std::abs(g.endAngle - g.startAngle);
    case GeometryKind::Catenary: return g.length;
    case GeometryKind::Wrap: return model::InitialGeometry(g, 2, {}).length();
    case GeometryKind::Polyline: {
      double sum = 0.0;
      for (size_t i = 0; i + 1 < g.points.size(); ++i) sum += norm(sub(g.points[i + 1], g.points[i]));
      return sum;
    }
  }
  return 0.0;
}

// ------------------------------------------------------------------------------------------------
// Bodies

// The kind's section keys (numbers, in their ranges) and formulation options (a value of each
// option's list; the first is the default).
void readSection(const Field& f, const elements::KindInfo& kind, BodyDesc& body) {
  std::vector<std::string> keys;
  for (int k = 0; k < kind.sectionKeyCount; ++k) keys.emplace_back(kind.sectionKeys[k].name);
  f.expectMap(keys);
  for (int k = 0; k < kind.sectionKeyCount; ++k) {
    const elements::SectionKey& key = kind.sectionKeys[k];
    const Field value = f.child(key.name);
    if (!value.present() && !key.required) {
      body.section.set(key.name, key.fallback);
      continue;
    }
    if (key.required && !key.lowerClosed && key.lower == 0.0 && key.upper == elements::kNoLimit) {
      body.section.set(key.name, requirePositive(value));
      continue;
    }
    if (!key.required && key.lowerClosed && key.lower == 0.0 && key.upper == elements::kNoLimit) {
      body.section.set(key.name, requireNonNegative(value));
      continue;
    }
    const double v = value.number();
    const bool above = key.lowerClosed ? v >= key.lower : v > key.lower;
    if (!above || !(v < key.upper))
      value.fail("must be in " + std::string(key.lowerClosed ? "[" : "(") + fmt(key.lower) + ", " + fmt(key.upper) +
                 ") (got " + fmt(v) + ")");
    body.section.set(key.name, v);
  }
}

void readFormulation(const Field& f, const elements::KindInfo& kind, BodyDesc& body) {
  for (int k = 0; k < kind.optionCount; ++k) body.section.options[kind.options[k].name] = kind.options[k].values[0];
  if (!f.present()) return;
  std::vector<std::string> keys;
  for (int k = 0; k < kind.optionCount; ++k) keys.emplace_back(kind.options[k].name);
  if (keys.empty()) f.fail(std::string(kind.name) + " has no formulation options");
  f.expectMap(keys);
  for (int k = 0; k < kind.optionCount; ++k) {
    const elements::OptionKey& option = kind.options[k];
    const Field value = f.child(option.name);
    if (!value.present()) continue;
    const std::string text = value.text();
    std::vector<std::string> allowed;
    for (int v = 0; v < elements::OptionKey::kMaxValues && option.values[v]; ++v) allowed.emplace_back(option.values[v]);
    if (std::find(allowed.begin(), allowed.end(), text) == allowed.end())
      value.fail("unknown " + std::string(option.name) + " '" + text + "'; allowed: " + join(allowed));
    body.section.options[option.name] = text;
  }
}

// Point masses: position `at` [m] or `location` (fraction of the body length, seed 003's beta);
// size `mass` [kg] or `mass_ratio` (mass / (rho A L), seed 003's alpha).
void readPointMasses(const Field& f, BodyDesc& body) {
  const double length = bodyLength(body.geometry);
  for (const Field& item : f.items()) {
    item.expectMap({"at", "location", "mass", "mass_ratio"});
    model::PointMassDesc pm;
    pm.mark = item.mark();
    const Field at = item.child("at"), location = item.child("location");
    if (at.present() == location.present()) item.fail("give exactly one of 'at' [m] and 'location' (at / L)");
    if (at.present()) {
      pm.at = at.number();
      if (pm.at < 0.0 || pm.at > length * (1.0 + kRelTol))
        at.fail("must be within [0, " + fmt(length) + "], the length of body '" + body.name + "' (got " +
                fmt(pm.at) + ")");
    } else {
      const double beta = location.number();
      if (beta < 0.0 || beta > 1.0) location.fail("must be within [0, 1] (got " + fmt(beta) + ")");
      pm.at = beta * length;
    }
    const Field mass = item.child("mass"), ratio = item.child("mass_ratio");
    if (mass.present() == ratio.present()) item.fail("give exactly one of 'mass' [kg] and 'mass_ratio' (mass / (rho A L))");
    const double rhoA = elements::kindInfo(body.kind).properties(body.section).rhoA;
    pm.mass = mass.present() ? requirePositive(mass) : requirePositive(ratio) * rhoA * length;
    body.pointMasses.push_back(pm);
  }
}


// material_nodes of an ALE body: [{node, at, motion}], nodes distinct, their arc lengths rising
// with the node index between the body's ends (the nodes between stay equally spaced in material).
void readMaterialNodes(const Field& f, BodyDesc& body) {
  const double length = bodyLength(body.geometry);
  std::vector<std::pair<long, double>> anchors = {{0, 0.0}, {body.elements, length}};
  for (const Field& item : f.items()) {
    item.expectMap({"node", "at", "motion"});
    model::MaterialNodeDesc m;
    m.mark = item.mark();
    const Field node = item.child("node");
    if (node.isScalar("last")) m.node = -1;
    else {
      m.node = node.integer("a node index or 'last'");
      if (m.node < 0 || m.node > body.elements)
        node.fail("node index out of range: the body has nodes 0.." + std::to_string(body.elements) + " or 'last'");
    }
    const long n = m.node < 0 ? body.elements : m.node;
    for (const model::MaterialNodeDesc& other : body.materialNodes)
      if ((other.node < 0 ? body.elements : other.node) == n) node.fail("node " + std::to_string(n) + " is listed twice");
    if (const Field at = item.child("at"); at.present()) {
      m.hasAt = true;
      m.at = at.number();
      if (!(m.at >= 0.0 && m.at <= length))
        at.fail("an arc length on the body's geometry, 0.." + fmt(length) + " m (got " + fmt(m.at) + ")");
    }
    if (const Field motion = item.child("motion"); motion.present()) {
      m.hasMotion = true;
      m.motion = readTimeFunction(motion);
    }
    const double arc = m.hasAt ? m.at : length * n / body.elements;
    if (n == 0 || n == body.elements) anchors[n == 0 ? 0 : 1].second = arc;
    else anchors.push_back({n, arc});
    body.materialNodes.push_back(m);
  }
  std::sort(anchors.begin(), anchors.end());
  for (size_t k = 0; k + 1 < anchors.size(); ++k)
    if (!(anchors[k + 1].second > anchors[k].second))
      f.fail("the nodes' arc lengths must rise with the node index (node " + std::to_string(anchors[k].first) + " at " +
             fmt(anchors[k].second) + " m, node " + std::to_string(anchors[k + 1].first) + " at " +
             fmt(anchors[k + 1].second) + " m)");
}

BodyDesc readBody(const Field& f, const Context& ctx) {
  f.expectMap({"name", "element", "elements", "geometry", "section", "formulation", "stress_free", "point_masses",
               "initial_velocity", "material_motion", "payout", "initial_stretch", "material_nodes"});
  BodyDesc body;
  body.mark = f.mark();
  const Field name = f.child("name");
  body.name = name.text();
  if (body.name.empty()) name.fail("must not be empty");

  const Field element = f.child("element");
  const std::string kindName = element.text();
  body.kind = elements::findKind(kindName);
  if (body.kind < 0) element.fail("unknown element type '" + printable(kindName) + "'; allowed: " + join(elements::kindNames()));
  const elements::KindInfo& kind = elements::kindInfo(body.kind);
  if (kind.dim != ctx.dim)
    element.fail(std::string(kind.name) + " needs dimension: " + std::to_string(kind.dim) +
                 " (dimension mismatch: the scene has dimension: " + std::to_string(ctx.dim) + ")");
  body.elements = requireIntAtLeast(f.child("elements"), 1);
  body.geometry = readGeometry(f.child("geometry"), ctx);
  readSection(f.child("section"), kind, body);
  readFormulation(f.child("formulation"), kind, body);

  if (const Field stressFree = f.child("stress_free"); stressFree.present()) {
    body.stressFreeInitial = pick(stressFree, "stress_free", kStressFree).value;
    if (body.stressFreeInitial && !kind.stressFreeInitial)
      stressFree.fail(std::string("'initial' is not available for ") + kind.name +
                      (ctx.dim != 2 ? " ('initial' is only allowed when dimension is 2)" : " (its stress-free shape is straight)"));
  }
  if (const Field masses = f.child("point_masses"); masses.present()) {
    if (!kind.constantMass) masses.fail(std::string("point masses on ") + kind.name + " bodies are not built yet");
    readPointMasses(masses, body);
  }
  const bool ale = kind.materialBlock() >= 0;
  for (const char* key : {"material_motion", "payout", "material_nodes"})
    if (const Field k = f.child(key); k.present() && !ale)
      k.fail(std::string(kind.name) + " has no material coordinates (an ALE kind has: " + aleKindNames() + ")");
  if (const Field motion = f.child("material_motion"); motion.present()) {
    body.hasMaterialMotion = true;
    body.materialMotion = readTimeFunction(motion);
  }
  if (const Field payout = f.child("payout"); payout.present()) {
    if (body.hasMaterialMotion) payout.fail("give either 'material_motion' (transport) or 'payout', not both");
    body.hasPayout = true;
    body.payout = readTimeFunction(payout);
  }
  if (const Field stretch = f.child("initial_stretch"); stretch.present()) {
    if (!kind.initialStretch) stretch.fail(std::string("a pretensioned initial state of ") + kind.name + " is not built yet");
    body.initialStretch = requirePositive(stretch);
  }
  if (const Field nodes = f.child("material_nodes"); nodes.present()) {
    if (body.hasMaterialMotion || body.hasPayout)
      nodes.fail("give either 'material_nodes' or 'material_motion' / 'payout', not both");
    readMaterialNodes(nodes, body);
  }
  if (const Field v = f.child("initial_velocity"); v.present()) {
    v.expectMap({"linear", "angular", "center"});
    body.hasInitialVelocity = true;
    if (const Field lin = v.child("linear"); lin.present()) body.linearVelocity = readVector(lin, ctx.dim);
    if (const Field ang = v.child("angular"); ang.present()) {
      if (ctx.dim == 2) body.angularVelocity[2] = ang.number();
      else body.angularVelocity = readVector(ang, 3);
    }
    if (const Field c = v.child("center"); c.present()) body.velocityCenter = readVector(c, ctx.dim);
  }
  return body;
}

// ------------------------------------------------------------------------------------------------
// The scene

class SceneParser {
public:
  explicit SceneParser(const std::string& file) : ctx_{file, fs::path(file).parent_path(), 3} {
    scene_.file = file;
    ctx_.inputs = &scene_.inputFiles;
    ctx_.pulleys = &scene_.pulleys;
  }

  model::SceneDescription parse(const YAML::Node& rootNode) {
    const Field root(rootNode, "", ctx_.file, lineOf(rootNode, 1));
    if (!root.present()) root.fail("the scene is empty; expected a map of scene keys");
    root.expectMap({"analysis", "dimension", "discretization", "bodies", "rigid_bodies", "joints", "supports",
                    "junctions", "loads", "static", "modes", "rotation", "sweep", "dynamics", "output", "hub_beam",
                    "probes", "pulleys", "contact", "reels"});
    scene_.analysis = pick(root.child("analysis"), "analysis", kAnalyses).value;
    scene_.analysisMark = root.child("analysis").mark();
    if (scene_.analysis == model::Analysis::Modes &&
        (root.child("rigid_bodies").present() || root.child("joints").present()))
      failAt(scene_.analysisMark, kNoConstrainedModes);  // before their own checks: as `strand modes` says
    if (const Field f = root.child("hub_beam"); f.present()) return parseHubBeamScene(root, f);
    scene_.dimension = ctx_.dim = requireIntInRange(root.child("dimension"), 2, 3);
    if (const Field f = root.child("discretization"); f.present()) readDiscretization(f);
    if (const Field f = root.child("pulleys"); f.present()) readPulleys(f);
    const Field rigid = root.child("rigid_bodies");
    readBodies(root.child("bodies"), rigid.present());
    if (rigid.present()) readRigidBodies(rigid);
    if (const Field f = root.child("joints"); f.present()) readJoints(f);

    if (const Field f = root.child("supports"); f.present()) readSupports(f);
    if (const Field f = root.child("reels"); f.present()) readReels(f);
    if (const Field f = root.child("junctions"); f.present()) readJunctions(f);
    if (const Field f = root.child("loads"); f.present()) readLoads(f);
    if (const Field f = root.child("static"); f.present()) {
      f.expectMap({"load_steps"});
      if (const Field steps = f.child("load_steps"); steps.present())
        scene_.statics.loadSteps = requireIntAtLeast(steps, 1);
    }
    if (const Field f = root.child("modes"); f.present()) readModes(f);
    if (const Field f = root.child("rotation"); f.present()) readRotation(f);
    if (const Field f = root.child("sweep"); f.present()) readSweep(f);
    if (const Field f = root.child("dynamics"); f.present()) readDynamics(f);
    for (size_t b = 0; b < scene_.bodies.size(); ++b) {  // kinds whose mass changes with their coordinates
      const elements::KindInfo& kind = elements::kindInfo(scene_.bodies[b].kind);
      if (kind.constantMass) continue;
      if (scene_.rotation.present)
        root.child("rotation").fail(std::string("a rotating frame with ") + kind.name + " bodies is not built");
      if (scene_.analysis == model::Analysis::Dynamic && model::isFirstOrder(scene_.dynamics.integrator))
        root.child("dynamics").child("integrator").fail(
            std::string(kind.name) + " (body '" + scene_.bodies[b].name + "') has a mass that changes with its material "
            "coordinates: use generalized_alpha, newmark or hht");
      // modes linearize about the steady flow at material_motion's rate at t = 0 (ModalSolver.hpp)
      bool nodesMove = false;
      for (const model::MaterialNodeDesc& m : scene_.bodies[b].materialNodes) nodesMove = nodesMove || m.hasMotion;
      if (scene_.analysis != model::Analysis::Dynamic && nodesMove)
        failAt(scene_.bodies[b].mark, "material_nodes with a motion move in time: only with analysis: dynamic");
      // static with material_motion: the state of the steady flow at its rate at t = 0 (StaticSolver)
      if (scene_.analysis != model::Analysis::Dynamic && scene_.bodies[b].hasPayout)
        failAt(scene_.bodies[b].mark, "payout is a motion in time: only with analysis: dynamic");
    }
    if (scene_.analysis == model::Analysis::Dynamic) {
      if (!root.child("dynamics").present())
        root.child("analysis").fail("analysis 'dynamic' needs a 'dynamics' section (dt, t_end)");
      if (scene_.rotation.present)
        root.child("rotation").fail("a rotating frame is not supported in dynamic analysis; prescribe the motion instead");
    } else {
      for (const model::SupportDesc& s : scene_.supports)
        if (s.hub.present) failAt(s.hub.mark, "a turning hub is a motion in time: only with analysis: dynamic");
    }
    if (const Field f = root.child("output"); f.present()) readOutput(f);
    if (const Field f = root.child("probes"); f.present()) readProbes(f);
    if (const Field f = root.child("contact"); f.present()) readContacts(f);
    else if (const Field p = root.child("pulleys"); p.present()) p.fail("pulleys act through contact: add a 'contact' entry for the body that touches them");
    checkCatenaryDefaults();
    checkOutputNames();
    checkRepresentable();
    if (!scene_.sweep.present) scene_.sweep.mark = {ctx_.file, root.line(), "sweep"};  // `strand sweep` names it
    return scene_;
  }

private:
  // A hub_beam scene (seed 001): the hub-beam model alone, in 2D, in time. Only `analysis`,
  // `dimension` (2 if given), `dynamics` (required) and `output` go with it.
  model::SceneDescription parseHubBeamScene(const Field& root, const Field& hubBeam) {
    for (const char* key : kNotInHubBeamScenes)
      if (const Field f = root.child(key); f.present())
        f.fail("a hub_beam scene has no '" + std::string(key) + "'; the beam is described under hub_beam");
    const Field analysis = root.child("analysis");
    if (scene_.analysis != model::Analysis::Dynamic)
      analysis.fail("a hub_beam scene is integrated in time: use analysis: dynamic (got '" + analysis.text() + "')");
    if (const Field dim = root.child("dimension"); dim.present()) {
      const long d = dim.integer();
      if (d != 2)
        dim.fail("a hub_beam turns in its plane: dimension must be 2 or left out (got " + std::to_string(d) + ")");
    }
    scene_.dimension = ctx_.dim = 2;
    readHubBeam(hubBeam);
    const Field dynamics = root.child("dynamics");
    if (!dynamics.present()) analysis.fail("analysis 'dynamic' needs a 'dynamics' section (dt, t_end)");
    readDynamics(dynamics);  // no joints: every integrator is allowed
    if (const Field f = root.child("output"); f.present()) readOutput(f);
    return scene_;
  }

  void readHubBeam(const Field& f) {
    f.expectMap({"beam", "hub", "coupling", "discretization"});
    model::HubBeamDesc& h = scene_.hubBeam;
    h.present = true;
    h.mark = f.mark();

    const Field beam = f.child("beam");
    std::vector<std::string> beamKeys;
    for (const HubBeamKey& k : kHubBeamBeamKeys) beamKeys.emplace_back(k.name);
    beam.expectMap(beamKeys);
    for (const HubBeamKey& k : kHubBeamBeamKeys) h.*k.field = requirePositive(beam.child(k.name));
    checkSection(beam.mark(), {h.E * h.A, h.E * h.I, h.rho * h.A}, h.length);

    readHubBeamHub(f.child("hub"), h);
    if (const Field c = f.child("coupling"); c.present()) h.coupling = pick(c, "coupling", kHubBeamCouplings).value;
    if (const Field d = f.child("discretization"); d.present()) readHubBeamDiscretization(d, h);
  }

  // hub: radius, and either angle (driven) or inertia with torque and rate (free).
  static void readHubBeamHub(const Field& f, model::HubBeamDesc& h) {
    f.expectMap({"radius", "angle", "inertia", "torque", "rate"});
    if (const Field r = f.child("radius"); r.present()) h.hubRadius = requireNonNegative(r);
    const Field angle = f.child("angle"), inertia = f.child("inertia");
    if (angle.present() == inertia.present())
      f.fail("give exactly one of 'angle' (a driven hub: its angle in time) and 'inertia' (a free hub) [kg m^2]");
    h.driven = angle.present();
    if (h.driven) {
      for (const char* key : {"torque", "rate"})
        if (const Field k = f.child(key); k.present())
          k.fail("only for a free hub (with 'inertia'); a driven hub's motion is prescribed by 'angle'");
      h.angle = readTimeFunction(angle);
      return;
    }
    h.hubInertia = requirePositive(inertia);
    if (const Field t = f.child("torque"); t.present()) h.torque = readTimeFunction(t);
    if (const Field r = f.child("rate"); r.present()) h.initialRate = r.number();
  }

  // discretization: method (default fem) and the keys of that method only.
  static void readHubBeamDiscretization(const Field& f, model::HubBeamDesc& h) {
    std::vector<std::string> keys{"method"};
    for (const HubBeamMethodInfo& m : kHubBeamMethods) keys.insert(keys.end(), m.keys.begin(), m.keys.end());
    f.expectMap(keys);
    const Field method = f.child("method");
    const HubBeamMethodInfo& m = method.present() ? pick(method, "method", kHubBeamMethods) : kHubBeamMethods[0];
    h.method = m.value;
    for (const HubBeamMethodInfo& other : kHubBeamMethods)
      if (other.value != m.value)
        for (const std::string& key : other.keys)
          if (const Field k = f.child(key); k.present())
            k.fail("'" + key + "' is a key of method " + other.name + " (the method here is " + m.name + ")");
    switch (h.method) {
      case model::HubBeamMethod::Fem:
        if (const Field e = f.child("elements"); e.present()) h.elements = requireIntAtLeast(e, 1);
        break;
      case model::HubBeamMethod::AssumedModes:
        if (const Field a = f.child("axial_modes"); a.present()) h.axialModes = requireIntInRange(a, 1, 10);
        if (const Field b = f.child("bending_modes"); b.present()) h.bendingModes = requireIntInRange(b, 1, 10);
        break;
      case model::HubBeamMethod::Rpim:
        if (const Field n = f.child("nodes"); n.present()) h.nodes = requireIntAtLeast(n, 3);
        if (const Field a = f.child("alpha_c"); a.present()) h.alphaC = requirePositive(a);
        if (const Field q = f.child("q"); q.present()) {
          h.q = q.number();
          if (h.q >= 0.0 && h.q == std::floor(h.q))
            q.fail("must not be 0 or a positive integer: the multiquadric (r^2 + (alpha_c d_c)^2)^q is then a "
                   "polynomial and the moment matrix is singular (got " + fmt(h.q) + ")");
        }
        if (const Field a = f.child("alpha_s"); a.present()) {
          h.alphaS = requirePositive(a);
          if (h.alphaS < 1.0) a.fail("must be at least 1, so that every point's support holds 2 nodes (got " + fmt(h.alphaS) + ")");
        }
        if (const Field g = f.child("gauss_points"); g.present()) h.gaussPoints = requireIntInRange(g, 1, 10);
        if (const Field s = f.child("support"); s.present()) h.cellSupport = pick(s, "support", kRpimSupports).value;
        break;
    }
  }

  void readModes(const Field& f) {
    f.expectMap({"count", "coriolis", "method", "projection_modes", "warm_start"});
    if (const Field w = f.child("warm_start"); w.present()) scene_.modes.warmStart = w.boolean();
    if (const Field count = f.child("count"); count.present()) scene_.modes.count = requireIntAtLeast(count, 1);
    if (const Field c = f.child("coriolis"); c.present()) scene_.modes.coriolis = c.boolean();
    if (const Field m = f.child("method"); m.present()) scene_.modes.method = pick(m, "modal method", kModalMethods).value;
    if (const Field m = f.child("projection_modes"); m.present()) {
      scene_.modes.projectionModes = requireIntAtLeast(m, 1);
      if (scene_.modes.projectionModes < scene_.modes.count)
        m.fail("must be at least modes.count = " + std::to_string(scene_.modes.count));
    }
  }

  void readDynamics(const Field& f) {
    f.expectMap({"integrator", "rho_inf", "hht_alpha", "bdf_order", "adaptive", "rtol", "atol", "constraint_form", "dt",
                 "t_end", "output_every", "dt_out", "step_cuts"});
    model::DynamicsDesc& d = scene_.dynamics;
    d.mark = f.mark();
    const Field integrator = f.child("integrator");
    if (integrator.present()) d.integrator = pick(integrator, "integrator", kIntegrators).value;
    if (const Field c = f.child("step_cuts"); c.present()) {
      if (model::isFirstOrder(d.integrator))
        c.fail("only used by integrator: generalized_alpha, newmark or hht (bdf cuts its step with adaptive: true)");
      d.stepCuts = requireIntInRange(c, 0, 10);
    }
    if (const Field r = f.child("rho_inf"); r.present()) {
      if (d.integrator != model::Integrator::GeneralizedAlpha) r.fail("only used by integrator: generalized_alpha");
      d.rhoInf = r.number();
      if (!(d.rhoInf >= 0.0 && d.rhoInf <= 1.0)) r.fail("must lie in [0, 1] (spectral radius at infinite frequency)");
    }
    if (const Field a = f.child("hht_alpha"); a.present()) {
      if (d.integrator != model::Integrator::Hht) a.fail("only used by integrator: hht");
      d.hhtAlpha = a.number();
      if (!(d.hhtAlpha >= 0.0 && d.hhtAlpha <= 1.0 / 3.0)) a.fail("must lie in [0, 1/3] (HHT stability range)");
    }
    if (const Field o = f.child("bdf_order"); o.present()) {
      if (d.integrator != model::Integrator::Bdf) o.fail("only used by integrator: bdf");
      d.bdfOrder = requireIntAtLeast(o, 1);
      if (d.bdfOrder > 5) o.fail("must lie in 1..5 (BDF of order 6 and above is not zero-stable)");
    }
    if (const Field a = f.child("adaptive"); a.present()) {
      if (d.integrator != model::Integrator::Bdf) a.fail("only used by integrator: bdf (the other integrators take fixed steps)");
      d.adaptive = a.boolean();
    }
    for (const char* key : {"rtol", "atol"})
      if (const Field t = f.child(key); t.present()) {
        if (!d.adaptive) t.fail("only used with integrator: bdf and adaptive: true");
        (std::string(key) == "rtol" ? d.rtol : d.atol) = requirePositive(t);
      }
    // 3D rigid bodies carry the orthonormality equations of their frame: constraints too; so does a
    // `clamped` hub support of a cable-like kind (its slope's direction turns: Model::addClampDirectionJoints)
    const model::SupportDesc* hubClamp = nullptr;
    for (const model::SupportDesc& s : scene_.supports) {
      if (!s.hub.present || s.type != model::SupportType::Clamped) continue;
      for (const model::BodyDesc& b : scene_.bodies) {
        const elements::KindInfo& k = elements::kindInfo(b.kind);
        if (b.name == s.at.body && k.layout[k.orientationBlock] == elements::BlockRole::AxialGradient) hubClamp = &s;
      }
    }
    bool sliding = false;  // its spacing joints (Model::addMaterialJoints)
    for (const model::SupportDesc& s : scene_.supports) sliding = sliding || s.type == model::SupportType::Sliding;
    const bool constrained = !scene_.joints.empty() || (ctx_.dim == 3 && !scene_.rigidBodies.empty()) || hubClamp || sliding;
    if (model::isExplicit(d.integrator) && hubClamp && scene_.joints.empty())
      integrator.fail("explicit integrators (rk4, abm4) take problems without Lagrange multipliers, and the `clamped` hub "
                      "support at " + hubClamp->mark.where() + " holds the turning slope direction by one; use "
                      "generalized_alpha or bdf, or `clamped_unstretched` (the whole slope held: zero axial strain at the root)");
    if (model::isExplicit(d.integrator) && constrained)
      integrator.fail("explicit integrators (rk4, abm4) take problems without joints (no Lagrange multipliers; a 3D "
                      "rigid body's frame is held by six); use generalized_alpha with rho_inf <= 0.9 or bdf for scenes with joints");
    if (const Field c = f.child("constraint_form"); c.present()) {
      if (d.integrator != model::Integrator::Bdf || !constrained)
        c.fail("only used by integrator: bdf in a scene with joints");
      d.constraintForm = pick(c, "constraint form", kConstraintForms).value;
    }
    d.dt = requirePositive(f.child("dt"));
    d.tEnd = requirePositive(f.child("t_end"));
    if (d.dt > d.tEnd) f.child("dt").fail("larger than t_end");
    // a fixed-step run counts its steps in a 32-bit PETSc integer (issue 32 item 8: 3e9 steps
    // ended in a PETSc abort, exit 63)
    if (!d.adaptive && std::ceil(d.tEnd / d.dt) + 2.0 > double(INT_MAX))
      f.child("dt").fail("t_end / dt = " + fmt(d.tEnd / d.dt, 3) + " steps, more than a run can count (" +
                         std::to_string(INT_MAX - 2) + "); use a larger dt");
    if (const Field k = f.child("output_every"); k.present()) d.outputEvery = requireIntAtLeast(k, 1);
    if (const Field o = f.child("dt_out"); o.present()) {
      if (f.child("output_every").present()) o.fail("give either 'output_every' (steps) or 'dt_out' (seconds), not both");
      d.dtOut = requirePositive(o);
    }
  }

  // Dimensionless scales of the first body (seed 003): T* = sqrt(rho A L^4 / (E I)), L.
  double referenceTime() const {
    const BodyDesc& b = scene_.bodies.front();
    const double L = bodyLength(b.geometry);
    const elements::BeamProperties p = elements::kindInfo(b.kind).properties(b.section);
    return std::sqrt(p.rhoA * L * L * L * L / p.EI);
  }

  // rotation: omega [rad/s] or gamma (= omega T*); axis (3D); center, or hub_radius [m] /
  // hub_radius_ratio (delta: hub radius / L) measured back from the first node of the first body,
  // which must then be a straight line.
  void readRotation(const Field& f) {
    f.expectMap({"omega", "gamma", "axis", "center", "hub_radius", "hub_radius_ratio"});
    model::RotationDesc& r = scene_.rotation;
    r.present = true;
    r.mark = f.mark();
    const Field omega = f.child("omega"), gamma = f.child("gamma");
    if (omega.present() == gamma.present()) f.fail("give exactly one of 'omega' [rad/s] and 'gamma' (omega sqrt(rho A L^4 / EI))");
    r.omega = omega.present() ? requireNonNegative(omega) : requireNonNegative(gamma) / referenceTime();
    if (const Field axis = f.child("axis"); axis.present()) {
      if (ctx_.dim == 2) axis.fail("a 2D scene rotates about z; remove 'axis'");
      r.axis = readDirection(axis, 3);
    }
    const Field center = f.child("center"), hub = f.child("hub_radius"), ratio = f.child("hub_radius_ratio");
    if (int(center.present()) + int(hub.present()) + int(ratio.present()) > 1)
      f.fail("give at most one of 'center', 'hub_radius' and 'hub_radius_ratio'");
    const BodyDesc& b = scene_.bodies.front();
    if (center.present()) {
      r.center = readVector(center, ctx_.dim);
    } else {
      const Field& given = hub.present() ? hub : ratio;
      if (b.geometry.kind != model::GeometryKind::Line)
        (given.present() ? given : f).fail("the hub radius is measured along the first body, which must be a straight 'line'; give 'center' instead");
      const double L = bodyLength(b.geometry);
      const double R = hub.present() ? requireNonNegative(hub) : ratio.present() ? requireNonNegative(ratio) * L : 0.0;
      for (int i = 0; i < 3; ++i)
        r.center[i] = b.geometry.start[i] - R * (b.geometry.end[i] - b.geometry.start[i]) / L;
    }
  }

  void readSweep(const Field& f) {
    f.expectMap({"parameter", "from", "to", "points", "mass", "refine"});
    model::SweepDesc& s = scene_.sweep;
    s.present = true;
    s.mark = f.mark();
    s.parameter = pick(f.child("parameter"), "sweep parameter", kSweepParameters).value;
    s.from = f.child("from").number();
    s.to = f.child("to").number();
    s.points = requireIntAtLeast(f.child("points"), 2);
    if (const Field r = f.child("refine"); r.present()) s.refine = requireIntAtLeast(r, 0);
    const bool massSweep = s.parameter == model::SweepParameter::MassRatio || s.parameter == model::SweepParameter::MassLocation;
    if (const Field m = f.child("mass"); m.present()) {
      if (!massSweep) m.fail("only mass_ratio and mass_location sweeps move a point mass");
      s.mass = requireIntAtLeast(m, 0);
    }
    if (massSweep && s.mass >= static_cast<int>(scene_.bodies.front().pointMasses.size()))
      f.fail("a " + std::string(s.parameter == model::SweepParameter::MassRatio ? "mass_ratio" : "mass_location") +
             " sweep needs point mass " + std::to_string(s.mass) + " on body '" + scene_.bodies.front().name + "'");
    const bool nonNegative = s.parameter != model::SweepParameter::MassLocation;
    for (const char* key : {"from", "to"}) {
      const double v = f.child(key).number();
      if (nonNegative && v < 0.0) f.child(key).fail("must not be negative (got " + fmt(v) + ")");
      if (s.parameter == model::SweepParameter::MassLocation && (v < 0.0 || v > 1.0))
        f.child(key).fail("a mass location is a fraction of the body length, within [0, 1] (got " + fmt(v) + ")");
      if (s.parameter == model::SweepParameter::MassRatio && v <= 0.0) f.child(key).fail("a mass ratio must be positive (got " + fmt(v) + ")");
    }
    if ((s.parameter == model::SweepParameter::Gamma || s.parameter == model::SweepParameter::Omega) && !scene_.rotation.present)
      f.fail("an angular-speed sweep needs a 'rotation' section (its axis and hub)");
    if (s.parameter == model::SweepParameter::TransportSpeed) {
      bool ale = false;
      for (const BodyDesc& b : scene_.bodies) ale = ale || !elements::kindInfo(b.kind).constantMass;
      if (!ale) f.fail("a transport_speed sweep moves the material of ALE bodies (" + aleKindNames() + "); there are none");
    }
  }

  void readDiscretization(const Field& f) {
    f.expectMap({"slope_scaling", "gauss_points"});
    if (const Field s = f.child("slope_scaling"); s.present())
      scene_.discretization.slopeScaling = s.boolean();
    if (const Field g = f.child("gauss_points"); g.present())
      scene_.discretization.gaussPoints = requireIntInRange(g, 2, 8);
  }

  void readBodies(const Field& f, bool rigidBodiesToo) {
    if (rigidBodiesToo && !f.present()) return;  // a scene of rigid bodies only
    const std::vector<Field> items = f.items();
    if (items.empty() && !rigidBodiesToo) f.fail("needs at least one body");
    for (const Field& item : items) {
      BodyDesc body = readBody(item, ctx_);
      if (body.hasInitialVelocity && scene_.analysis != model::Analysis::Dynamic)
        item.child("initial_velocity").fail("initial velocities need analysis: dynamic");
      for (const BodyDesc& other : scene_.bodies)
        if (other.name == body.name)
          item.child("name").fail("duplicate body name '" + body.name + "' (also " + other.mark.key +
                                  " on line " + std::to_string(other.mark.line) + ")");
      scene_.bodies.push_back(std::move(body));
    }
  }

  const BodyDesc& findBody(const Field& name) const {
    const std::string wanted = name.text();
    std::vector<std::string> names;
    for (const BodyDesc& b : scene_.bodies) {
      if (b.name == wanted) return b;
      names.push_back(b.name);
    }
    name.fail("no body named '" + printable(wanted) + "'; bodies: " + join(names));
  }

  // The `body` and `node` keys of `f` (which the caller has checked for allowed keys).
  NodeRef readNodeRef(const Field& f) const {
    NodeRef ref;
    ref.mark = f.mark();
    const BodyDesc& body = findBody(f.child("body"));
    ref.body = body.name;
    const Field node = f.child("node");
    if (node.isScalar("last")) {
      ref.node = -1;
      return ref;
    }
    ref.node = node.integer("a node index or 'last'");
    if (ref.node < 0 || ref.node > body.elements)
      node.fail("node index out of range: body '" + body.name + "' has nodes 0.." +
                std::to_string(body.elements) + " or 'last' (got " + std::to_string(ref.node) + ")");
    return ref;
  }

  // rigid_bodies: 2D (x, y, phi) or 3D (centre of mass and body axes; angles and vectors in 3D).
  void readRigidBodies(const Field& f) {
    const int D = ctx_.dim;
    for (const Field& item : f.items()) {
      if (D == 2)
        item.expectMap({"name", "mass", "inertia", "position", "angle", "velocity", "angular_velocity", "force",
                        "torque", "fixed", "rotation"});
      else
        item.expectMap({"name", "mass", "inertia", "position", "angle", "axis", "velocity", "angular_velocity",
                        "force", "torque", "fixed", "rotation", "rotation_axis"});
      model::RigidBodyDesc r;
      r.mark = item.mark();
      r.name = item.child("name").text();
      for (const BodyDesc& b : scene_.bodies)
        if (b.name == r.name) item.child("name").fail("the name '" + r.name + "' is already a body");
      for (const model::RigidBodyDesc& o : scene_.rigidBodies)
        if (o.name == r.name) item.child("name").fail("duplicate rigid body name '" + r.name + "'");
      r.mass = requirePositive(item.child("mass"));
      if (D == 2) r.inertia = requirePositive(item.child("inertia"));
      else r.principalInertia = readPrincipalInertia(item.child("inertia"));
      r.position = readVector(item.child("position"), D);
      if (const Field a = item.child("angle"); a.present()) r.angle = a.number();
      if (const Field ax = item.child("axis"); ax.present()) {
        r.axis = readVector(ax, 3);
        if (r.axis[0] == 0.0 && r.axis[1] == 0.0 && r.axis[2] == 0.0) ax.fail("the rotation axis must not be zero");
      }
      if (const Field v = item.child("velocity"); v.present()) r.velocity = readVector(v, D);
      if (const Field w = item.child("angular_velocity"); w.present()) {
        if (D == 2) r.angularVelocity[2] = w.number();
        else r.angularVelocity = readVector(w, 3);
      }
      if (const Field F = item.child("force"); F.present()) r.force = readVector(F, D);
      if (const Field t = item.child("torque"); t.present()) {
        if (D == 2) r.torque[2] = t.number();
        else r.torque = readVector(t, 3);
      }
      if (const Field fx = item.child("fixed"); fx.present()) {
        for (const Field& e : fx.items()) {
          const std::string c = e.text();
          const int k = c == "x" ? 0 : c == "y" ? 1 : (D == 2 && c == "phi") || (D == 3 && c == "z") ? 2 : -1;
          if (k < 0)
            e.fail("unknown coordinate '" + printable(c) + (D == 2 ? "'; allowed: x, y, phi" : "'; allowed: x, y, z (a 3D body's orientation is held by joints)"));
          if (std::find(r.fixed.begin(), r.fixed.end(), k) != r.fixed.end()) e.fail("listed twice");
          r.fixed.push_back(k);
        }
      }
      if (const Field rot = item.child("rotation"); rot.present()) {
        if (scene_.analysis != model::Analysis::Dynamic) rot.fail("a driven rotation needs analysis: dynamic");
        if (D == 2 && std::find(r.fixed.begin(), r.fixed.end(), 2) != r.fixed.end())
          rot.fail("phi is listed in 'fixed'; a driven body's phi follows 'rotation' instead");
        if (item.child("angular_velocity").present())
          rot.fail("the initial angular velocity of a driven body is the rotation's rate; remove 'angular_velocity'");
        if (item.child("torque").present())
          rot.fail("a driven body's rotation is prescribed, so a 'torque' on it would do nothing; remove one of them");
        r.driven = true;
        r.rotation = readTimeFunction(rot);
      }
      if (const Field ax = item.child("rotation_axis"); ax.present()) {
        if (!r.driven) ax.fail("'rotation_axis' is the axis of a driven rotation; give 'rotation' too");
        r.rotationAxis = readDirection(ax, 3);
      }
      scene_.rigidBodies.push_back(std::move(r));
    }
  }

  // 3D principal moments of inertia [I1, I2, I3] about the body axes: positive, and each below the
  // sum of the other two (I1 < I2 + I3 ...: a real mass distribution; equality is a line of mass,
  // whose spin about its own axis has no inertia and leaves the mass matrix singular).
  static model::Vec3 readPrincipalInertia(const Field& f) {
    const model::Vec3 I = readVector(f, 3);
    for (int k = 0; k < 3; ++k)
      if (!(I[k] > 0.0)) f.fail("3D principal moments of inertia must be positive (got " + fmt(I[k]) + ")");
    for (int k = 0; k < 3; ++k)
      if (!(I[k] < I[(k + 1) % 3] + I[(k + 2) % 3]))
        f.fail("moment I" + std::to_string(k + 1) + " = " + fmt(I[k]) +
               " is not below the sum of the other two; no mass distribution has these moments "
               "(a thin rod's are [0, I, I]: give its spin axis a small moment)");
    return I;
  }

  // One end of a joint: {ground: [x, y(, z)]}, {body: <cable>, node: i}, {body: <rigid>, point: [x, y(, z)]}.
  model::JointEndDesc readJointEnd(const Field& f) const {
    f.expectMap({"ground", "body", "node", "point"});
    model::JointEndDesc e;
    e.mark = f.mark();
    if (const Field g = f.child("ground"); g.present()) {
      if (f.child("body").present()) f.fail("give either 'ground' or 'body', not both");
      e.kind = model::JointEndDesc::Kind::Ground;
      e.point = readVector(g, ctx_.dim);
      return e;
    }
    const Field body = f.child("body");
    if (!body.present()) f.fail("a joint end needs 'ground: [point]' or 'body'");
    const std::string name = body.text();
    for (const model::RigidBodyDesc& r : scene_.rigidBodies)
      if (r.name == name) {
        if (f.child("node").present()) f.child("node").fail("'" + name + "' is a rigid body: give 'point' (body frame)");
        e.kind = model::JointEndDesc::Kind::RigidPoint;
        e.body = name;
        if (const Field p = f.child("point"); p.present()) e.point = readVector(p, ctx_.dim);
        return e;
      }
    if (f.child("point").present()) f.child("point").fail("'point' is for rigid bodies; a cable end is a 'node'");
    const NodeRef ref = readNodeRef(f);
    e.kind = model::JointEndDesc::Kind::CableNode;
    e.body = ref.body;
    e.node = ref.node;
    return e;
  }

  void readJoints(const Field& f) {
    for (const Field& item : f.items()) {
      item.expectMap({"type", "a", "b", "length"});
      model::JointDesc j;
      j.mark = item.mark();
      j.type = pick(item.child("type"), "joint type", kJointTypes).value;
      j.a = readJointEnd(item.child("a"));
      j.b = readJointEnd(item.child("b"));
      if (const Field l = item.child("length"); l.present()) {
        if (j.type != model::JointType::Distance) l.fail("only used by type: distance");
        j.length = requirePositive(l);
      }
      if (j.type == model::JointType::Clamp) {
        if (j.a.kind != model::JointEndDesc::Kind::CableNode)
          item.child("a").fail("a clamp holds a cable node: end a must be {body: <cable>, node: i}");
        if (j.b.kind == model::JointEndDesc::Kind::CableNode)
          item.child("b").fail("a clamp holds to the ground or a rigid body, not to another cable node (use pin)");
      }
      scene_.joints.push_back(std::move(j));
    }
  }

  // Node index with `last` resolved, to compare references.
  long resolvedNode(const NodeRef& ref) const {
    if (ref.node >= 0) return ref.node;
    for (const BodyDesc& b : scene_.bodies)
      if (b.name == ref.body) return b.elements;
    return ref.node;
  }

  void readSupports(const Field& f) {
    for (const Field& item : f.items()) {
      item.expectMap({"body", "node", "type", "dofs", "hub"});
      model::SupportDesc s;
      s.mark = item.mark();
      s.at = readNodeRef(item);
      int maxDof = 2 * ctx_.dim - 1;  // a node's coordinates, block by block in its kind's layout
      for (const BodyDesc& b : scene_.bodies)
        if (b.name == s.at.body) maxDof = elements::kindInfo(b.kind).blocksPerNode * ctx_.dim - 1;
      s.type = pick(item.child("type"), "support type", kSupportTypes).value;
      const Field dofs = item.child("dofs");
      if (s.type != model::SupportType::Fixed) {
        if (dofs.present()) dofs.fail("only allowed with type: fixed");
      } else {
        if (!dofs.present())
          dofs.fail("missing required value (type: fixed needs the list of fixed coordinates)");
        const std::vector<Field> entries = dofs.items();
        if (entries.empty()) dofs.fail("must list at least one coordinate");
        for (const Field& entry : entries) {
          const int dof = requireIntInRange(entry, 0, maxDof);
          if (std::find(s.dofs.begin(), s.dofs.end(), dof) != s.dofs.end())
            entry.fail("coordinate " + std::to_string(dof) + " is listed twice");
          s.dofs.push_back(dof);
        }
      }
      if (const Field hub = item.child("hub"); hub.present()) {
        if (s.type == model::SupportType::Sliding) hub.fail("a sliding support is held at a fixed point (a hub is not built for it)");
        readHub(hub, s);
      }
      if (s.type == model::SupportType::Sliding) checkSliding(item, s);
      scene_.supports.push_back(std::move(s));
    }
  }

  // type: sliding: an inner node of an ALE body (material slides through it), in dynamics, on a body
  // whose material nothing moves but a payout or a reel (Model::addMaterialJoints).
  void checkSliding(const Field& item, const model::SupportDesc& s) const {
    const Field type = item.child("type");
    const BodyDesc& body = findBody(item.child("body"));
    if (elements::kindInfo(body.kind).materialBlock() < 0)
      type.fail(std::string("sliding: material slides through the node only on an ALE body (AleCable2d, AleCable3d, "
                            "AleBeamShaft3d), not ") + elements::kindInfo(body.kind).name);
    if (scene_.analysis != model::Analysis::Dynamic) type.fail("sliding: only with analysis: dynamic");
    if (s.at.node <= 0 || s.at.node >= body.elements)
      item.child("node").fail("sliding: an inner node (1.." + std::to_string(body.elements - 1) +
                              "); an end node is a material point, the end of the body");
    if (body.hasMaterialMotion || !body.materialNodes.empty())
      type.fail("sliding: not built on a body whose material moves by material_motion or material_nodes (a payout "
                "or a reel: yes)");
    for (const model::SupportDesc& o : scene_.supports)
      if (o.at.body == s.at.body && o.at.node == s.at.node) type.fail("sliding: this node has another support");
  }

  // reels: [{name, body, node: 0 | last, radius, inertia, content, rotation | torque, damping}]
  // (ReelDesc): a drum paying out an ALE body's material from its exit node, in dynamics.
  void readReels(const Field& f) {
    for (const Field& item : f.items()) {
      item.expectMap({"name", "body", "node", "radius", "inertia", "content", "rotation", "torque", "damping"});
      model::ReelDesc r;
      r.mark = item.mark();
      const Field name = item.child("name");
      r.name = name.text();
      if (r.name.empty()) name.fail("must not be empty");
      for (const model::ReelDesc& other : scene_.reels)
        if (other.name == r.name) name.fail("a second reel named '" + r.name + "'");
      if (scene_.analysis != model::Analysis::Dynamic) item.fail("a reel pays out in time: only with analysis: dynamic");
      const Field bodyField = item.child("body");
      const BodyDesc& body = findBody(bodyField);
      r.body = body.name;
      if (elements::kindInfo(body.kind).materialBlock() < 0)
        bodyField.fail(std::string("a reel pays out the material of an ALE body (") + aleKindNames() + "), not " +
                       elements::kindInfo(body.kind).name);
      if (body.hasPayout || body.hasMaterialMotion || !body.materialNodes.empty())
        bodyField.fail("this body's material already moves by payout, material_motion or material_nodes");
      for (const model::ReelDesc& other : scene_.reels)
        if (other.body == r.body) bodyField.fail("body '" + r.body + "' already has a reel ('" + other.name + "')");
      if (const Field node = item.child("node"); node.present()) {
        const long n = node.isScalar("last") ? -1 : node.integer("0 or 'last'");
        if (n == 0) r.node = 0;
        else if (n == -1 || n == body.elements) r.node = -1;
        else node.fail("a reel pays out at an end of the body: 0 or 'last' (" + std::to_string(body.elements) + ")");
      }
      r.radius = requirePositive(item.child("radius"));
      if (const Field c = item.child("content"); c.present()) r.content = requireNonNegative(c);
      const Field rotation = item.child("rotation");
      r.driven = rotation.present();
      if (r.driven) {
        r.rotation = readTimeFunction(rotation);
        if (r.rotation.at(0.0).df != 0.0)
          rotation.fail("a reel starts at rest (the tether with it): give a rotation whose rate is zero at t = 0, e.g. "
                        "{function: spin_up, omega: ..., duration: ...}");
        for (const char* key : {"torque", "damping"})
          if (const Field k = item.child(key); k.present())
            k.fail("only for a free reel (without 'rotation'); a driven reel's motion is its 'rotation'");
        if (const Field j = item.child("inertia"); j.present()) r.inertia = requireNonNegative(j);
      } else {
        r.inertia = requirePositive(item.child("inertia"));
        if (const Field t = item.child("torque"); t.present()) r.torque = readTimeFunction(t);
        if (const Field d = item.child("damping"); d.present()) r.damping = requireNonNegative(d);
      }
      scene_.reels.push_back(std::move(r));
    }
  }

  // pulleys: [{name, center, radius, speed}] (PulleyDesc; 2D).
  void readPulleys(const Field& f) {
    if (ctx_.dim != 2) f.fail("pulleys are circles in the xy plane: only when dimension is 2 (3D belt drives are not built)");
    if (scene_.analysis == model::Analysis::Modes) f.fail("contact is not linearized for modes: use static or dynamic");
    for (const Field& item : f.items()) {
      item.expectMap({"name", "center", "radius", "speed", "inertia", "damping", "torque", "slide"});
      model::PulleyDesc p;
      p.mark = item.mark();
      const Field name = item.child("name");
      p.name = name.text();
      if (p.name.empty()) name.fail("must not be empty");
      for (const model::PulleyDesc& other : scene_.pulleys)
        if (other.name == p.name) name.fail("a second pulley named '" + p.name + "'");
      p.center = readVector(item.child("center"), ctx_.dim);
      p.radius = requirePositive(item.child("radius"));
      if (const Field speed = item.child("speed"); speed.present()) p.speed = readTimeFunction(speed);
      if (const Field inertia = item.child("inertia"); inertia.present()) {
        if (scene_.analysis != model::Analysis::Dynamic)
          inertia.fail("a pulley free to turn moves in time: only with analysis: dynamic (statics: give its speed)");
        p.inertia = requirePositive(inertia);
        if (const Field speed = item.child("speed"); speed.present() && (speed.isMap() || speed.isList()))
          speed.fail("a free pulley's speed is its initial speed: a number [rad/s]");
      }
      for (const char* key : {"damping", "torque"})
        if (const Field k = item.child(key); k.present() && !p.free())
          k.fail("only for a pulley free to turn (with 'inertia'); a driven pulley's motion is its 'speed'");
      if (const Field d = item.child("damping"); d.present()) p.damping = requireNonNegative(d);
      if (const Field t = item.child("torque"); t.present()) p.torque = readTimeFunction(t);
      if (const Field slide = item.child("slide"); slide.present()) readSlide(slide, p);
      scene_.pulleys.push_back(std::move(p));
    }
  }

  // slide: {direction, mass, stiffness, damping, preload}: a tensioner (a free pulley on a
  // spring-damper slide).
  void readSlide(const Field& f, model::PulleyDesc& p) {
    if (!p.free())
      f.fail("a tensioner's pulley turns freely: give the pulley an 'inertia' (dynamics only)");
    f.expectMap({"direction", "mass", "stiffness", "damping", "preload"});
    p.hasSlide = true;
    p.slide.mark = f.mark();
    p.slide.direction = readDirection(f.child("direction"), ctx_.dim);
    p.slide.mass = requirePositive(f.child("mass"));
    if (const Field k = f.child("stiffness"); k.present()) p.slide.stiffness = requireNonNegative(k);
    if (const Field c = f.child("damping"); c.present()) p.slide.damping = requireNonNegative(c);
    if (const Field F = f.child("preload"); F.present()) p.slide.preload = readTimeFunction(F);
  }

  // contact: [{body, pulleys, stiffness, damping, belt_height, points,
  //            friction: {law: none | coulomb (mu, slip_velocity) | creep_rate (mu, slip_velocity)
  //                       | bristle (mu, stiffness)}}].
  void readContacts(const Field& f) {
    if (scene_.pulleys.empty()) f.fail("contact needs pulleys: the scene has none (key 'pulleys')");
    for (const Field& item : f.items()) {
      item.expectMap({"body", "pulleys", "stiffness", "damping", "belt_height", "points", "friction"});
      model::ContactDesc c;
      c.mark = item.mark();
      const BodyDesc& body = findBody(item.child("body"));
      c.body = body.name;
      if (elements::kindInfo(body.kind).materialBlock() >= 0)
        item.child("body").fail("contact with ALE bodies is not built yet");
      for (const model::ContactDesc& other : scene_.contacts)
        if (other.body == c.body) item.child("body").fail("a second contact entry for body '" + c.body + "'");
      if (const Field list = item.child("pulleys"); list.present()) {
        for (const Field& p : list.items()) {
          const std::string name = p.text();
          bool found = false;
          for (const model::PulleyDesc& pd : scene_.pulleys) found = found || pd.name == name;
          if (!found) p.fail("no pulley named '" + printable(name) + "'");
          if (std::find(c.pulleys.begin(), c.pulleys.end(), name) != c.pulleys.end()) p.fail("listed twice");
          c.pulleys.push_back(name);
        }
      } else {
        for (const model::PulleyDesc& pd : scene_.pulleys) c.pulleys.push_back(pd.name);
      }
      c.law.stiffness = requirePositive(item.child("stiffness"));
      if (const Field d = item.child("damping"); d.present()) c.law.damping = requireNonNegative(d);
      if (const Field h = item.child("belt_height"); h.present()) c.law.offset = 0.5 * requireNonNegative(h);
      if (const Field n = item.child("points"); n.present()) c.points = requireIntInRange(n, 1, 8);
      if (const Field fr = item.child("friction"); fr.present()) {
        fr.expectMap({"law", "mu", "slip_velocity", "stiffness"});
        const std::string law = fr.child("law").text();
        auto unused = [&](std::initializer_list<const char*> keys) {
          for (const char* key : keys)
            if (const Field k = fr.child(key); k.present()) k.fail("not used by law: " + law);
        };
        if (law == "none") {
          unused({"mu", "slip_velocity", "stiffness"});
        } else if (law == "coulomb" || law == "creep_rate") {
          unused({"stiffness"});
          c.law.friction = law == "coulomb" ? contact::FrictionLaw::RegularizedCoulomb : contact::FrictionLaw::CreepRate;
          c.law.mu = requireNonNegative(fr.child("mu"));
          if (const Field v = fr.child("slip_velocity"); v.present()) c.law.slipVelocity = requirePositive(v);
        } else if (law == "bristle") {
          unused({"slip_velocity"});
          if (scene_.analysis != model::Analysis::Dynamic)
            fr.child("law").fail("the bristle law follows each point's slip from step to step: it needs a dynamic analysis");
          c.law.friction = contact::FrictionLaw::Bristle;
          c.law.mu = requireNonNegative(fr.child("mu"));
          c.law.tangentialStiffness = c.law.stiffness;  // default: the normal penalty's
          if (const Field k = fr.child("stiffness"); k.present()) c.law.tangentialStiffness = requirePositive(k);
        } else {
          fr.child("law").fail("unknown friction law '" + printable(law) + "'; allowed: none, coulomb, creep_rate, bristle");
        }
      }
      scene_.contacts.push_back(std::move(c));
    }
  }

  // probes: [{name, body + node | body + at | rigid_body (+ point), frame, force}] (ProbeDesc).
  void readProbes(const Field& f) {
    if (scene_.analysis != model::Analysis::Static && scene_.analysis != model::Analysis::Dynamic)
      f.fail("probes are written by static and dynamic runs (each load or time step)");
    std::vector<std::string> names;
    for (const Field& item : f.items()) {
      item.expectMap({"name", "body", "node", "at", "rigid_body", "point", "frame", "force"});
      model::ProbeDesc p;
      p.mark = item.mark();
      const Field name = item.child("name");
      p.name = name.text();
      if (p.name.empty() || p.name.find_first_of("/: ") != std::string::npos)
        name.fail("'" + printable(p.name) + "' cannot name a probe's series: non-empty, no '/', ':' or spaces");
      if (std::find(names.begin(), names.end(), p.name) != names.end()) name.fail("a second probe named '" + p.name + "'");
      names.push_back(p.name);
      const Field body = item.child("body"), rigid = item.child("rigid_body"), node = item.child("node"),
                  at = item.child("at"), point = item.child("point"), force = item.child("force");
      if (body.present() == rigid.present()) item.fail("give either 'body' (with 'node' or 'at') or 'rigid_body'");
      if (body.present()) {
        if (node.present() == at.present()) item.fail("give either 'node' or 'at' (a fraction of the body's length)");
        if (point.present()) point.fail("'point' goes with 'rigid_body'");
        if (node.present()) {
          const model::NodeRef ref = readNodeRef(item);
          p.kind = model::ProbeDesc::Kind::Node;
          p.body = ref.body;
          p.node = ref.node;
        } else {
          p.kind = model::ProbeDesc::Kind::Along;
          p.body = findBody(body).name;
          p.along = at.number();
          if (p.along < 0.0 || p.along > 1.0) at.fail("must be in [0, 1] (a fraction of the body's length)");
        }
      } else {
        if (node.present() || at.present()) item.fail("'node' and 'at' go with 'body', not 'rigid_body'");
        p.kind = model::ProbeDesc::Kind::RigidPoint;
        p.body = rigid.text();
        if (!hasRigidBody(p.body)) rigid.fail("no rigid body named '" + printable(p.body) + "'");
        if (point.present()) p.point = readVector(point, ctx_.dim);
      }
      if (const Field frame = item.child("frame"); frame.present()) {
        p.frame = frame.text();
        p.frameMark = frame.mark();
        if (p.frame != "world" && p.frame != "hub" && !hasRigidBody(p.frame))
          frame.fail("expected world, hub (the frame of the hub turning the probe's body) or a rigid body's name (got '" +
                     printable(p.frame) + "')");
      }
      if (force.present()) {
        p.force = force.boolean();
        if (p.force && p.kind != model::ProbeDesc::Kind::Node)
          force.fail("a probe's force is the support force on a held node: give 'node'");
        if (p.force && scene_.analysis != model::Analysis::Dynamic)
          force.fail("support forces are written by dynamic runs");
      }
      scene_.probes.push_back(std::move(p));
    }
  }

  bool hasRigidBody(const std::string& name) const {
    for (const model::RigidBodyDesc& r : scene_.rigidBodies)
      if (r.name == name) return true;
    return false;
  }

  // hub: {angle: <time function>, center, axis (3D)}: the support turns with a prescribed hub.
  void readHub(const Field& f, model::SupportDesc& s) {
    f.expectMap({"angle", "center", "axis"});
    if (s.type == model::SupportType::Fixed)
      f.fail("a hub turns a clamped or pinned support, not single coordinates (type: fixed)");
    s.hub.present = true;
    s.hub.mark = f.mark();
    s.hub.angle = readTimeFunction(f.child("angle"));
    if (const Field c = f.child("center"); c.present()) s.hub.center = readVector(c, ctx_.dim);
    if (const Field axis = f.child("axis"); axis.present()) {
      if (ctx_.dim == 2) axis.fail("a 2D hub turns about z; remove 'axis'");
      s.hub.axis = readDirection(axis, 3);
    }
  }

  void readJunctions(const Field& f) {
    for (const Field& item : f.items()) {
      item.expectMap({"nodes"});
      model::JunctionDesc j;
      j.mark = item.mark();
      const Field nodes = item.child("nodes");
      const std::vector<Field> entries = nodes.items();
      if (entries.size() < 2)
        nodes.fail("needs at least 2 nodes (got " + std::to_string(entries.size()) + ")");
      for (const Field& entry : entries) {
        entry.expectMap({"body", "node"});
        NodeRef ref = readNodeRef(entry);
        for (const NodeRef& other : j.nodes)
          if (other.body == ref.body && resolvedNode(other) == resolvedNode(ref))
            entry.fail("the same node as " + other.mark.key);
        j.nodes.push_back(std::move(ref));
      }
      scene_.junctions.push_back(std::move(j));
    }
  }

  void readLoads(const Field& f) {
    f.expectMap({"gravity", "nodal", "distributed", "function"});
    if (const Field fn = f.child("function"); fn.present()) {
      if (scene_.analysis != model::Analysis::Dynamic) fn.fail("time-dependent loads need analysis: dynamic");
      scene_.loads.timed = true;
      scene_.loads.function = readTimeFunction(fn);
    }
    if (const Field g = f.child("gravity"); g.present()) scene_.loads.gravity = readVector(g, ctx_.dim);
    if (const Field nodal = f.child("nodal"); nodal.present()) {
      for (const Field& item : nodal.items()) {
        item.expectMap({"body", "node", "force", "moment", "spin_torque", "function"});
        model::NodalLoadDesc load;
        load.mark = item.mark();
        load.at = readNodeRef(item);
        if (const Field force = item.child("force"); force.present())
          load.force = readVector(force, ctx_.dim);
        if (const Field moment = item.child("moment"); moment.present())
          load.moment = readMoment(moment, ctx_.dim);
        if (const Field torque = item.child("spin_torque"); torque.present()) {
          const elements::KindInfo& kind = elements::kindInfo(findBody(item.child("body")).kind);
          if (kind.blockWith(elements::BlockRole::MaterialSpin) < 0) torque.fail(std::string(kind.name) + " has no spin angle (AleBeamShaft3d has)");
          load.spinTorque = torque.number();
        }
        if (const Field fn = item.child("function"); fn.present()) {
          if (scene_.analysis != model::Analysis::Dynamic)
            fn.fail("time-dependent loads need analysis: dynamic");
          if (item.child("moment").present()) fn.fail("scales a force; give the moment as a separate, constant load");
          if (!item.child("force").present() && !item.child("spin_torque").present())
            fn.fail("needs a 'force' or 'spin_torque' to scale");
          load.timed = true;
          load.function = readTimeFunction(fn);
        }
        scene_.loads.nodal.push_back(std::move(load));
      }
    }
    if (const Field distributed = f.child("distributed"); distributed.present()) {
      for (const Field& item : distributed.items()) {
        item.expectMap({"body", "force_per_length", "spin_torque_per_length"});
        model::DistributedLoadDesc load;
        load.mark = item.mark();
        const model::BodyDesc& body = findBody(item.child("body"));
        load.body = body.name;
        const Field force = item.child("force_per_length"), torque = item.child("spin_torque_per_length");
        if (!force.present() && !torque.present()) item.fail("needs a 'force_per_length' or a 'spin_torque_per_length'");
        if (force.present()) load.forcePerLength = readVector(force, ctx_.dim);
        if (torque.present()) {
          const elements::KindInfo& kind = elements::kindInfo(body.kind);
          if (kind.blockWith(elements::BlockRole::MaterialSpin) < 0) torque.fail(std::string(kind.name) + " has no spin angle (AleBeamShaft3d has)");
          load.spinTorquePerLength = torque.number();
        }
        scene_.loads.distributed.push_back(std::move(load));
      }
    }
  }

  void readOutput(const Field& f) {
    f.expectMap({"file", "samples_per_element"});
    if (const Field file = f.child("file"); file.present()) {
      scene_.output.file = file.text();
      if (scene_.output.file.empty()) file.fail("must not be empty");
    }
    if (const Field samples = f.child("samples_per_element"); samples.present())
      scene_.output.samplesPerElement = requireIntAtLeast(samples, 1);
  }

  // Values that are valid one by one but whose products leave double precision: the stiffness and
  // mass of a section, the time scale rho A L^4 / (E I). E 1e308 or A 1e-300 ended in PETSc aborts
  // (zero pivots, NaN tolerances; issue 32 item 8). Each must lie within [1e-100, 1e100], far
  // outside any physical scene and far inside double precision, so that their squares stay finite.
  static bool representable(double v) { return std::isfinite(v) && std::fabs(v) >= 1e-100 && std::fabs(v) <= 1e100; }

  static void checkSection(const SourceMark& at, const elements::BeamProperties& p, double length) {
    const std::pair<const char*, double> products[] = {{"E A", p.EA},
                                                       {"E I", p.EI},
                                                       {"rho A", p.rhoA},
                                                       {"the length", length},
                                                       {"rho A L^4 / (E I)", p.rhoA * std::pow(length, 4) / p.EI}};
    for (const auto& [name, v] : products)
      if (!representable(v))
        failAt(at, name + std::string(" = ") + fmt(v) + " is beyond what the solvers can represent (1e-100..1e100); "
                                                        "check the units");
  }

  void checkRepresentable() const {
    for (const BodyDesc& b : scene_.bodies) {
      checkSection({b.mark.file, b.mark.line, b.mark.key + ".section"}, elements::kindInfo(b.kind).properties(b.section),
                   bodyLength(b.geometry));
      for (const model::PointMassDesc& pm : b.pointMasses)
        if (!representable(pm.mass)) failAt(pm.mark, "a mass of " + fmt(pm.mass) + " kg is beyond 1e-100..1e100");
    }
    for (const model::RigidBodyDesc& r : scene_.rigidBodies) {
      const double values[] = {r.mass, ctx_.dim == 2 ? r.inertia : r.principalInertia[0], r.principalInertia[1],
                               r.principalInertia[2]};
      for (int k = 0; k < (ctx_.dim == 2 ? 2 : 4); ++k)
        if (!representable(values[k]))
          failAt(r.mark, "mass " + fmt(r.mass) + " and inertia must lie within 1e-100..1e100 (got " + fmt(values[k]) + ")");
    }
  }

  // Body and rigid-body names become HDF5 group and series names and XDMF text: no '/' or ':'
  // (OutputWriter refused them later without a line), not "." or ".." (issue 32 item 10).
  void checkOutputNames() const {
    auto check = [](const std::string& name, const SourceMark& mark) {
      if (name == "." || name == ".." || name.find_first_of("/:") != std::string::npos)
        failAt({mark.file, mark.line, mark.key + ".name"},
               "'" + printable(name) + "' cannot name an output group: no '/' or ':', not '.' or '..'");
    };
    for (const BodyDesc& b : scene_.bodies) check(b.name, b.mark);
    for (const model::RigidBodyDesc& r : scene_.rigidBodies) check(r.name, r.mark);
  }

  // A catenary without sag_direction hangs along gravity (or -y / -z without gravity); that
  // direction must not be parallel to its chord.
  void checkCatenaryDefaults() const {
    const Vec3& g = scene_.loads.gravity;
    const bool hasGravity = norm(g) > 0.0;
    const Vec3 down = hasGravity ? scaled(g, 1.0 / norm(g)) : ctx_.dim == 2 ? Vec3{0, -1, 0} : Vec3{0, 0, -1};
    const std::string downName = hasGravity ? "gravity" : ctx_.dim == 2 ? "-y" : "-z";
    for (const BodyDesc& b : scene_.bodies) {
      const GeometryDesc& geo = b.geometry;
      if (geo.kind == GeometryKind::Catenary && norm(geo.sagDirection) == 0.0 &&
          parallelToChord(down, geo.start, geo.end))
        failAt(geo.mark, "the default sag direction (" + downName +
                             ") is parallel to the line from start to end; give sag_direction");
    }
  }

  Context ctx_;
  model::SceneDescription scene_;
};

}  // namespace

namespace {

// The events of one YAML document: the line of its first value (0: the document is empty).
class FirstValue : public YAML::EventHandler {
public:
  int line = 0;
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { note(m); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t, const std::string&) override { note(m); }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    note(m);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    note(m);
  }
  void OnMapEnd() override {}

private:
  void note(const YAML::Mark& m) {
    if (line == 0) line = m.line + 1;
  }
};

// The line where a second YAML document of `text` has a value, 0 if it has none. Walked with a
// Parser, two documents at most: yaml-cpp 0.7's LoadAll never ends on some malformed input (it
// keeps producing empty documents; found by tests/fuzz).
int secondDocumentLine(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  FirstValue first, second;
  if (!parser.HandleNextDocument(first) || !parser.HandleNextDocument(second)) return 0;
  return second.line;
}

}  // namespace

void requireModalScene(const model::SceneDescription& scene) {
  // Modes of a constrained system need its static equilibrium first, and the static Newton of a
  // mechanism starts singular (no stiffness for the rigid motion while the multipliers are 0):
  // refused here, the same way for `analysis: modes` and `strand modes` (issue 32 item 6).
  if (!scene.rigidBodies.empty() || !scene.joints.empty()) failAt(scene.analysisMark, kNoConstrainedModes);
  // modes linearize about a steady state: a material flow at a constant rate, not a payout
  for (const model::BodyDesc& b : scene.bodies) {
    if (b.hasPayout) failAt(b.mark, "payout changes the body's length: there are no modes about it (use material_motion "
                                    "for a steady flow)");
    for (const model::MaterialNodeDesc& m : b.materialNodes)
      if (m.hasMotion) failAt(m.mark, "a moving material node changes the elements' lengths: there are no modes about it");
  }
}

model::SceneDescription parseScene(const std::string& yamlText, const std::string& fileNameForMessages) {
  const std::string& file = fileNameForMessages;
  YAML::Node root;
  try {
    root = YAML::Load(yamlText);
    if (const int line = secondDocumentLine(yamlText))  // refused rather than ignored (issue 32 item 10)
      throw InputError(file + ":" + std::to_string(line) +
                       ": (document): a second YAML document ('---') is not read; a scene is one document");
  } catch (const YAML::Exception& e) {
    throw InputError(file + ":" + std::to_string(e.mark.line + 1) + ": (syntax): " + e.msg);
  }
  try {
    return SceneParser(file).parse(root);
  } catch (const YAML::Exception& e) {  // not expected: Field turns YAML errors into InputError
    throw InputError(file + ":" + std::to_string(e.mark.line + 1) + ": (yaml): " + e.msg);
  }
}

model::SceneDescription readScene(const std::string& path) {
  std::error_code ec;
  const bool isDir = fs::is_directory(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (!in || isDir) {
    const std::string why = isDir ? " (it is a directory)" : !fs::exists(path, ec) ? " (no such file)" : "";
    throw InputError(path + ":0: (file): cannot open scene file '" + path + "'" + why);
  }
  // bounded: a device or a pipe is not a scene (/dev/zero read without end, issue 32 item 9)
  if (!fs::is_regular_file(path, ec))
    throw InputError(path + ":0: (file): not a regular file; a scene is a YAML text file");
  const auto size = fs::file_size(path, ec);
  if (ec || size > kMaxSceneBytes)
    throw InputError(path + ":0: (file): " + std::to_string(size) + " bytes, more than a scene may have (" +
                     std::to_string(kMaxSceneBytes >> 20) + " MB); put long polylines in a CSV file (geometry.file)");
  std::string text(size, '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<size_t>(in.gcount()));
  return parseScene(text, path);
}

}  // namespace strand::io
