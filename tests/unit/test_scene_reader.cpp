// requirement: the scene reader turns a valid YAML scene into a SceneDescription with every value and
// source mark in place, and rejects every invalid scene with "<file>:<line>: <key>: <reason>"
// (docs/scene-reference.md lists the keys and rules checked here).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "strand/core/Error.hpp"
#include "strand/elements/ElementRegistry.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/model/InitialGeometry.hpp"

namespace fs = std::filesystem;
using namespace strand;
using namespace strand::model;
namespace elements = strand::elements;
using strand::io::parseScene;
using strand::io::readScene;

namespace {

// A minimal valid 3D scene; the error tests change one thing in it. Line numbers matter.
const std::string kBase3d =                                           // line
    "analysis: static\n"                                              // 1
    "dimension: 3\n"                                                  // 2
    "bodies:\n"                                                       // 3
    "  - name: cable\n"                                               // 4
    "    element: AncfCable3d\n"                                      // 5
    "    elements: 20\n"                                              // 6
    "    geometry: {kind: line, start: [0, 0, 0], end: [2, 0, 0]}\n"  // 7
    "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"  // 8
    "supports:\n"                                                     // 9
    "  - {body: cable, node: 0, type: clamped}\n"                     // 10
    "loads:\n"                                                        // 11
    "  nodal: [{body: cable, node: last, force: [0, 0, -1]}]\n";      // 12

// The same in 2D.
const std::string kBase2d =
    "analysis: static\n"                                              // 1
    "dimension: 2\n"                                                  // 2
    "bodies:\n"                                                       // 3
    "  - name: cable\n"                                               // 4
    "    element: AncfCable2d\n"                                      // 5
    "    elements: 20\n"                                              // 6
    "    geometry: {kind: line, start: [0, 0], end: [2, 0]}\n"        // 7
    "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"  // 8
    "supports:\n"                                                     // 9
    "  - {body: cable, node: 0, type: clamped}\n"                     // 10
    "loads:\n"                                                        // 11
    "  nodal: [{body: cable, node: last, force: [0, -1]}]\n";         // 12

// `text` with the single occurrence of `from` replaced by `to`.
std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "'" << from << "' not in the scene";
  EXPECT_EQ(text.find(from, pos + 1), std::string::npos) << "'" << from << "' is not unique";
  if (pos == std::string::npos) return text;
  return text.substr(0, pos) + to + text.substr(pos + from.size());
}

// The message of the InputError that `read` throws, or "" if it throws none.
template <class Read>
std::string errorOf(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Succeeds when parsing `yaml` as "scene.yaml" throws an InputError whose message starts with
// "scene.yaml:<line>: <key>: " and contains `word`.
::testing::AssertionResult failsWith(const std::string& yaml, int line, const std::string& key,
                                     const std::string& word) {
  const std::string msg = errorOf([&] { parseScene(yaml, "scene.yaml"); });
  const std::string prefix = "scene.yaml:" + std::to_string(line) + ": " + key + ": ";
  if (msg.empty()) return ::testing::AssertionFailure() << "no InputError for:\n" << yaml;
  if (msg.rfind(prefix, 0) != 0 || msg.find(word, prefix.size()) == std::string::npos)
    return ::testing::AssertionFailure() << "message '" << msg << "' does not start with '" << prefix << "' or lacks '"
                                         << word << "'";
  return ::testing::AssertionSuccess() << msg;
}

// A temporary directory for scene and CSV files, removed at the end of each test.
class SceneFiles : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("strand_scene_reader_" + std::to_string(::getpid()) + "_" + info->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  fs::path dir_;
};

void expectVec(const Vec3& v, double x, double y, double z) {
  EXPECT_DOUBLE_EQ(v[0], x);
  EXPECT_DOUBLE_EQ(v[1], y);
  EXPECT_DOUBLE_EQ(v[2], z);
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Valid scenes

TEST(SceneReader, FullScene3dParsesEveryValue) {
  const std::string yaml =
      "# every key once\n"                                                                   // 1
      "analysis: modes\n"                                                                    // 2
      "dimension: 3\n"                                                                       // 3
      "discretization: {slope_scaling: false, gauss_points: 4}\n"                            // 4
      "bodies:\n"                                                                            // 5
      "  - name: a\n"                                                                        // 6
      "    element: AncfCable3d\n"                                                           // 7
      "    elements: 10\n"                                                                   // 8
      "    geometry: {kind: line, start: [0, 0, 0], end: [3, 4, 0]}\n"                       // 9
      "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850, damping_axial: 0.01,\n"  // 10
      "              damping_bending: 0.02}\n"                                               // 11
      "    point_masses:\n"                                                                  // 12
      "      - {at: 2.5, mass: 1.5}\n"                                                       // 13
      "      - {at: 5, mass: 0.25}\n"                                                        // 14
      "  - name: b\n"                                                                        // 15
      "    element: AncfCable3d\n"                                                           // 16
      "    elements: 8\n"                                                                    // 17
      "    geometry:\n"                                                                      // 18
      "      kind: arc\n"                                                                    // 19
      "      center: [3, 4, 1]\n"                                                            // 20
      "      radius: 1\n"                                                                    // 21
      "      start_angle: -1.5707963267948966\n"                                             // 22
      "      end_angle: 0\n"                                                                 // 23
      "      normal: [0, 2, 0]\n"                                                            // 24
      "    section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}\n"                                 // 25
      "    point_masses: [{at: 1.5707963267948966, mass: 2}]\n"                              // 26
      "  - name: c\n"                                                                        // 27
      "    element: AncfCable3d\n"                                                           // 28
      "    elements: 6\n"                                                                    // 29
      "    geometry:\n"                                                                      // 30
      "      kind: polyline\n"                                                               // 31
      "      points: [[0, 0, 0], [1, 0, 0], [1, 1, 0]]\n"                                    // 32
      "    section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}\n"                                 // 33
      "    stress_free: straight\n"                                                          // 34
      "    point_masses: [{at: 2, mass: 3}]\n"                                               // 35
      "  - name: d\n"                                                                        // 36
      "    element: AncfCable3d\n"                                                           // 37
      "    elements: 12\n"                                                                   // 38
      "    geometry: {kind: catenary, start: [0, 0, 0], end: [10, 0, 0], length: 12,\n"      // 39
      "               sag_direction: [0, 0, -2]}\n"                                          // 40
      "    section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}\n"                                 // 41
      "supports:\n"                                                                          // 42
      "  - {body: a, node: 0, type: clamped}\n"                                              // 43
      "  - {body: b, node: last, type: pinned}\n"                                            // 44
      "  - {body: d, node: 12, type: fixed, dofs: [1, 2, 5]}\n"                              // 45
      "junctions:\n"                                                                         // 46
      "  - nodes: [{body: a, node: last}, {body: b, node: 0}]\n"                             // 47
      "loads:\n"                                                                             // 48
      "  gravity: [0, 0, -9.81]\n"                                                           // 49
      "  nodal:\n"                                                                           // 50
      "    - {body: a, node: 5, force: [1, 2, 3], moment: [4, 5, 6]}\n"                      // 51
      "    - {body: c, node: last, force: [0, 0, -1]}\n"                                     // 52
      "  distributed:\n"                                                                     // 53
      "    - {body: d, force_per_length: [0, 0, -2]}\n"                                      // 54
      "static: {load_steps: 10}\n"                                                           // 55
      "modes: {count: 8}\n"                                                                  // 56
      "output: {file: out.h5, samples_per_element: 3}\n";                                    // 57
  const SceneDescription s = parseScene(yaml, "dir/full.yaml");

  EXPECT_EQ(s.file, "dir/full.yaml");
  EXPECT_EQ(s.analysis, Analysis::Modes);
  EXPECT_EQ(s.dimension, 3);
  EXPECT_FALSE(s.discretization.slopeScaling);
  EXPECT_EQ(s.discretization.gaussPoints, 4);
  ASSERT_EQ(s.bodies.size(), 4u);

  const BodyDesc& a = s.bodies[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.kind, elements::findKind("AncfCable3d"));
  EXPECT_EQ(a.elements, 10);
  EXPECT_EQ(a.geometry.kind, GeometryKind::Line);
  expectVec(a.geometry.start, 0, 0, 0);
  expectVec(a.geometry.end, 3, 4, 0);
  EXPECT_DOUBLE_EQ(a.section.number("E"), 2.1e11);
  EXPECT_DOUBLE_EQ(a.section.number("A"), 7.85e-5);
  EXPECT_DOUBLE_EQ(a.section.number("I"), 4.91e-10);
  EXPECT_DOUBLE_EQ(a.section.number("rho"), 7850);
  EXPECT_DOUBLE_EQ(a.section.number("damping_axial"), 0.01);
  EXPECT_DOUBLE_EQ(a.section.number("damping_bending"), 0.02);
  EXPECT_FALSE(a.stressFreeInitial);
  ASSERT_EQ(a.pointMasses.size(), 2u);
  EXPECT_DOUBLE_EQ(a.pointMasses[0].at, 2.5);
  EXPECT_DOUBLE_EQ(a.pointMasses[0].mass, 1.5);
  EXPECT_DOUBLE_EQ(a.pointMasses[1].at, 5.0);  // exactly the body length: allowed
  EXPECT_DOUBLE_EQ(a.pointMasses[1].mass, 0.25);
  EXPECT_EQ(a.mark.where(), "dir/full.yaml:6: bodies[0]");
  EXPECT_EQ(a.geometry.mark.where(), "dir/full.yaml:9: bodies[0].geometry");
  EXPECT_EQ(a.pointMasses[1].mark.where(), "dir/full.yaml:14: bodies[0].point_masses[1]");

  const BodyDesc& b = s.bodies[1];
  EXPECT_EQ(b.geometry.kind, GeometryKind::Arc);
  expectVec(b.geometry.center, 3, 4, 1);
  EXPECT_DOUBLE_EQ(b.geometry.radius, 1.0);
  EXPECT_DOUBLE_EQ(b.geometry.startAngle, -M_PI / 2);
  EXPECT_DOUBLE_EQ(b.geometry.endAngle, 0.0);
  expectVec(b.geometry.normal, 0, 1, 0);  // normalized
  EXPECT_DOUBLE_EQ(b.section.number("E"), 1e9);
  EXPECT_DOUBLE_EQ(b.section.number("damping_axial"), 0.0);
  EXPECT_DOUBLE_EQ(b.pointMasses.at(0).at, M_PI / 2);  // the arc length
  EXPECT_EQ(b.geometry.mark.line, 18);  // the line of the key

  const BodyDesc& c = s.bodies[2];
  EXPECT_EQ(c.geometry.kind, GeometryKind::Polyline);
  ASSERT_EQ(c.geometry.points.size(), 3u);
  expectVec(c.geometry.points[2], 1, 1, 0);
  EXPECT_DOUBLE_EQ(c.pointMasses.at(0).at, 2.0);  // the polyline length

  const BodyDesc& d = s.bodies[3];
  EXPECT_EQ(d.geometry.kind, GeometryKind::Catenary);
  expectVec(d.geometry.start, 0, 0, 0);
  expectVec(d.geometry.end, 10, 0, 0);
  EXPECT_DOUBLE_EQ(d.geometry.length, 12.0);
  expectVec(d.geometry.sagDirection, 0, 0, -1);  // normalized

  ASSERT_EQ(s.supports.size(), 3u);
  EXPECT_EQ(s.supports[0].at.body, "a");
  EXPECT_EQ(s.supports[0].at.node, 0);
  EXPECT_EQ(s.supports[0].type, SupportType::Clamped);
  EXPECT_EQ(s.supports[1].at.body, "b");
  EXPECT_EQ(s.supports[1].at.node, -1);  // last
  EXPECT_EQ(s.supports[1].type, SupportType::Pinned);
  EXPECT_TRUE(s.supports[1].dofs.empty());
  EXPECT_EQ(s.supports[2].at.node, 12);
  EXPECT_EQ(s.supports[2].type, SupportType::Fixed);
  EXPECT_EQ(s.supports[2].dofs, (std::vector<int>{1, 2, 5}));
  EXPECT_EQ(s.supports[2].mark.where(), "dir/full.yaml:45: supports[2]");
  EXPECT_EQ(s.supports[2].at.mark.line, 45);

  ASSERT_EQ(s.junctions.size(), 1u);
  ASSERT_EQ(s.junctions[0].nodes.size(), 2u);
  EXPECT_EQ(s.junctions[0].nodes[0].body, "a");
  EXPECT_EQ(s.junctions[0].nodes[0].node, -1);
  EXPECT_EQ(s.junctions[0].nodes[1].body, "b");
  EXPECT_EQ(s.junctions[0].nodes[1].node, 0);
  EXPECT_EQ(s.junctions[0].mark.where(), "dir/full.yaml:47: junctions[0]");
  EXPECT_EQ(s.junctions[0].nodes[1].mark.key, "junctions[0].nodes[1]");

  expectVec(s.loads.gravity, 0, 0, -9.81);
  ASSERT_EQ(s.loads.nodal.size(), 2u);
  EXPECT_EQ(s.loads.nodal[0].at.body, "a");
  EXPECT_EQ(s.loads.nodal[0].at.node, 5);
  expectVec(s.loads.nodal[0].force, 1, 2, 3);
  expectVec(s.loads.nodal[0].moment, 4, 5, 6);
  EXPECT_EQ(s.loads.nodal[1].at.node, -1);
  expectVec(s.loads.nodal[1].moment, 0, 0, 0);  // default
  EXPECT_EQ(s.loads.nodal[1].mark.where(), "dir/full.yaml:52: loads.nodal[1]");
  ASSERT_EQ(s.loads.distributed.size(), 1u);
  EXPECT_EQ(s.loads.distributed[0].body, "d");
  expectVec(s.loads.distributed[0].forcePerLength, 0, 0, -2);
  EXPECT_EQ(s.loads.distributed[0].mark.line, 54);

  EXPECT_EQ(s.statics.loadSteps, 10);
  EXPECT_EQ(s.modes.count, 8);
  EXPECT_EQ(s.output.file, "out.h5");
  EXPECT_EQ(s.output.samplesPerElement, 3);
}

TEST(SceneReader, MinimalSceneGetsDefaults) {
  const SceneDescription s = parseScene(kBase3d, "scene.yaml");
  EXPECT_EQ(s.analysis, Analysis::Static);
  EXPECT_FALSE(s.discretization.slopeScaling);  // default off: docs/validation.md, "Conditioning"
  EXPECT_EQ(s.discretization.gaussPoints, 5);
  EXPECT_EQ(s.statics.loadSteps, 1);
  EXPECT_EQ(s.modes.count, 6);
  EXPECT_EQ(s.output.file, "");
  EXPECT_EQ(s.output.samplesPerElement, 4);
  expectVec(s.loads.gravity, 0, 0, 0);
  EXPECT_TRUE(s.junctions.empty());
  EXPECT_TRUE(s.loads.distributed.empty());
  const BodyDesc& b = s.bodies.at(0);
  EXPECT_DOUBLE_EQ(b.section.number("damping_axial"), 0.0);
  EXPECT_DOUBLE_EQ(b.section.number("damping_bending"), 0.0);
  EXPECT_FALSE(b.stressFreeInitial);
  EXPECT_TRUE(b.pointMasses.empty());
  expectVec(b.geometry.sagDirection, 0, 0, 0);
}

TEST(SceneReader, Scene2dAcceptsTwoEntryVectorsScalarMomentsAndInitialStressFree) {
  const std::string yaml =
      "analysis: static\n"
      "dimension: 2\n"
      "bodies:\n"
      "  - name: ring\n"
      "    element: AncfCable2d\n"
      "    elements: 4\n"
      "    geometry: {kind: arc, center: [1, 2], radius: 2, start_angle: 0, end_angle: 3.141592653589793}\n"
      "    section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}\n"
      "    stress_free: initial\n"
      "  - name: hang\n"
      "    element: AncfCable2d\n"
      "    elements: 4\n"
      "    geometry: {kind: catenary, start: [0, 0, 0], end: [4, 0], length: 5}\n"
      "    section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}\n"
      "supports:\n"
      "  - {body: ring, node: 0, type: fixed, dofs: [0, 1, 3]}\n"
      "loads:\n"
      "  gravity: [0, -9.81]\n"
      "  nodal:\n"
      "    - {body: ring, node: last, force: [1, 2, 0], moment: 7}\n"
      "    - {body: ring, node: 2, moment: [0, 0, -3]}\n";
  const SceneDescription s = parseScene(yaml, "ring.yaml");
  EXPECT_EQ(s.dimension, 2);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].kind, elements::findKind("AncfCable2d"));
  EXPECT_TRUE(s.bodies[0].stressFreeInitial);
  expectVec(s.bodies[0].geometry.center, 1, 2, 0);
  expectVec(s.bodies[0].geometry.normal, 0, 0, 1);  // default
  expectVec(s.bodies[1].geometry.start, 0, 0, 0);
  expectVec(s.bodies[1].geometry.end, 4, 0, 0);
  EXPECT_EQ(s.supports.at(0).dofs, (std::vector<int>{0, 1, 3}));
  expectVec(s.loads.gravity, 0, -9.81, 0);
  expectVec(s.loads.nodal.at(0).force, 1, 2, 0);
  expectVec(s.loads.nodal.at(0).moment, 0, 0, 7);
  expectVec(s.loads.nodal.at(1).moment, 0, 0, -3);
}

TEST_F(SceneFiles, ReadSceneReadsAPolylineCsvRelativeToTheSceneFile) {
  write("shapes/route.csv",
        "# x, y, z\n"
        "0, 0, 0\n"
        "\n"
        "1.5,0,0   # corner\n"
        "1.5, 2, 1e-1\n");
  const std::string path =
      write("scenes/../shapes/route.yaml",  // the CSV is next to the scene
            edit(kBase3d, "{kind: line, start: [0, 0, 0], end: [2, 0, 0]}", "{kind: polyline, file: route.csv}"));
  const SceneDescription s = readScene(path);
  EXPECT_EQ(s.file, path);
  const GeometryDesc& g = s.bodies.at(0).geometry;
  EXPECT_EQ(g.kind, GeometryKind::Polyline);
  ASSERT_EQ(g.points.size(), 3u);
  expectVec(g.points[0], 0, 0, 0);
  expectVec(g.points[1], 1.5, 0, 0);
  expectVec(g.points[2], 1.5, 2, 0.1);
}

TEST_F(SceneFiles, ReadSceneAcceptsTwoColumnCsvIn2d) {
  write("route.csv", "0,0\n1,0\n1,1\n");
  const std::string path =
      write("s.yaml", edit(kBase2d, "{kind: line, start: [0, 0], end: [2, 0]}", "{kind: polyline, file: route.csv}"));
  const SceneDescription s = readScene(path);
  ASSERT_EQ(s.bodies.at(0).geometry.points.size(), 3u);
  expectVec(s.bodies[0].geometry.points[2], 1, 1, 0);
}

// ------------------------------------------------------------------------------------------------
// Files and syntax

TEST_F(SceneFiles, MissingSceneFileNamesThePath) {
  const std::string path = (dir_ / "nope.yaml").string();
  const std::string msg = errorOf([&] { readScene(path); });
  EXPECT_NE(msg.find("cannot open scene file '" + path + "'"), std::string::npos) << msg;
  EXPECT_EQ(msg.rfind(path + ":", 0), 0u) << msg;
}

TEST_F(SceneFiles, ErrorsFromReadSceneNameTheGivenPath) {
  const std::string path = write("bad.yaml", edit(kBase3d, "E: 2.1e11", "E: -2e11"));
  EXPECT_EQ(errorOf([&] { readScene(path); }), path + ":8: bodies[0].section.E: must be positive (got -2e+11)");
}

TEST(SceneReader, SyntaxErrorGivesTheParserLine) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "end: [2, 0, 0]}", "end: [2, 0, 0}"), 7, "(syntax)", "illegal flow end"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "    elements: 20", "\telements: 20"), 6, "(syntax)", "tab"));
}

TEST(SceneReader, EmptyOrNonMapSceneIsRejected) {
  EXPECT_TRUE(failsWith("", 1, "(root)", "empty"));
  EXPECT_TRUE(failsWith("# only a comment\n", 1, "(root)", "empty"));
  EXPECT_TRUE(failsWith("- a\n- b\n", 1, "(root)", "expected a map"));
}

// ------------------------------------------------------------------------------------------------
// Keys

TEST(SceneReader, UnknownKeysAreRejectedAtEveryLevel) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "analysis: static", "analysis: static\nsolver: newton"), 2, "solver",
                        "unknown key; allowed: analysis, dimension, discretization, bodies"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850", "rho: 7850, Young: 1"), 8, "bodies[0].section.Young",
                        "unknown key; allowed: E, A, I, rho, damping_axial, damping_bending"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "    elements: 20", "    elements: 20\n    color: red"), 7, "bodies[0].color",
                        "unknown key"));
  // keys of another geometry kind
  EXPECT_TRUE(failsWith(edit(kBase3d, "end: [2, 0, 0]}", "end: [2, 0, 0], radius: 1}"), 7, "bodies[0].geometry.radius",
                        "unknown key; allowed: kind, start, end"));
  EXPECT_TRUE(
      failsWith(edit(kBase3d, "type: clamped}", "type: clamped, torque: 1}"), 10, "supports[0].torque", "unknown key"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "force: [0, 0, -1]}", "forces: [0, 0, -1]}"), 12, "loads.nodal[0].forces",
                        "unknown key; allowed: body, node, force, moment"));
  EXPECT_TRUE(failsWith(kBase3d + "static: {steps: 3}\n", 13, "static.steps", "unknown key; allowed: load_steps"));
}

TEST(SceneReader, DuplicateKeysAreRejected) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "dimension: 3", "dimension: 3\ndimension: 2"), 3, "dimension",
                        "duplicate key (first given on line 2)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850", "rho: 7850, A: 1"), 8, "bodies[0].section.A", "duplicate key"));
}

TEST(SceneReader, WrongTypesAreRejected) {
  EXPECT_TRUE(
      failsWith(edit(kBase3d, "E: 2.1e11", "E: steel"), 8, "bodies[0].section.E", "expected a number (got 'steel')"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "E: 2.1e11", "E: .inf"), 8, "bodies[0].section.E", "finite"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "elements: 20", "elements: 2.5"), 6, "bodies[0].elements",
                        "expected an integer (got '2.5')"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "dimension: 3", "dimension: three"), 2, "dimension", "expected an integer"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "start: [0, 0, 0]", "start: 0"), 7, "bodies[0].geometry.start",
                        "expected a list (got '0')"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "start: [0, 0, 0]", "start: [0, zero, 0]"), 7, "bodies[0].geometry.start[1]",
                        "expected a number"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}", "    section: 5"),
                        8, "bodies[0].section", "expected a map (got '5')"));
  EXPECT_TRUE(
      failsWith(edit(kBase3d, "name: cable", "name: [cable]"), 4, "bodies[0].name", "expected a string (got a list)"));
  EXPECT_TRUE(failsWith("analysis: static\ndimension: 3\nbodies: {}\n", 3, "bodies", "expected a list (got a map)"));
  EXPECT_TRUE(failsWith(kBase3d + "discretization: {slope_scaling: maybe}\n", 13, "discretization.slope_scaling",
                        "expected true or false"));
}

TEST(SceneReader, VectorsOfTheWrongLengthAreRejected) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "end: [2, 0, 0]", "end: [2, 0]"), 7, "bodies[0].geometry.end",
                        "expected 3 numbers (got 2)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "force: [0, 0, -1]", "force: [0, 0, -1, 0]"), 12, "loads.nodal[0].force",
                        "expected 3 numbers (got 4)"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "end: [2, 0]", "end: [2, 0, 0, 0]"), 7, "bodies[0].geometry.end",
                        "expected 2 or 3 numbers (got 4)"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "end: [2, 0]", "end: [2]"), 7, "bodies[0].geometry.end",
                        "expected 2 or 3 numbers (got 1)"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "end: [2, 0]", "end: [2, 0, 1]"), 7, "bodies[0].geometry.end",
                        "the third number must be 0 in a 2D scene (got 1)"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "force: [0, -1]}", "moment: [1, 0]}"), 12, "loads.nodal[0].moment",
                        "a 2D moment acts about z"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "force: [0, -1]}", "moment: [1, 0, 2]}"), 12, "loads.nodal[0].moment",
                        "a 2D moment acts about z"));
}

TEST(SceneReader, MissingRequiredValuesAreRejected) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "E: 2.1e11, ", ""), 8, "bodies[0].section.E", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "E: 2.1e11, ", "E: , "), 8, "bodies[0].section.E", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "analysis: static\n", ""), 1, "analysis", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "dimension: 3\n", ""), 1, "dimension", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "name: cable\n    ", ""), 4, "bodies[0].name", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "    elements: 20\n", ""), 4, "bodies[0].elements", "missing"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "kind: line, ", ""), 7, "bodies[0].geometry.kind", "missing"));
  EXPECT_TRUE(failsWith(edit(kBase3d, ", end: [2, 0, 0]", ""), 7, "bodies[0].geometry.end", "missing"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n", ""), 4,
                        "bodies[0].section", "missing"));
  EXPECT_TRUE(failsWith(edit(kBase3d, ", type: clamped", ""), 10, "supports[0].type", "missing"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "node: 0, ", ""), 10, "supports[0].node", "missing"));
  EXPECT_TRUE(failsWith("analysis: static\ndimension: 3\n", 1, "bodies", "missing required value"));
  EXPECT_TRUE(failsWith("analysis: static\ndimension: 3\nbodies: []\n", 3, "bodies", "at least one body"));
  EXPECT_TRUE(failsWith(kBase3d + "  distributed: [{body: cable}]\n", 13, "loads.distributed[0]",
                        "needs a 'force_per_length' or a 'spin_torque_per_length'"));
}

// ------------------------------------------------------------------------------------------------
// Ranges

TEST(SceneReader, NonPositiveSectionValuesAreRejected) {
  const std::string msg = errorOf([] { parseScene(edit(kBase3d, "E: 2.1e11", "E: -2e11"), "cable.yaml"); });
  EXPECT_EQ(msg, "cable.yaml:8: bodies[0].section.E: must be positive (got -2e+11)");
  EXPECT_TRUE(failsWith(edit(kBase3d, "A: 7.85e-5", "A: 0"), 8, "bodies[0].section.A", "must be positive (got 0)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "I: 4.91e-10", "I: -1"), 8, "bodies[0].section.I", "must be positive"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850", "rho: 0.0"), 8, "bodies[0].section.rho", "must be positive"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850", "rho: 7850, damping_axial: -0.1"), 8,
                        "bodies[0].section.damping_axial", "must not be negative (got -0.1)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850", "rho: 7850, damping_bending: -1"), 8,
                        "bodies[0].section.damping_bending", "must not be negative"));
}

TEST(SceneReader, CountsOutOfRangeAreRejected) {
  EXPECT_TRUE(
      failsWith(edit(kBase3d, "elements: 20", "elements: 0"), 6, "bodies[0].elements", "must be at least 1 (got 0)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "dimension: 3", "dimension: 4"), 2, "dimension", "must be 2 or 3 (got 4)"));
  EXPECT_TRUE(failsWith(kBase3d + "discretization: {gauss_points: 9}\n", 13, "discretization.gauss_points",
                        "must be 2..8 (got 9)"));
  EXPECT_TRUE(failsWith(kBase3d + "static: {load_steps: 0}\n", 13, "static.load_steps", "at least 1"));
  EXPECT_TRUE(failsWith(kBase3d + "modes: {count: -2}\n", 13, "modes.count", "at least 1"));
  EXPECT_TRUE(
      failsWith(kBase3d + "output: {samples_per_element: 0}\n", 13, "output.samples_per_element", "at least 1"));
  EXPECT_TRUE(failsWith(kBase3d + "output: {file: ''}\n", 13, "output.file", "empty"));
}

TEST(SceneReader, PointMassesAreCheckedAgainstTheBodyLength) {
  const std::string withMass = edit(kBase3d, "rho: 7850}\n", "rho: 7850}\n    point_masses: [{at: AT, mass: M}]\n");
  EXPECT_NO_THROW(parseScene(edit(edit(withMass, "AT", "2"), "M", "1"), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(edit(withMass, "AT", "2.1"), "M", "1"), 9, "bodies[0].point_masses[0].at",
                        "must be within [0, 2]"));
  EXPECT_TRUE(
      failsWith(edit(edit(withMass, "AT", "-0.5"), "M", "1"), 9, "bodies[0].point_masses[0].at", "must be within"));
  EXPECT_TRUE(
      failsWith(edit(edit(withMass, "AT", "1"), "M", "0"), 9, "bodies[0].point_masses[0].mass", "must be positive"));
  EXPECT_TRUE(
      failsWith(edit(edit(withMass, "AT", "1"), "M", "-3"), 9, "bodies[0].point_masses[0].mass", "must be positive"));
  // arc length of a half circle of radius 2 is 2*pi
  const std::string arc = edit(edit(withMass, "{kind: line, start: [0, 0, 0], end: [2, 0, 0]}",
                                    "{kind: arc, center: [0, 0, 0], radius: 2, start_angle: 0, end_angle: -3.14159}"),
                               "M", "1");
  EXPECT_NO_THROW(parseScene(edit(arc, "AT", "6.28"), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(arc, "AT", "6.3"), 9, "bodies[0].point_masses[0].at", "must be within [0, 6.28318]"));
}

// ------------------------------------------------------------------------------------------------
// Geometry

const std::string kLine = "{kind: line, start: [0, 0, 0], end: [2, 0, 0]}";

TEST(SceneReader, LineNeedsTwoDistinctEnds) {
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, "{kind: line, start: [1, 1, 1], end: [1, 1, 1]}"), 7,
                        "bodies[0].geometry.end", "zero length"));
}

TEST(SceneReader, ArcChecks) {
  const std::string arc = "{kind: arc, center: [0, 0, 0], radius: R, start_angle: 0.5, end_angle: A1}";
  const auto scene = [&](const std::string& r, const std::string& a1) {
    return edit(kBase3d, kLine, edit(edit(arc, "R", r), "A1", a1));
  };
  EXPECT_NO_THROW(parseScene(scene("1", "2"), "scene.yaml"));
  EXPECT_TRUE(failsWith(scene("1", "0.5"), 7, "bodies[0].geometry.end_angle", "must differ from start_angle"));
  EXPECT_TRUE(failsWith(scene("0", "2"), 7, "bodies[0].geometry.radius", "must be positive (got 0)"));
  EXPECT_TRUE(failsWith(scene("-1", "2"), 7, "bodies[0].geometry.radius", "must be positive"));
  EXPECT_TRUE(failsWith(scene("1", "7"), 7, "bodies[0].geometry.end_angle", "more than once"));
  EXPECT_TRUE(failsWith(scene("1", "2, normal: [0, 0, 0]"), 7, "bodies[0].geometry.normal", "zero vector"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "{kind: line, start: [0, 0], end: [2, 0]}",
                             "{kind: arc, center: [0, 0], radius: 1, start_angle: 0, end_angle: 1, normal: [0, 0, 1]}"),
                        7, "bodies[0].geometry.normal", "only allowed when dimension is 3"));
}

TEST(SceneReader, CatenaryChecks) {
  const std::string cat = "{kind: catenary, start: [0, 0, 0], end: [3, 4, 0], length: L}";
  EXPECT_NO_THROW(parseScene(edit(kBase3d, kLine, edit(cat, "L", "5.01")), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, edit(cat, "L", "5")), 7, "bodies[0].geometry.length",
                        "must exceed the distance between start and end (length 5 <= distance 5)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, edit(cat, "L", "4")), 7, "bodies[0].geometry.length", "must exceed"));
  EXPECT_TRUE(
      failsWith(edit(kBase3d, kLine, edit(cat, "L", "-4")), 7, "bodies[0].geometry.length", "must be positive"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, edit(cat, "L}", "6, sag_direction: [3, 4, 0]}")), 7,
                        "bodies[0].geometry.sag_direction", "parallel"));
  // Without sag_direction the cable hangs along -z (no gravity) or along gravity.
  const std::string vertical = "{kind: catenary, start: [0, 0, 0], end: [0, 0, 3], length: 4}";
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, vertical), 7, "bodies[0].geometry", "parallel"));
  EXPECT_NO_THROW(parseScene(edit(kBase3d, kLine, edit(cat, "L", "6")) + "  gravity: [0, 0, -9.81]\n", "s.yaml"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, edit(cat, "L", "6")) + "  gravity: [3, 4, 0]\n", 7, "bodies[0].geometry",
                        "default sag direction (gravity)"));
}

TEST(SceneReader, PolylineChecks) {
  const auto poly = [](const std::string& points) {
    return edit(kBase3d, kLine, "{kind: polyline, points: " + points + "}");
  };
  EXPECT_NO_THROW(parseScene(poly("[[0, 0, 0], [1, 0, 0]]"), "scene.yaml"));
  EXPECT_TRUE(failsWith(poly("[[0, 0, 0]]"), 7, "bodies[0].geometry.points", "at least 2 points (got 1)"));
  EXPECT_TRUE(failsWith(poly("[]"), 7, "bodies[0].geometry.points", "at least 2 points (got 0)"));
  EXPECT_TRUE(
      failsWith(poly("[[0, 0, 0], [1, 0, 0], [1, 0, 0]]"), 7, "bodies[0].geometry.points[2]", "zero-length segment"));
  EXPECT_TRUE(failsWith(poly("[[0, 0, 0], [1, 0]]"), 7, "bodies[0].geometry.points[1]", "expected 3 numbers"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, "{kind: polyline}"), 7, "bodies[0].geometry.points",
                        "missing required value (give points or file)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, kLine, "{kind: polyline, points: [[0, 0, 0], [1, 0, 0]], file: a.csv}"), 7,
                        "bodies[0].geometry.file", "either points or file"));
}

TEST_F(SceneFiles, PolylineCsvProblemsNameTheFileKeyAndCsvLine) {
  const std::string scene = edit(kBase3d, kLine, "{kind: polyline, file: route.csv}");
  const std::string path = write("s.yaml", scene);
  const std::string csv = (dir_ / "route.csv").string();
  const auto check = [&](const std::string& word) {
    const std::string msg = errorOf([&] { readScene(path); });
    EXPECT_EQ(msg.rfind(path + ":7: bodies[0].geometry.file: ", 0), 0u) << msg;
    EXPECT_NE(msg.find(word), std::string::npos) << msg << "\n  lacks: " << word;
  };
  check("cannot open polyline file '" + csv + "'");  // not written yet
  write("route.csv", "0,0,0\n1,0,0\n# comment\n1,x,0\n");
  check("'" + csv + "' line 4: expected comma-separated numbers");
  write("route.csv", "0,0,0\n1,0\n");
  check("'" + csv + "' line 2: expected 3 numbers (got 2)");
  write("route.csv", "0,0,0\n1,0,0\n\n1,0,0\n");
  check("zero-length segment between lines 2 and 4");
  write("route.csv", "# nothing but\n0,0,0\n");
  check("at least 2 points (got 1)");
}

TEST(SceneReader, UnknownChoicesListTheAllowedValues) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "analysis: static", "analysis: transient"), 1, "analysis",
                        "unknown analysis 'transient'; allowed: static, modes, dynamic"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "element: AncfCable3d", "element: Beam3d"), 5, "bodies[0].element",
                        "unknown element type 'Beam3d'; allowed: AncfCable2d, AncfCable3d"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "kind: line", "kind: helix"), 7, "bodies[0].geometry.kind",
                        "unknown geometry kind 'helix'; allowed: line, arc, polyline, catenary"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "type: clamped", "type: welded"), 10, "supports[0].type",
                        "unknown support type 'welded'; allowed: clamped, clamped_unstretched, pinned, fixed"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850}\n", "rho: 7850}\n    stress_free: curved\n"), 9,
                        "bodies[0].stress_free", "unknown stress_free 'curved'; allowed: straight, initial"));
}

// ------------------------------------------------------------------------------------------------
// References, dimension and supports

TEST(SceneReader, ReferencesToUnknownBodiesAreRejected) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "{body: cable, node: 0", "{body: rope, node: 0"), 10, "supports[0].body",
                        "no body named 'rope'; bodies: cable"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "{body: cable, node: last", "{body: rope, node: last"), 12, "loads.nodal[0].body",
                        "no body named 'rope'"));
  EXPECT_TRUE(failsWith(kBase3d + "  distributed: [{body: rope, force_per_length: [0, 0, 1]}]\n", 13,
                        "loads.distributed[0].body", "no body named 'rope'"));
  EXPECT_TRUE(failsWith(kBase3d + "junctions:\n  - nodes: [{body: cable, node: 0}, {body: rope, node: 0}]\n", 14,
                        "junctions[0].nodes[1].body", "no body named 'rope'"));
}

TEST(SceneReader, NodeIndicesMustExist) {
  EXPECT_NO_THROW(parseScene(edit(kBase3d, "node: 0", "node: 20"), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "node: 0", "node: 21"), 10, "supports[0].node",
                        "node index out of range: body 'cable' has nodes 0..20 or 'last' (got 21)"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "node: 0", "node: -1"), 10, "supports[0].node", "out of range"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "node: last", "node: first"), 12, "loads.nodal[0].node",
                        "expected a node index or 'last' (got 'first')"));
}

TEST(SceneReader, DuplicateBodyNamesAreRejected) {
  const std::string second =
      "  - name: cable\n"
      "    element: AncfCable3d\n"
      "    elements: 2\n"
      "    geometry: {kind: line, start: [0, 0, 0], end: [0, 1, 0]}\n"
      "    section: {E: 1, A: 1, I: 1, rho: 1}\n";
  EXPECT_TRUE(failsWith(edit(kBase3d, "supports:\n", second + "supports:\n"), 9, "bodies[1].name",
                        "duplicate body name 'cable' (also bodies[0] on line 4)"));
}

TEST(SceneReader, JunctionChecks) {
  EXPECT_TRUE(failsWith(kBase3d + "junctions:\n  - nodes: [{body: cable, node: 0}]\n", 14, "junctions[0].nodes",
                        "at least 2 nodes (got 1)"));
  EXPECT_TRUE(failsWith(kBase3d + "junctions:\n  - nodes: [{body: cable, node: last}, {body: cable, node: 20}]\n", 14,
                        "junctions[0].nodes[1]", "the same node as junctions[0].nodes[0]"));
  EXPECT_TRUE(failsWith(kBase3d + "junctions:\n  - nodes: [{body: cable, node: 0, slope: 1}, {body: cable, node: 2}]\n",
                        14, "junctions[0].nodes[0].slope", "unknown key; allowed: body, node"));
}

TEST(SceneReader, ElementTypeMustMatchTheDimension) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "element: AncfCable3d", "element: AncfCable2d"), 5, "bodies[0].element",
                        "AncfCable2d needs dimension: 2 (dimension mismatch: the scene has dimension: 3)"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "element: AncfCable2d", "element: AncfCable3d"), 5, "bodies[0].element",
                        "dimension mismatch"));
}

TEST(SceneReader, InitialStressFreeOnlyIn2d) {
  EXPECT_NO_THROW(parseScene(edit(kBase2d, "rho: 7850}\n", "rho: 7850}\n    stress_free: initial\n"), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(kBase3d, "rho: 7850}\n", "rho: 7850}\n    stress_free: initial\n"), 9,
                        "bodies[0].stress_free", "only allowed when dimension is 2"));
}

TEST(SceneReader, FixedSupportDofs) {
  const auto support = [](const std::string& base, const std::string& s) {
    return edit(base, "{body: cable, node: 0, type: clamped}", "{body: cable, node: 0, " + s + "}");
  };
  EXPECT_NO_THROW(parseScene(support(kBase3d, "type: fixed, dofs: [0, 5]"), "scene.yaml"));
  EXPECT_TRUE(failsWith(support(kBase3d, "type: fixed"), 10, "supports[0].dofs", "missing required value"));
  EXPECT_TRUE(failsWith(support(kBase3d, "type: fixed, dofs: []"), 10, "supports[0].dofs", "at least one"));
  EXPECT_TRUE(
      failsWith(support(kBase3d, "type: fixed, dofs: [1, 6]"), 10, "supports[0].dofs[1]", "must be 0..5 (got 6)"));
  EXPECT_TRUE(failsWith(support(kBase2d, "type: fixed, dofs: [4]"), 10, "supports[0].dofs[0]", "must be 0..3 (got 4)"));
  EXPECT_TRUE(failsWith(support(kBase3d, "type: fixed, dofs: [1, 1]"), 10, "supports[0].dofs[1]", "listed twice"));
  EXPECT_TRUE(
      failsWith(support(kBase3d, "type: pinned, dofs: [1]"), 10, "supports[0].dofs", "only allowed with type: fixed"));
}

// ------------------------------------------------------------------------------------------------
// Documentation

// requirement: every complete example in docs/scene-reference.md (a ```yaml block starting with
// "# scene:") is a valid scene.
TEST(SceneReader, DocumentationExamplesParse) {
  const std::string path = std::string(STRAND_DOCS_DIR) + "/scene-reference.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  int examples = 0;
  std::string line, block;
  bool inBlock = false;
  while (std::getline(in, line)) {
    if (!inBlock && line == "```yaml") {
      inBlock = true;
      block.clear();
    } else if (inBlock && line == "```") {
      inBlock = false;
      if (block.rfind("# scene:", 0) != 0) continue;
      ++examples;
      EXPECT_NO_THROW(parseScene(block, "docs example")) << block;
    } else if (inBlock) {
      block += line + "\n";
    }
  }
  EXPECT_GE(examples, 4);
}

// requirement (issue 3): the dynamics section is read with its defaults, and every wrong value
// names its line and key.
TEST(SceneReader, DynamicsSection) {
  const std::string dyn = edit(kBase2d, "analysis: static", "analysis: dynamic") +
                          "dynamics: {integrator: generalized_alpha, rho_inf: 0.8, dt: 1e-3, t_end: 2}\n";  // line 13
  const model::SceneDescription s = parseScene(dyn, "scene.yaml");
  EXPECT_EQ(s.analysis, model::Analysis::Dynamic);
  EXPECT_EQ(s.dynamics.integrator, model::Integrator::GeneralizedAlpha);
  EXPECT_DOUBLE_EQ(s.dynamics.rhoInf, 0.8);
  EXPECT_DOUBLE_EQ(s.dynamics.dt, 1e-3);
  EXPECT_DOUBLE_EQ(s.dynamics.tEnd, 2.0);
  EXPECT_EQ(s.dynamics.outputEvery, 1);
  EXPECT_TRUE(failsWith(edit(kBase2d, "analysis: static", "analysis: dynamic"), 1, "analysis",
                        "analysis 'dynamic' needs a 'dynamics' section"));
  EXPECT_TRUE(failsWith(edit(dyn, "rho_inf: 0.8", "rho_inf: 1.2"), 13, "dynamics.rho_inf", "must lie in [0, 1]"));
  EXPECT_TRUE(failsWith(edit(dyn, "generalized_alpha", "newmark"), 13, "dynamics.rho_inf",
                        "only used by integrator: generalized_alpha"));
  EXPECT_TRUE(failsWith(edit(dyn, "integrator: generalized_alpha, rho_inf: 0.8", "integrator: hht, hht_alpha: 0.5"), 13,
                        "dynamics.hht_alpha", "must lie in [0, 1/3]"));
  EXPECT_TRUE(failsWith(edit(dyn, "integrator: generalized_alpha", "integrator: euler"), 13, "dynamics.integrator",
                        "unknown integrator 'euler'; allowed: generalized_alpha, newmark, hht, bdf, rk4, abm4"));
  // the first-order integrators and their keys
  const std::string bdf = edit(dyn, "integrator: generalized_alpha, rho_inf: 0.8",
                               "integrator: bdf, bdf_order: 3, adaptive: true, rtol: 1e-5, atol: 1e-8");
  const model::SceneDescription b = parseScene(bdf, "scene.yaml");
  EXPECT_EQ(b.dynamics.integrator, model::Integrator::Bdf);
  EXPECT_EQ(b.dynamics.bdfOrder, 3);
  EXPECT_TRUE(b.dynamics.adaptive);
  EXPECT_DOUBLE_EQ(b.dynamics.rtol, 1e-5);
  EXPECT_DOUBLE_EQ(b.dynamics.atol, 1e-8);
  EXPECT_EQ(parseScene(edit(dyn, "integrator: generalized_alpha, rho_inf: 0.8", "integrator: abm4"), "s.yaml")
                .dynamics.integrator,
            model::Integrator::Abm4);
  EXPECT_TRUE(failsWith(edit(bdf, "bdf_order: 3", "bdf_order: 6"), 13, "dynamics.bdf_order", "must lie in 1..5"));
  EXPECT_TRUE(failsWith(edit(bdf, "integrator: bdf", "integrator: rk4"), 13, "dynamics.bdf_order",
                        "only used by integrator: bdf"));
  EXPECT_TRUE(failsWith(edit(bdf, "adaptive: true", "adaptive: false"), 13, "dynamics.rtol",
                        "only used with integrator: bdf and adaptive: true"));
  EXPECT_TRUE(failsWith(edit(dyn, "integrator: generalized_alpha, rho_inf: 0.8", "integrator: rk4, adaptive: true"), 13,
                        "dynamics.adaptive", "only used by integrator: bdf"));
  // step cuts (the second-order integrators' remedy for a failed Newton)
  EXPECT_EQ(parseScene(edit(dyn, "dt: 1e-3", "dt: 1e-3, step_cuts: 3"), "s.yaml").dynamics.stepCuts, 3);
  EXPECT_EQ(s.dynamics.stepCuts, 0);
  EXPECT_TRUE(failsWith(edit(dyn, "dt: 1e-3", "dt: 1e-3, step_cuts: 11"), 13, "dynamics.step_cuts", "must be 0..10"));
  EXPECT_TRUE(failsWith(edit(bdf, "integrator: bdf", "integrator: bdf, step_cuts: 2"), 13, "dynamics.step_cuts",
                        "only used by integrator: generalized_alpha, newmark or hht"));
  EXPECT_TRUE(failsWith(edit(dyn, "dt: 1e-3", "dt: 3"), 13, "dynamics.dt", "larger than t_end"));
  EXPECT_TRUE(failsWith(edit(dyn, "dt: 1e-3", "dt: -1"), 13, "dynamics.dt", "must be positive"));
}

// requirement (issue 3): initial velocities of cables, time-dependent nodal forces and dt_out, with
// their checks.
TEST(SceneReader, InitialVelocityTimedLoadsAndDtOut) {
  const std::string dyn = edit(edit(kBase2d, "analysis: static", "analysis: dynamic"),
                               "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n",
                               "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"
                               "    initial_velocity: {linear: [1, 2], angular: 3, center: [1, 0]}\n") +  // line 9
                          "dynamics: {dt: 1e-3, t_end: 1, dt_out: 0.01}\n";                                 // line 14
  const model::SceneDescription s = parseScene(edit(dyn, "force: [0, -1]}", "force: [0, -1], function: {function: "
                                                                             "sine, amplitude: 2, frequency: 5}}"),
                                               "scene.yaml");
  EXPECT_TRUE(s.bodies[0].hasInitialVelocity);
  EXPECT_DOUBLE_EQ(s.bodies[0].linearVelocity[1], 2.0);
  EXPECT_DOUBLE_EQ(s.bodies[0].angularVelocity[2], 3.0);
  EXPECT_DOUBLE_EQ(s.bodies[0].velocityCenter[0], 1.0);
  ASSERT_EQ(s.loads.nodal.size(), 1u);
  EXPECT_TRUE(s.loads.nodal[0].timed);
  EXPECT_EQ(s.loads.nodal[0].function.kind, model::TimeFunction::Kind::Sine);
  EXPECT_DOUBLE_EQ(s.dynamics.dtOut, 0.01);
  EXPECT_TRUE(failsWith(edit(dyn, "analysis: dynamic", "analysis: static"), 9, "bodies[0].initial_velocity",
                        "initial velocities need analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(dyn, "angular: 3,", "spin: 3,"), 9, "bodies[0].initial_velocity.spin",
                        "unknown key; allowed: linear, angular, center"));
  EXPECT_TRUE(failsWith(edit(dyn, "force: [0, -1]}", "force: [0, -1], moment: 1, function: 2}"), 13,
                        "loads.nodal[0].function", "scales a force"));
  EXPECT_TRUE(failsWith(edit(kBase2d, "force: [0, -1]}", "force: [0, -1], function: 2}"), 12,
                        "loads.nodal[0].function", "time-dependent loads need analysis: dynamic"));
  const model::SceneDescription ramp = parseScene(
      edit(dyn, "  nodal: [{body: cable, node: last, force: [0, -1]}]\n",
           "  nodal: [{body: cable, node: last, force: [0, -1]}]\n  function: {function: ramp, value: 1, start: 0, end: 0.1}\n"),
      "scene.yaml");
  EXPECT_TRUE(ramp.loads.timed);
  EXPECT_EQ(ramp.loads.function.kind, model::TimeFunction::Kind::Ramp);
  {  // the cosine ramp 25 (1 - cos(pi (t - 1) / 0.5)) / 2 of Pechstein & Gerstmayr's load torque, exact derivatives
    const model::SceneDescription c = parseScene(
        edit(dyn, "  nodal: [{body: cable, node: last, force: [0, -1]}]\n",
             "  nodal: [{body: cable, node: last, force: [0, -1]}]\n  function: {function: cosine_ramp, value: 25, start: 1, end: 1.5}\n"),
        "scene.yaml");
    const model::TimeFunction& f = c.loads.function;
    const double pi = std::acos(-1.0), h = 1e-6;
    EXPECT_EQ(f.at(0.9).f, 0.0);
    EXPECT_EQ(f.at(2.0).f, 25.0);
    EXPECT_NEAR(f.at(1.25).f, 12.5, 1e-12);
    for (double t : {1.1, 1.3, 1.45}) {
      EXPECT_NEAR(f.at(t).f, 12.5 * (1.0 - std::cos(2.0 * pi * (t - 1.0))), 1e-12);
      EXPECT_NEAR(f.at(t).df, (f.at(t + h).f - f.at(t - h).f) / (2 * h), 1e-6);
      EXPECT_NEAR(f.at(t).ddf, (f.at(t + h).df - f.at(t - h).df) / (2 * h), 1e-4);
    }
  }
  EXPECT_TRUE(failsWith(edit(kBase2d, "  nodal: [{body: cable, node: last, force: [0, -1]}]\n",
                             "  nodal: [{body: cable, node: last, force: [0, -1]}]\n  function: 2\n"),
                        13, "loads.function", "time-dependent loads need analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(dyn, "dt_out: 0.01", "dt_out: 0.01, output_every: 3"), 14, "dynamics.dt_out",
                        "give either 'output_every' (steps) or 'dt_out' (seconds), not both"));
}

TEST(SceneReader, HubSupportAndTimeFunctions) {
  const std::string base = edit(kBase2d, "analysis: static", "analysis: dynamic") +
                           "dynamics: {dt: 1e-3, t_end: 2}\n";
  const std::string hub = edit(base, "  - {body: cable, node: 0, type: clamped}",
                               "  - {body: cable, node: 0, type: clamped, hub: {center: [0, 0], "
                               "angle: {function: spin_up, omega: 4, duration: 15}}}");
  const model::SceneDescription s = parseScene(hub, "scene.yaml");
  ASSERT_TRUE(s.supports[0].hub.present);
  EXPECT_EQ(s.supports[0].hub.angle.kind, model::TimeFunction::Kind::SpinUp);
  EXPECT_DOUBLE_EQ(s.supports[0].hub.angle.omega, 4.0);
  EXPECT_DOUBLE_EQ(s.supports[0].hub.angle.duration, 15.0);
  auto withAngle = [&](const std::string& angle) {
    return edit(hub, "{function: spin_up, omega: 4, duration: 15}", angle);
  };
  EXPECT_EQ(parseScene(withAngle("0.5"), "scene.yaml").supports[0].hub.angle.value, 0.5);
  const model::TimeFunction table =
      parseScene(withAngle("{function: table, time: [0, 1, 3], value: [0, 2, 2]}"), "s.yaml").supports[0].hub.angle;
  EXPECT_DOUBLE_EQ(table.at(0.5).f, 1.0);
  EXPECT_TRUE(failsWith(withAngle("{function: spline}"), 10, "supports[0].hub.angle.function",
                        "unknown time function 'spline'; allowed: constant, linear, ramp, cosine_ramp, sine, spin_up, table"));
  EXPECT_TRUE(failsWith(withAngle("{function: table, time: [0, 2, 1], value: [0, 1, 2]}"), 10,
                        "supports[0].hub.angle.time", "times must increase"));
  EXPECT_TRUE(failsWith(withAngle("{function: table, time: [0, 1], value: [0]}"), 10, "supports[0].hub.angle.value",
                        "needs one value per time"));
  EXPECT_TRUE(failsWith(withAngle("{function: ramp, start: 2, end: 1, value: 1}"), 10, "supports[0].hub.angle.end",
                        "must be later than start"));
  EXPECT_TRUE(failsWith(withAngle("{function: spin_up, omega: 4}"), 10, "supports[0].hub.angle.duration",
                        "missing required value"));
  EXPECT_TRUE(failsWith(edit(hub, "type: clamped, hub", "type: fixed, dofs: [0], hub"), 10, "supports[0].hub",
                        "a hub turns a clamped or pinned support"));
  EXPECT_TRUE(failsWith(edit(hub, "analysis: dynamic", "analysis: static"), 10, "supports[0].hub",
                        "only with analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(hub, "center: [0, 0], ", "center: [0, 0], axis: [0, 0, 1], "), 10,
                        "supports[0].hub.axis", "a 2D hub turns about z"));
}

TEST(SceneReader, RigidBodiesAndJoints) {
  const std::string base = kBase2d +
      "rigid_bodies:\n"                                                                   // 13
      "  - {name: hub, mass: 2, inertia: 0.5, position: [-0.5, 0], angle: 0.1,\n"          // 14
      "     velocity: [0, 1], angular_velocity: 2, fixed: [x, y]}\n"                      // 15
      "joints:\n"                                                                         // 16
      "  - {type: clamp, a: {body: cable, node: 0}, b: {body: hub, point: [0.5, 0]}}\n"    // 17
      "  - {type: distance, a: {body: cable, node: last}, b: {ground: [2, 1]}, length: 1}\n";  // 18
  const model::SceneDescription s = parseScene(base, "scene.yaml");
  ASSERT_EQ(s.rigidBodies.size(), 1u);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].inertia, 0.5);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].angularVelocity[2], 2.0);
  EXPECT_EQ(s.rigidBodies[0].fixed, (std::vector<int>{0, 1}));
  ASSERT_EQ(s.joints.size(), 2u);
  EXPECT_EQ(s.joints[0].type, model::JointType::Clamp);
  EXPECT_EQ(s.joints[0].b.kind, model::JointEndDesc::Kind::RigidPoint);
  EXPECT_DOUBLE_EQ(s.joints[0].b.point[0], 0.5);
  EXPECT_EQ(s.joints[1].a.kind, model::JointEndDesc::Kind::CableNode);
  EXPECT_EQ(s.joints[1].a.node, -1);
  EXPECT_DOUBLE_EQ(s.joints[1].length, 1.0);
  EXPECT_TRUE(failsWith(edit(base, "type: clamp,", "type: hinge,"), 17, "joints[0].type",
                        "unknown joint type 'hinge'; allowed: pin, revolute, spherical, distance, clamp"));
  EXPECT_TRUE(failsWith(edit(base, "b: {body: hub, point: [0.5, 0]}", "b: {body: hub, node: 0}"), 17,
                        "joints[0].b.node", "'hub' is a rigid body: give 'point' (body frame)"));
  EXPECT_TRUE(failsWith(edit(base, "a: {body: cable, node: 0}", "a: {body: hub}"), 17, "joints[0].a",
                        "a clamp holds a cable node"));
  EXPECT_TRUE(failsWith(edit(base, "fixed: [x, y]", "fixed: [x, z]"), 15, "rigid_bodies[0].fixed[1]",
                        "unknown coordinate 'z'; allowed: x, y, phi"));
  EXPECT_TRUE(failsWith(edit(base, "mass: 2,", "mass: 0,"), 14, "rigid_bodies[0].mass", "must be positive"));
  EXPECT_TRUE(failsWith(edit(base, "type: clamp,", "type: pin, length: 2,"), 17, "joints[0].length",
                        "only used by type: distance"));
  EXPECT_TRUE(failsWith(edit(base, "analysis: static", "analysis: modes"), 1, "analysis",
                        "modal analysis of rigid bodies and joints is not supported yet"));
  // a scene of rigid bodies only needs no cable body
  const model::SceneDescription r = parseScene(
      "analysis: dynamic\ndimension: 2\nrigid_bodies: [{name: rod, mass: 1, inertia: 0.1, position: [0.5, 0]}]\n"
      "joints: [{type: pin, a: {body: rod, point: [-0.5, 0]}, b: {ground: [0, 0]}}]\ndynamics: {dt: 1e-3, t_end: 1}\n",
      "rigid.yaml");
  EXPECT_TRUE(r.bodies.empty());
  // a driven rigid body: phi = angle + rotation(t), dynamics only, not also fixed or given a rate
  const std::string driven =
      "analysis: dynamic\ndimension: 2\nrigid_bodies: [{name: hub, mass: 1, inertia: 1, position: [0, 0], "
      "fixed: [x, y], rotation: {function: spin_up, omega: 4, duration: 15}}]\ndynamics: {dt: 1e-3, t_end: 1}\n";
  const model::SceneDescription dr = parseScene(driven, "driven.yaml");
  ASSERT_EQ(dr.rigidBodies.size(), 1u);
  EXPECT_TRUE(dr.rigidBodies[0].driven);
  EXPECT_EQ(dr.rigidBodies[0].rotation.kind, model::TimeFunction::Kind::SpinUp);
  EXPECT_TRUE(failsWith(edit(driven, "fixed: [x, y]", "fixed: [x, y, phi]"), 3, "rigid_bodies[0].rotation",
                        "phi is listed in 'fixed'"));
  EXPECT_TRUE(failsWith(edit(driven, "analysis: dynamic", "analysis: static"), 3, "rigid_bodies[0].rotation",
                        "a driven rotation needs analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(driven, "fixed: [x, y]", "fixed: [x, y], torque: 2"), 3, "rigid_bodies[0].rotation",
                        "a 'torque' on it would do nothing"));
  // 3D: driven about rotation_axis (normalized); the axis needs a rotation
  const std::string driven3d =
      "analysis: dynamic\ndimension: 3\nrigid_bodies: [{name: hub, mass: 1, inertia: [1, 2, 2], position: [0, 0, 0], "
      "fixed: [x, y, z], rotation: {function: linear, rate: 2}, rotation_axis: [0, 3, 4]}]\ndynamics: {dt: 1e-3, t_end: 1}\n";
  const model::SceneDescription d3 = parseScene(driven3d, "driven3d.yaml");
  ASSERT_EQ(d3.rigidBodies.size(), 1u);
  EXPECT_TRUE(d3.rigidBodies[0].driven);
  EXPECT_NEAR(d3.rigidBodies[0].rotationAxis[1], 0.6, 1e-15);
  EXPECT_NEAR(d3.rigidBodies[0].rotationAxis[2], 0.8, 1e-15);
  EXPECT_TRUE(failsWith(edit(driven3d, "rotation: {function: linear, rate: 2}, ", ""), 3,
                        "rigid_bodies[0].rotation_axis", "give 'rotation' too"));
  EXPECT_TRUE(failsWith(edit(driven3d, "[0, 3, 4]", "[0, 0, 0]"), 3, "rigid_bodies[0].rotation_axis",
                        "must not be the zero vector"));
  // the explicit integrators take no joints (no multipliers); the message says what to use; bdf
  // takes them on the GGL form or (constraint_form: index3) the plain index-3 form
  const std::string pinned =
      "analysis: dynamic\ndimension: 2\nrigid_bodies: [{name: rod, mass: 1, inertia: 0.1, position: [0.5, 0]}]\n"
      "joints: [{type: pin, a: {body: rod, point: [-0.5, 0]}, b: {ground: [0, 0]}}]\n"
      "dynamics: {integrator: rk4, dt: 1e-3, t_end: 1}\n";  // line 5
  EXPECT_TRUE(failsWith(pinned, 5, "dynamics.integrator", "explicit integrators (rk4, abm4) take problems without joints"));
  // a `clamped` hub support of a cable holds the turning slope direction by a multiplier: the
  // message names the support and the alternatives; clamped_unstretched (eliminated) runs on rk4
  const std::string hubClamp =
      "analysis: dynamic\ndimension: 2\nbodies: [{name: b, element: AncfCable2d, elements: 2, geometry: {kind: line, "
      "start: [0, 0], end: [1, 0]}, section: {E: 1e9, A: 1e-4, I: 1e-9, rho: 1000}}]\n"
      "supports: [{body: b, node: 0, type: clamped, hub: {angle: {function: linear, rate: 1}}}]\n"
      "dynamics: {integrator: rk4, dt: 1e-5, t_end: 1e-3}\n";  // line 5
  EXPECT_TRUE(failsWith(hubClamp, 5, "dynamics.integrator", "the `clamped` hub support at scene.yaml:4: supports[0]"));
  EXPECT_NO_THROW(parseScene(edit(hubClamp, "type: clamped,", "type: clamped_unstretched,"), "hc.yaml"));
  EXPECT_NO_THROW(parseScene(edit(hubClamp, "rk4", "bdf, constraint_form: index3"), "hc.yaml"));
  // type: sliding: an inner node of an ALE body, dynamics, material moved by nothing else
  const std::string ring =
      "analysis: dynamic\ndimension: 2\nbodies: [{name: r, element: AleCable2d, elements: 4, geometry: {kind: line, "
      "start: [0, 0], end: [0, -4]}, section: {E: 1e9, A: 1e-4, I: 1e-10, rho: 1000}}]\n"
      "supports: [{body: r, node: 2, type: sliding}]\n"
      "dynamics: {dt: 1e-3, t_end: 1e-2}\n";  // line 5
  EXPECT_NO_THROW(parseScene(ring, "ring.yaml"));
  EXPECT_TRUE(failsWith(edit(ring, "node: 2", "node: 0"), 4, "supports[0].node", "an inner node (1..3)"));
  EXPECT_TRUE(failsWith(edit(ring, "AleCable2d", "AncfCable2d"), 4, "supports[0].type", "only on an ALE body"));
  EXPECT_NO_THROW(parseScene(edit(ring, "rho: 1000}}", "rho: 1000}, payout: {function: linear, rate: 1}}"), "r.yaml"));
  EXPECT_TRUE(failsWith(edit(ring, "rho: 1000}}", "rho: 1000}, material_motion: {function: linear, rate: 1}}"), 4,
                        "supports[0].type", "not built on a body whose material moves"));
  EXPECT_TRUE(failsWith(edit(ring, "dt: 1e-3", "integrator: rk4, dt: 1e-3"), 5, "dynamics.integrator", "explicit"));
  // reels: on an ALE body's end, in dynamics; driven (rotation, starting at rest) or free (inertia,
  // torque, damping); not with another motion of the body's material
  const std::string reel =
      "analysis: dynamic\ndimension: 2\nbodies: [{name: r, element: AleCable2d, elements: 4, geometry: {kind: line, "
      "start: [0, 0], end: [0, -4]}, section: {E: 1e9, A: 1e-4, I: 1e-10, rho: 1000}}]\n"
      "supports: [{body: r, node: 0, type: pinned}]\n"
      "reels: [{name: w, body: r, radius: 0.5, inertia: 2, content: 10, damping: 1, torque: 3}]\n"  // line 5
      "dynamics: {dt: 1e-3, t_end: 1e-2}\n";
  const model::SceneDescription rs = parseScene(reel, "reel.yaml");
  ASSERT_EQ(rs.reels.size(), 1u);
  EXPECT_EQ(rs.reels[0].node, 0);
  EXPECT_FALSE(rs.reels[0].driven);
  EXPECT_DOUBLE_EQ(rs.reels[0].torque.at(0.0).f, 3.0);
  EXPECT_EQ(parseScene(edit(reel, "radius: 0.5", "node: last, radius: 0.5"), "reel.yaml").reels[0].node, -1);
  EXPECT_EQ(parseScene(edit(reel, "radius: 0.5", "node: 4, radius: 0.5"), "reel.yaml").reels[0].node, -1);  // the last
  EXPECT_TRUE(failsWith(edit(reel, "radius: 0.5", "node: 2, radius: 0.5"), 5, "reels[0].node", "0 or 'last'"));
  EXPECT_TRUE(failsWith(edit(reel, "AleCable2d", "AncfCable2d"), 5, "reels[0].body", "the material of an ALE body"));
  EXPECT_TRUE(failsWith(edit(reel, "rho: 1000}}", "rho: 1000}, payout: {function: linear, rate: 1}}"), 5,
                        "reels[0].body", "already moves by payout"));
  EXPECT_TRUE(failsWith(edit(reel, "inertia: 2,", ""), 5, "reels[0].inertia", ""));
  EXPECT_TRUE(failsWith(edit(reel, "radius: 0.5", "radius: -0.5"), 5, "reels[0].radius", "must be positive"));
  EXPECT_TRUE(failsWith(edit(reel, "damping: 1, torque: 3", "rotation: {function: spin_up, omega: 1, duration: 1}, damping: 1"),
                        5, "reels[0].damping", "only for a free reel"));
  EXPECT_TRUE(failsWith(edit(reel, "damping: 1, torque: 3", "rotation: {function: linear, rate: 1}"), 5,
                        "reels[0].rotation", "starts at rest"));
  EXPECT_TRUE(parseScene(edit(reel, "damping: 1, torque: 3", "rotation: {function: spin_up, omega: 1, duration: 1}"),
                         "reel.yaml").reels[0].driven);
  EXPECT_TRUE(failsWith(edit(reel, "analysis: dynamic", "analysis: static"), 5, "reels[0]", "only with analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(reel, "dt: 1e-3", "integrator: rk4, dt: 1e-3"), 6, "dynamics.integrator", "generalized_alpha"));
  EXPECT_EQ(parseScene(edit(pinned, "rk4", "bdf"), "p.yaml").dynamics.constraintForm,
            model::DynamicsDesc::ConstraintForm::Ggl);
  EXPECT_EQ(parseScene(edit(pinned, "rk4", "bdf, constraint_form: index3"), "p.yaml").dynamics.constraintForm,
            model::DynamicsDesc::ConstraintForm::Index3);
  EXPECT_TRUE(failsWith(edit(pinned, "rk4", "bdf, constraint_form: index2"), 5, "dynamics.constraint_form",
                        "ggl"));
  EXPECT_TRUE(failsWith(edit(pinned, "rk4", "generalized_alpha, constraint_form: ggl"), 5, "dynamics.constraint_form",
                        "only used by integrator: bdf in a scene with joints"));
}

// 3D rigid bodies: principal inertia [I1, I2, I3] (a real mass distribution), orientation by angle
// about axis, vectors in 3D; explicit integrators refuse them (their frame is held by multipliers);
// a driven one takes no initial angular velocity.
TEST(SceneReader, ThreeDimensionalRigidBodies) {
  const std::string base =
      "analysis: dynamic\ndimension: 3\n"
      "rigid_bodies: [{name: top, mass: 2, inertia: [0.3, 0.3, 0.2], position: [0, 0, 0.1], angle: 0.5,\n"  // line 3
      "                axis: [1, 0, 0], angular_velocity: [0, 0, 40], torque: [0, 0, 1], fixed: [x, y, z]}]\n"
      "dynamics: {integrator: bdf, dt: 1e-3, t_end: 1}\n";  // line 5
  const model::SceneDescription s = parseScene(base, "t.yaml");
  ASSERT_EQ(s.rigidBodies.size(), 1u);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].principalInertia[2], 0.2);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].axis[0], 1.0);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].angularVelocity[2], 40.0);
  EXPECT_DOUBLE_EQ(s.rigidBodies[0].torque[2], 1.0);
  EXPECT_EQ(s.rigidBodies[0].fixed, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(failsWith(edit(base, "[0.3, 0.3, 0.2]", "[0.05, 0.3, 0.2]"), 3, "rigid_bodies[0].inertia",
                        "I2 = 0.3 is not below the sum of the other two"));
  EXPECT_TRUE(failsWith(edit(base, "[0.3, 0.3, 0.2]", "0.3"), 3, "rigid_bodies[0].inertia", ""));
  EXPECT_TRUE(failsWith(edit(base, "axis: [1, 0, 0]", "axis: [0, 0, 0]"), 4, "rigid_bodies[0].axis", "must not be zero"));
  EXPECT_TRUE(failsWith(edit(base, "fixed: [x, y, z]", "fixed: [x, phi]"), 4, "rigid_bodies[0].fixed[1]",
                        "allowed: x, y, z"));
  // a 3D body may be driven (rotation, rotation_axis), but then its rate is the rotation's
  EXPECT_TRUE(failsWith(edit(base, "fixed: [x, y, z]", "rotation: {function: linear, rate: 1}"), 4,
                        "rigid_bodies[0].rotation", "the initial angular velocity of a driven body is the rotation's rate"));
  EXPECT_TRUE(failsWith(edit(base, "integrator: bdf", "integrator: rk4"), 5, "dynamics.integrator",
                        "a 3D rigid body's frame is held by six"));
}

// ------------------------------------------------------------------------------------------------
// hub_beam (seed 001): a scene of its own

namespace {

// A driven hub with an FEM beam; the hub_beam tests change one thing in it. Line numbers matter.
const std::string kHubBeam =                                           // line
    "analysis: dynamic\n"                                              // 1
    "hub_beam:\n"                                                      // 2
    "  beam: {length: 10, E: 70e9, A: 4e-4, I: 2e-7, rho: 3000}\n"     // 3
    "  hub:\n"                                                         // 4
    "    radius: 0.5\n"                                                // 5
    "    angle: {function: spin_up, omega: 4, duration: 15}\n"         // 6
    "  coupling: zero_order\n"                                         // 7
    "  discretization: {method: fem, elements: 8}\n"                   // 8
    "dynamics: {integrator: rk4, dt: 1e-3, t_end: 20}\n";              // 9

// kHubBeam with its discretization line replaced by `discretization` (still line 8).
std::string hubBeamWith(const std::string& discretization) {
  return edit(kHubBeam, "  discretization: {method: fem, elements: 8}\n", "  discretization: " + discretization + "\n");
}

}  // namespace

// requirement (issue 5): a driven hub with an FEM beam is read with every value, in 2D, without
// bodies or dimension; the explicit integrators are allowed (a hub_beam has no joints).
TEST(SceneReader, HubBeamDrivenFem) {
  const model::SceneDescription s = parseScene(kHubBeam, "hub.yaml");
  const model::HubBeamDesc& h = s.hubBeam;
  EXPECT_TRUE(h.present);
  EXPECT_EQ(h.mark.file, "hub.yaml");
  EXPECT_EQ(h.mark.line, 2);
  EXPECT_EQ(h.mark.key, "hub_beam");
  EXPECT_EQ(s.dimension, 2);
  EXPECT_EQ(s.analysis, model::Analysis::Dynamic);
  EXPECT_TRUE(s.bodies.empty());
  EXPECT_TRUE(s.supports.empty());
  EXPECT_DOUBLE_EQ(h.length, 10.0);
  EXPECT_DOUBLE_EQ(h.E, 70e9);
  EXPECT_DOUBLE_EQ(h.A, 4e-4);
  EXPECT_DOUBLE_EQ(h.I, 2e-7);
  EXPECT_DOUBLE_EQ(h.rho, 3000.0);
  EXPECT_DOUBLE_EQ(h.hubRadius, 0.5);
  EXPECT_TRUE(h.driven);
  EXPECT_EQ(h.angle.kind, model::TimeFunction::Kind::SpinUp);
  EXPECT_DOUBLE_EQ(h.angle.omega, 4.0);
  EXPECT_DOUBLE_EQ(h.angle.duration, 15.0);
  EXPECT_EQ(h.coupling, model::HubBeamCoupling::ZeroOrder);
  EXPECT_EQ(h.method, model::HubBeamMethod::Fem);
  EXPECT_EQ(h.elements, 8);
  EXPECT_EQ(s.dynamics.integrator, model::Integrator::Rk4);
  EXPECT_DOUBLE_EQ(s.dynamics.tEnd, 20.0);
  // defaults: first_order coupling, fem with 10 elements, hub radius 0; dimension: 2 may be given
  const model::SceneDescription d = parseScene(
      "analysis: dynamic\ndimension: 2\nhub_beam:\n  beam: {length: 1, E: 1, A: 1, I: 1, rho: 1}\n"
      "  hub: {angle: 0.5}\ndynamics: {dt: 1e-3, t_end: 1}\n",
      "defaults.yaml");
  EXPECT_EQ(d.hubBeam.coupling, model::HubBeamCoupling::FirstOrder);
  EXPECT_EQ(d.hubBeam.method, model::HubBeamMethod::Fem);
  EXPECT_EQ(d.hubBeam.elements, 10);
  EXPECT_DOUBLE_EQ(d.hubBeam.hubRadius, 0.0);
  EXPECT_EQ(d.hubBeam.angle.kind, model::TimeFunction::Kind::Constant);
  EXPECT_DOUBLE_EQ(d.hubBeam.angle.value, 0.5);
  // every integrator
  for (const char* integrator : {"generalized_alpha", "newmark", "hht", "bdf", "rk4", "abm4"})
    EXPECT_NO_THROW(parseScene(edit(kHubBeam, "integrator: rk4", std::string("integrator: ") + integrator), "hub.yaml"))
        << integrator;
  // an ordinary scene has no hubBeam
  EXPECT_FALSE(parseScene(kBase3d, "scene.yaml").hubBeam.present);
}

// requirement (issue 5): a free hub (inertia, torque, initial rate) with assumed modes.
TEST(SceneReader, HubBeamFreeHubModes) {
  const std::string yaml =
      "analysis: dynamic\n"                                                    // 1
      "dimension: 2\n"                                                         // 2
      "hub_beam:\n"                                                            // 3
      "  beam: {length: 8, E: 2e11, A: 1e-3, I: 1e-6, rho: 7800}\n"            // 4
      "  hub:\n"                                                               // 5
      "    inertia: 500\n"                                                     // 6
      "    torque: {function: ramp, value: 100, start: 0, end: 1}\n"           // 7
      "    rate: 0.5\n"                                                        // 8
      "  discretization: {method: modes, axial_modes: 2, bending_modes: 4}\n"  // 9
      "dynamics: {integrator: bdf, dt: 1e-3, t_end: 1}\n"                      // 10
      "output: {file: hub.h5}\n";                                              // 11
  const model::SceneDescription s = parseScene(yaml, "free.yaml");
  const model::HubBeamDesc& h = s.hubBeam;
  EXPECT_TRUE(h.present);
  EXPECT_EQ(h.mark.line, 3);
  EXPECT_FALSE(h.driven);
  EXPECT_DOUBLE_EQ(h.hubInertia, 500.0);
  EXPECT_EQ(h.torque.kind, model::TimeFunction::Kind::Ramp);
  EXPECT_DOUBLE_EQ(h.torque.value, 100.0);
  EXPECT_DOUBLE_EQ(h.torque.end, 1.0);
  EXPECT_DOUBLE_EQ(h.initialRate, 0.5);
  EXPECT_DOUBLE_EQ(h.hubRadius, 0.0);
  EXPECT_EQ(h.coupling, model::HubBeamCoupling::FirstOrder);
  EXPECT_EQ(h.method, model::HubBeamMethod::AssumedModes);
  EXPECT_EQ(h.axialModes, 2);
  EXPECT_EQ(h.bendingModes, 4);
  EXPECT_DOUBLE_EQ(h.length, 8.0);
  EXPECT_EQ(s.dimension, 2);
  EXPECT_EQ(s.dynamics.integrator, model::Integrator::Bdf);
  EXPECT_EQ(s.output.file, "hub.h5");
  // torque and rate default to zero
  const model::SceneDescription bare =
      parseScene(edit(edit(yaml, "    torque: {function: ramp, value: 100, start: 0, end: 1}\n", ""), "    rate: 0.5\n", ""),
                 "free.yaml");
  EXPECT_EQ(bare.hubBeam.torque.kind, model::TimeFunction::Kind::Constant);
  EXPECT_DOUBLE_EQ(bare.hubBeam.torque.value, 0.0);
  EXPECT_DOUBLE_EQ(bare.hubBeam.initialRate, 0.0);
  EXPECT_TRUE(failsWith(edit(yaml, "inertia: 500", "inertia: 0"), 6, "hub_beam.hub.inertia", "must be positive (got 0)"));
  EXPECT_TRUE(failsWith(edit(yaml, "bending_modes: 4", "bending_modes: 11"), 9, "hub_beam.discretization.bending_modes",
                        "must be 1..10 (got 11)"));
  EXPECT_TRUE(failsWith(edit(yaml, "axial_modes: 2", "axial_modes: 0"), 9, "hub_beam.discretization.axial_modes",
                        "must be 1..10 (got 0)"));
}

// requirement (issue 5): rpim reads all its keys; q must not make the multiquadric a polynomial.
TEST(SceneReader, HubBeamRpim) {
  const std::string rpim = hubBeamWith("{method: rpim, nodes: 15, alpha_c: 4, q: -0.5, alpha_s: 3, gauss_points: 6}");
  const model::HubBeamDesc h = parseScene(rpim, "rpim.yaml").hubBeam;
  EXPECT_EQ(h.method, model::HubBeamMethod::Rpim);
  EXPECT_EQ(h.nodes, 15);
  EXPECT_DOUBLE_EQ(h.alphaC, 4.0);
  EXPECT_DOUBLE_EQ(h.q, -0.5);
  EXPECT_DOUBLE_EQ(h.alphaS, 3.0);
  EXPECT_EQ(h.gaussPoints, 6);
  // defaults of rpim
  const model::HubBeamDesc d = parseScene(hubBeamWith("{method: rpim}"), "rpim.yaml").hubBeam;
  EXPECT_EQ(d.nodes, 11);
  EXPECT_DOUBLE_EQ(d.alphaC, 3.0);
  EXPECT_DOUBLE_EQ(d.q, 1.03);
  EXPECT_DOUBLE_EQ(d.alphaS, 2.5);
  EXPECT_EQ(d.gaussPoints, 4);
  EXPECT_NO_THROW(parseScene(edit(rpim, "q: -0.5", "q: 1.5"), "rpim.yaml"));
  EXPECT_NO_THROW(parseScene(edit(rpim, "q: -0.5", "q: -1"), "rpim.yaml"));
  EXPECT_TRUE(failsWith(edit(rpim, "q: -0.5", "q: 1"), 8, "hub_beam.discretization.q",
                        "must not be 0 or a positive integer: the multiquadric (r^2 + (alpha_c d_c)^2)^q is then a "
                        "polynomial and the moment matrix is singular (got 1)"));
  EXPECT_TRUE(failsWith(edit(rpim, "q: -0.5", "q: 0"), 8, "hub_beam.discretization.q", "must not be 0"));
  EXPECT_TRUE(failsWith(edit(rpim, "q: -0.5", "q: 2.0"), 8, "hub_beam.discretization.q", "(got 2)"));
  EXPECT_TRUE(failsWith(edit(rpim, "nodes: 15", "nodes: 2"), 8, "hub_beam.discretization.nodes", "must be at least 3 (got 2)"));
  EXPECT_TRUE(failsWith(edit(rpim, "alpha_c: 4", "alpha_c: 0"), 8, "hub_beam.discretization.alpha_c", "must be positive"));
  EXPECT_TRUE(failsWith(edit(rpim, "alpha_s: 3", "alpha_s: -1"), 8, "hub_beam.discretization.alpha_s", "must be positive"));
  EXPECT_TRUE(failsWith(edit(rpim, "gauss_points: 6", "gauss_points: 11"), 8, "hub_beam.discretization.gauss_points",
                        "must be 1..10 (got 11)"));
  EXPECT_TRUE(failsWith(edit(rpim, "nodes: 15", "nodes: 15, elements: 4"), 8, "hub_beam.discretization.elements",
                        "'elements' is a key of method fem (the method here is rpim)"));
}

// requirement (issue 5): every wrong hub_beam names its line and key.
TEST(SceneReader, HubBeamErrors) {
  // beam
  EXPECT_TRUE(failsWith(edit(kHubBeam, "E: 70e9, ", ""), 3, "hub_beam.beam.E", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "rho: 3000", "rho: -1"), 3, "hub_beam.beam.rho", "must be positive (got -1)"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "rho: 3000", "rho: 3000, nu: 0.3"), 3, "hub_beam.beam.nu",
                        "unknown key; allowed: length, E, A, I, rho"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "  beam: {length: 10, E: 70e9, A: 4e-4, I: 2e-7, rho: 3000}\n", ""), 2,
                        "hub_beam.beam", "missing required value"));
  // hub: exactly one of angle and inertia; torque and rate only for a free hub
  EXPECT_TRUE(failsWith(edit(kHubBeam, "    radius: 0.5\n", "    radius: 0.5\n    inertia: 500\n"), 4, "hub_beam.hub",
                        "give exactly one of 'angle' (a driven hub: its angle in time) and 'inertia' (a free hub)"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "    angle: {function: spin_up, omega: 4, duration: 15}\n", ""), 4, "hub_beam.hub",
                        "give exactly one of 'angle'"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "    radius: 0.5\n", "    radius: 0.5\n    torque: 5\n"), 6, "hub_beam.hub.torque",
                        "only for a free hub (with 'inertia'); a driven hub's motion is prescribed by 'angle'"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "    radius: 0.5\n", "    radius: 0.5\n    rate: 1\n"), 6, "hub_beam.hub.rate",
                        "a driven hub's motion is prescribed"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "radius: 0.5", "radius: -0.5"), 5, "hub_beam.hub.radius", "must not be negative"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "function: spin_up", "function: spin"), 6, "hub_beam.hub.angle.function",
                        "unknown time function 'spin'"));
  // coupling, method and the keys of another method
  EXPECT_TRUE(failsWith(edit(kHubBeam, "zero_order", "second_order"), 7, "hub_beam.coupling",
                        "unknown coupling 'second_order'; allowed: first_order, zero_order"));
  EXPECT_TRUE(failsWith(hubBeamWith("{method: galerkin}"), 8, "hub_beam.discretization.method",
                        "unknown method 'galerkin'; allowed: fem, modes, rpim"));
  EXPECT_TRUE(failsWith(hubBeamWith("{method: fem, elements: 8, nodes: 11}"), 8, "hub_beam.discretization.nodes",
                        "'nodes' is a key of method rpim (the method here is fem)"));
  EXPECT_TRUE(failsWith(hubBeamWith("{alpha_c: 3}"), 8, "hub_beam.discretization.alpha_c",
                        "'alpha_c' is a key of method rpim (the method here is fem)"));
  EXPECT_TRUE(failsWith(hubBeamWith("{method: modes, elements: 8}"), 8, "hub_beam.discretization.elements",
                        "'elements' is a key of method fem (the method here is modes)"));
  EXPECT_TRUE(failsWith(hubBeamWith("{elements: 0}"), 8, "hub_beam.discretization.elements", "must be at least 1 (got 0)"));
  EXPECT_TRUE(failsWith(hubBeamWith("{method: fem, points: 3}"), 8, "hub_beam.discretization.points",
                        "unknown key; allowed: method, elements, axial_modes, bending_modes, nodes, alpha_c, q, alpha_s, "
                        "gauss_points"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "  coupling: zero_order\n", "  coupling: zero_order\n  damping: 1\n"), 8,
                        "hub_beam.damping", "unknown key; allowed: beam, hub, coupling, discretization"));
  // the rest of the scene: no cable-scene keys, analysis dynamic with dynamics, dimension 2 if given
  EXPECT_TRUE(failsWith(kHubBeam + "bodies: []\n", 10, "bodies",
                        "a hub_beam scene has no 'bodies'; the beam is described under hub_beam"));
  EXPECT_TRUE(failsWith(kHubBeam + "supports: []\n", 10, "supports", "a hub_beam scene has no 'supports'"));
  EXPECT_TRUE(failsWith(kHubBeam + "loads: {gravity: [0, -9.81]}\n", 10, "loads", "a hub_beam scene has no 'loads'"));
  EXPECT_TRUE(failsWith(kHubBeam + "discretization: {gauss_points: 4}\n", 10, "discretization",
                        "a hub_beam scene has no 'discretization'"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "analysis: dynamic", "analysis: static"), 1, "analysis",
                        "a hub_beam scene is integrated in time: use analysis: dynamic (got 'static')"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "analysis: dynamic", "analysis: modes"), 1, "analysis", "use analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "analysis: dynamic\n", "analysis: dynamic\ndimension: 3\n"), 2, "dimension",
                        "a hub_beam turns in its plane: dimension must be 2 or left out (got 3)"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "dynamics: {integrator: rk4, dt: 1e-3, t_end: 20}\n", ""), 1, "analysis",
                        "analysis 'dynamic' needs a 'dynamics' section"));
  EXPECT_TRUE(failsWith(edit(kHubBeam, "dt: 1e-3", "dt: 0"), 9, "dynamics.dt", "must be positive"));
  EXPECT_TRUE(failsWith("analysis: dynamic\nhub_beam: 5\ndynamics: {dt: 1e-3, t_end: 1}\n", 2, "hub_beam",
                        "expected a map (got '5')"));
  // ordinary scenes still need dimension and bodies
  EXPECT_TRUE(failsWith("analysis: static\nbodies: []\n", 1, "dimension", "missing required value"));
}

// Element kinds: the scene's `element` picks the kind per body; its `section` keys and its
// `formulation` options are the kind's (elements::KindInfo), checked with file:line:key.
namespace {
const std::string kShear2d =
    "analysis: static\n"                                                          // 1
    "dimension: 2\n"                                                              // 2
    "bodies:\n"                                                                   // 3
    "  - name: belt\n"                                                            // 4
    "    element: AncfBeam2dShear\n"                                              // 5
    "    elements: 8\n"                                                           // 6
    "    geometry: {kind: line, start: [0, 0], end: [1, 0]}\n"                    // 7
    "    section: {E: 2.1e11, nu: 0.3, rho: 7850, width: 0.1, height: 0.02}\n"   // 8
    "    formulation: {integration: full}\n"                                      // 9
    "  - name: rope\n"                                                            // 10
    "    element: AncfCable2d\n"                                                  // 11
    "    elements: 4\n"                                                           // 12
    "    geometry: {kind: line, start: [1, 0], end: [2, 0]}\n"                    // 13
    "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"              // 14
    "junctions:\n"                                                                // 15
    "  - nodes: [{body: belt, node: last}, {body: rope, node: 0}]\n"              // 16
    "supports:\n"                                                                 // 17
    "  - {body: belt, node: 0, type: clamped}\n";                                 // 18
}  // namespace

TEST(SceneReader, ElementKindsMixInOneSceneWithTheirOwnSectionsAndOptions) {
  const SceneDescription s = parseScene(kShear2d, "scene.yaml");
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodyDesc& belt = s.bodies[0];
  EXPECT_EQ(belt.kind, elements::findKind("AncfBeam2dShear"));
  EXPECT_EQ(s.bodies[1].kind, elements::findKind("AncfCable2d"));
  EXPECT_DOUBLE_EQ(belt.section.number("height"), 0.02);
  EXPECT_DOUBLE_EQ(belt.section.number("nu"), 0.3);
  EXPECT_DOUBLE_EQ(belt.section.number("damping"), 0.0);  // optional keys take their defaults
  EXPECT_EQ(belt.section.option("integration"), "full");
  EXPECT_EQ(belt.section.option("elasticity"), "decoupled");  // the first value is the default
  const std::string linear = edit(edit(kShear2d, "AncfBeam2dShear", "AncfBeam2dLinear"), "    formulation: {integration: full}\n", "");
  EXPECT_EQ(parseScene(linear, "scene.yaml").bodies[0].section.option("integration"), "selective");
  // a point mass ratio is relative to the kind's rho A (here rho width height)
  const SceneDescription pm = parseScene(
      edit(kShear2d, "    formulation: {integration: full}\n",
           "    formulation: {integration: full}\n    point_masses: [{location: 1, mass_ratio: 2}]\n"),
      "scene.yaml");
  EXPECT_NEAR(pm.bodies[0].pointMasses[0].mass, 2.0 * 7850 * 0.1 * 0.02 * 1.0, 1e-9);
}

TEST(SceneReader, ElementKindErrorsNameTheKindsKeysAndValues) {
  EXPECT_TRUE(failsWith(edit(kShear2d, "AncfBeam2dShear", "AncfBeam2dTimoshenko"), 5, "bodies[0].element",
                        "unknown element type 'AncfBeam2dTimoshenko'; allowed: AncfCable2d, AncfCable3d, AncfBeam2dShear, "
                        "AncfBeam2dLinear"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "dimension: 2", "dimension: 3"), 5, "bodies[0].element",
                        "AncfBeam2dShear needs dimension: 2"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "nu: 0.3,", "nu: 0.3, A: 1,"), 8, "bodies[0].section.A",
                        "unknown key; allowed: E, nu, rho, width, height, shear_factor, damping"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "nu: 0.3", "nu: 0.5"), 8, "bodies[0].section.nu", "must be in [0, 0.5) (got 0.5)"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "height: 0.02", "height: 0"), 8, "bodies[0].section.height", "must be positive"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "width: 0.1, ", ""), 8, "bodies[0].section.width", "missing required value"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "integration: full", "integration: exact"), 9,
                        "bodies[0].formulation.integration", "unknown integration 'exact'; allowed: selective, full, reduced"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "integration: full", "poisson: off"), 9, "bodies[0].formulation.poisson",
                        "unknown key; allowed: integration, elasticity"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "rho: 7850}\njunctions", "rho: 7850}\n    formulation: {integration: full}\njunctions"),
                        15, "bodies[1].formulation", "AncfCable2d has no formulation options"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "    formulation: {integration: full}\n", "    stress_free: initial\n"), 9,
                        "bodies[0].stress_free", "'initial' is not available for AncfBeam2dShear"));
  // a node of the Shear kind has 3 blocks (r, r_x, r_y): fixed coordinates 0..5; the cable's 0..3
  EXPECT_NO_THROW(parseScene(edit(kShear2d, "type: clamped}", "type: fixed, dofs: [0, 1, 4, 5]}"), "scene.yaml"));
  EXPECT_TRUE(failsWith(edit(kShear2d, "{body: belt, node: 0, type: clamped}", "{body: rope, node: 2, type: fixed, dofs: [4]}"),
                        18, "supports[0].dofs[0]", "must be 0..3 (got 4)"));
}

// ALE bodies (issue 35): material_motion, payout and initial_stretch only on kinds with material
// coordinates; statics and modes about a steady flow (material_motion), not about a payout; no
// rotating frame.
TEST(SceneReader, AleBodiesAndTheirMotions) {
  const std::string ale = edit(edit(kBase2d, "element: AncfCable2d", "element: AleCable2d"),
                               "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n",
                               "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"
                               "    initial_stretch: 1.001\n");  // 9; supports from line 10
  const std::string flowing = edit(ale, "    initial_stretch: 1.001\n",
                                   "    initial_stretch: 1.001\n    material_motion: {function: linear, rate: -2}\n");
  const std::string modes = edit(flowing, "analysis: static", "analysis: modes");
  const model::SceneDescription s = parseScene(modes, "scene.yaml");
  EXPECT_DOUBLE_EQ(s.bodies[0].initialStretch, 1.001);
  EXPECT_TRUE(s.bodies[0].hasMaterialMotion);
  EXPECT_DOUBLE_EQ(s.bodies[0].materialMotion.at(3.0).df, -2.0);
  EXPECT_TRUE(parseScene(flowing, "scene.yaml").bodies[0].hasMaterialMotion);  // statics: the steady flow's state
  EXPECT_TRUE(failsWith(edit(modes, "material_motion: {function: linear, rate: -2}", "payout: {function: linear, rate: 1}"),
                        4, "bodies[0]", "payout is a motion in time"));
  // a cable takes a pretension too (issue 34: belts), as its elements' reference length
  EXPECT_DOUBLE_EQ(parseScene(edit(kBase2d, "    elements: 20\n", "    elements: 20\n    initial_stretch: 1.1\n"), "scene.yaml")
                       .bodies[0].initialStretch, 1.1);
  const model::SceneDescription sw =
      parseScene(modes + "sweep: {parameter: transport_speed, from: 0, to: 40, points: 5}\n", "scene.yaml");
  EXPECT_EQ(sw.sweep.parameter, model::SweepParameter::TransportSpeed);
  EXPECT_TRUE(failsWith(edit(kBase2d, "analysis: static", "analysis: modes") +
                            "sweep: {parameter: transport_speed, from: 0, to: 40, points: 5}\n",
                        13, "sweep", "a transport_speed sweep moves the material of ALE bodies"));
  EXPECT_TRUE(failsWith(modes + "rotation: {omega: 1}\n", 15, "rotation",
                        "a rotating frame with AleCable2d bodies is not built"));
}

// material_nodes (issue 35): listed nodes of an ALE body at an arc length, optionally moving; the
// arc lengths must rise with the node index; not with material_motion; moving ones only in dynamics.
TEST(SceneReader, AleMaterialNodes) {
  const std::string ale = edit(edit(kBase2d, "element: AncfCable2d", "element: AleCable2d"), "analysis: static",
                               "analysis: dynamic");
  const std::string withNodes =
      edit(ale, "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n",
           "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n"
           "    material_nodes: [{node: 10, at: 0.1, motion: {function: linear, rate: 3}}, {node: last}]\n") +
      "dynamics: {dt: 0.001, t_end: 0.01}\n";
  const model::SceneDescription s = parseScene(withNodes, "scene.yaml");
  ASSERT_EQ(s.bodies[0].materialNodes.size(), 2u);
  EXPECT_EQ(s.bodies[0].materialNodes[0].node, 10);
  EXPECT_TRUE(s.bodies[0].materialNodes[0].hasAt);
  EXPECT_DOUBLE_EQ(s.bodies[0].materialNodes[0].at, 0.1);
  EXPECT_DOUBLE_EQ(s.bodies[0].materialNodes[0].motion.at(1.0).df, 3.0);
  EXPECT_EQ(s.bodies[0].materialNodes[1].node, -1);
  EXPECT_FALSE(s.bodies[0].materialNodes[1].hasMotion);
  EXPECT_TRUE(failsWith(edit(withNodes, "at: 0.1", "at: 2.5"), 9, "bodies[0].material_nodes[0].at", "0..2 m"));
  EXPECT_TRUE(failsWith(edit(withNodes, "{node: last}", "{node: 10}"), 9, "bodies[0].material_nodes[1].node",
                        "node 10 is listed twice"));
  EXPECT_TRUE(failsWith(edit(withNodes, "{node: last}", "{node: 15, at: 0.05}"), 9, "bodies[0].material_nodes",
                        "the nodes' arc lengths must rise with the node index"));
  EXPECT_TRUE(failsWith(edit(withNodes, "analysis: dynamic", "analysis: static"), 4, "bodies[0]",
                        "material_nodes with a motion move in time"));
  EXPECT_TRUE(failsWith(edit(withNodes, "    material_nodes:", "    material_motion: {function: linear, rate: 1}\n    material_nodes:"),
                        10, "bodies[0].material_nodes", "not both"));
}

// spin_torque (issue 35): only on kinds with a spin angle.
TEST(SceneReader, SpinTorqueNeedsASpinAngle) {
  EXPECT_TRUE(failsWith(edit(kBase3d, "force: [0, 0, -1]}", "force: [0, 0, -1], spin_torque: 5}"), 12,
                        "loads.nodal[0].spin_torque", "AncfCable3d has no spin angle (AleBeamShaft3d has)"));
  const std::string shaft =
      edit(edit(kBase3d, "element: AncfCable3d", "element: AleBeamShaft3d"),
           "section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}", "section: {E: 2.1e11, rho: 7850, radius: 0.005}");
  const model::SceneDescription s = parseScene(edit(shaft, "force: [0, 0, -1]}", "spin_torque: 5}"), "scene.yaml");
  EXPECT_DOUBLE_EQ(s.loads.nodal[0].spinTorque, 5.0);
}

// spin_torque_per_length (a distributed torque on the spin angle): likewise.
TEST(SceneReader, DistributedSpinTorqueNeedsASpinAngle) {
  EXPECT_TRUE(failsWith(kBase3d + "  distributed: [{body: cable, spin_torque_per_length: 2}]\n", 13,
                        "loads.distributed[0].spin_torque_per_length", "AncfCable3d has no spin angle (AleBeamShaft3d has)"));
  const std::string shaft =
      edit(edit(kBase3d, "element: AncfCable3d", "element: AleBeamShaft3d"),
           "section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}", "section: {E: 2.1e11, rho: 7850, radius: 0.005}");
  const model::SceneDescription s =
      parseScene(shaft + "  distributed: [{body: cable, spin_torque_per_length: 2}]\n", "scene.yaml");
  ASSERT_EQ(s.loads.distributed.size(), 1u);
  EXPECT_DOUBLE_EQ(s.loads.distributed[0].spinTorquePerLength, 2.0);
  EXPECT_EQ(s.loads.distributed[0].forcePerLength[2], 0.0);
}

// requirement (issue 36 item 5): probes name a point and a frame; a wrong one names file, line,
// key and reason.
TEST(SceneReader, ProbesAreReadAndCheckedWhereTheyAreWritten) {
  const std::string ok = kBase3d +
                         "probes:\n"                                                   // 13
                         "  - {name: tip, body: cable, node: last}\n"                  // 14
                         "  - {name: mid, body: cable, at: 0.5, frame: world}\n";      // 15
  const SceneDescription s = parseScene(ok, "scene.yaml");
  ASSERT_EQ(s.probes.size(), 2u);
  EXPECT_EQ(s.probes[0].node, -1);
  EXPECT_EQ(s.probes[1].kind, strand::model::ProbeDesc::Kind::Along);
  EXPECT_DOUBLE_EQ(s.probes[1].along, 0.5);
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: a/b, body: cable, node: 0}\n", 14, "probes[0].name",
                        "cannot name a probe's series"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: rope, node: 0}\n", 14, "probes[0].body",
                        "no body named 'rope'"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: cable, at: 1.5}\n", 14, "probes[0].at", "must be in [0, 1]"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: cable, node: 0, at: 0.2}\n", 14, "probes[0]",
                        "give either 'node' or 'at'"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: cable, node: 0, frame: hub2}\n", 14, "probes[0].frame",
                        "expected world, hub"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: cable, node: 0, force: true}\n", 14, "probes[0].force",
                        "support forces are written by dynamic runs"));
  EXPECT_TRUE(failsWith(kBase3d + "probes:\n  - {name: p, body: cable, node: 0}\n  - {name: p, body: cable, node: 1}\n", 15,
                        "probes[1].name", "a second probe named 'p'"));
}

// requirement (issue 34): pulleys, contact and wrap paths are read with their values; a wrong one
// names file, line, key and reason.
TEST(SceneReader, PulleysContactAndWrapPathsAreReadAndChecked) {
  const std::string head =
      "analysis: static\n"                                                                  // 1
      "dimension: 2\n"                                                                      // 2
      "pulleys:\n"                                                                          // 3
      "  - {name: drum, center: [0, 0], radius: 0.5, speed: -1}\n"                          // 4
      "bodies:\n"                                                                           // 5
      "  - name: rope\n"                                                                    // 6
      "    element: AncfCable2d\n"                                                          // 7
      "    elements: 20\n"                                                                  // 8
      "    section: {E: 1e9, A: 1e-4, I: 1e-12, rho: 1000}\n";                              // 9
  const std::string wrap = "    geometry: {kind: wrap, start: [-0.5, -2], end: [0.5, -2], around: [{pulley: drum, sense: cw}]}\n";  // 10
  const std::string contact =
      "contact:\n"                                                                          // 11
      "  - {body: rope, stiffness: 1e7, belt_height: 0.002, points: 3, friction: {law: coulomb, mu: 0.4}}\n";  // 12
  const SceneDescription s = parseScene(head + wrap + contact, "scene.yaml");
  ASSERT_EQ(s.pulleys.size(), 1u);
  EXPECT_DOUBLE_EQ(s.pulleys[0].speed.at(3.0).f, -1.0);
  ASSERT_EQ(s.contacts.size(), 1u);
  EXPECT_EQ(s.contacts[0].pulleys, std::vector<std::string>{"drum"});
  EXPECT_DOUBLE_EQ(s.contacts[0].law.offset, 0.001);
  EXPECT_EQ(s.contacts[0].points, 3);
  EXPECT_EQ(s.contacts[0].law.friction, strand::contact::FrictionLaw::RegularizedCoulomb);
  EXPECT_DOUBLE_EQ(s.contacts[0].law.mu, 0.4);
  EXPECT_DOUBLE_EQ(s.contacts[0].law.slipVelocity, 1e-3);
  ASSERT_EQ(s.bodies[0].geometry.wrap.size(), 1u);
  EXPECT_EQ(s.bodies[0].geometry.wrap[0].sense, -1);
  // a wrap path of two tangent lines and a half circle: 2 + pi/2 + 2
  strand::model::InitialGeometry g(s.bodies[0].geometry, 2, {});
  EXPECT_NEAR(g.length(), 4.0 + std::acos(-1.0) * 0.5, 1e-12);
  EXPECT_NEAR(g.at(2.0 + std::acos(-1.0) * 0.25).r[1], 0.5, 1e-12);  // the top of the drum
  EXPECT_NEAR(g.at(2.0 + std::acos(-1.0) * 0.25).t[0], 1.0, 1e-12);  // heading +x there (clockwise)

  EXPECT_TRUE(failsWith(head + edit(wrap, "pulley: drum", "pulley: wheel") + contact, 10, "bodies[0].geometry.around[0].pulley",
                        "no pulley named 'wheel'; pulleys: drum"));
  EXPECT_TRUE(failsWith(head + edit(wrap, "sense: cw", "sense: left") + contact, 10, "bodies[0].geometry.around[0].sense",
                        "expected cw or ccw"));
  EXPECT_TRUE(failsWith(head + edit(wrap, "start: [-0.5, -2]", "start: [0.1, 0]") + contact, 10, "bodies[0].geometry",
                        "no tangent line from start to around[0]"));
  EXPECT_TRUE(failsWith(head + wrap, 3, "pulleys", "pulleys act through contact"));
  EXPECT_TRUE(failsWith(head + wrap + edit(contact, "law: coulomb, mu: 0.4", "law: stribeck"), 12, "contact[0].friction.law",
                        "unknown friction law 'stribeck'; allowed: none, coulomb, creep_rate, bristle"));
  {
    const SceneDescription cr =
        parseScene(head + wrap + edit(contact, "law: coulomb, mu: 0.4", "law: creep_rate, mu: 0.4, slip_velocity: 0.02"),
                   "scene.yaml");
    EXPECT_EQ(cr.contacts[0].law.friction, strand::contact::FrictionLaw::CreepRate);
    EXPECT_DOUBLE_EQ(cr.contacts[0].law.slipVelocity, 0.02);
  }
  EXPECT_TRUE(failsWith(head + wrap + edit(contact, "law: coulomb, mu: 0.4", "law: bristle, mu: 0.4"), 12,
                        "contact[0].friction.law", "it needs a dynamic analysis"));
  EXPECT_TRUE(failsWith(head + wrap + edit(contact, "law: coulomb, mu: 0.4", "law: coulomb, mu: 0.4, stiffness: 1e6"), 12,
                        "contact[0].friction.stiffness", "not used by law: coulomb"));
  EXPECT_TRUE(failsWith(head + wrap + edit(contact, "stiffness: 1e7", "stiffness: 0"), 12, "contact[0].stiffness",
                        "must be positive"));
  EXPECT_TRUE(failsWith(head + wrap + edit(contact, "body: rope", "body: belt"), 12, "contact[0].body", "no body named 'belt'"));
  EXPECT_TRUE(failsWith(edit(head, "speed: -1}", "speed: -1}\n  - {name: drum, center: [1, 0], radius: 0.5}") + wrap + contact,
                        5, "pulleys[1].name", "a second pulley named 'drum'"));
  EXPECT_TRUE(failsWith(edit(head + wrap + contact, "dimension: 2", "dimension: 3"), 3, "pulleys",
                        "only when dimension is 2"));
  // a pulley free to turn: dynamics only; damping and torque only with inertia; its speed a number
  const std::string dyn = edit(head, "analysis: static", "analysis: dynamic");
  const std::string dynTail = wrap + contact + "dynamics: {dt: 1e-3, t_end: 0.1}\n";  // lines 10 .. 13
  {  // a free pulley with a first-order scheme
    const std::string freeDrum = edit(dyn, "speed: -1}", "inertia: 0.5}");
    const SceneDescription b =
        parseScene(freeDrum + wrap + contact + "dynamics: {dt: 1e-3, t_end: 0.1, integrator: bdf}\n", "scene.yaml");
    EXPECT_TRUE(b.pulleys[0].free());
  }
  {  // the bristle law: its stiffness defaults to the normal penalty's
    const std::string bristle = edit(contact, "law: coulomb, mu: 0.4", "law: bristle, mu: 0.4");
    const SceneDescription b = parseScene(dyn + wrap + bristle + "dynamics: {dt: 1e-3, t_end: 0.1}\n", "scene.yaml");
    EXPECT_EQ(b.contacts[0].law.friction, strand::contact::FrictionLaw::Bristle);
    EXPECT_DOUBLE_EQ(b.contacts[0].law.tangentialStiffness, 1e7);
    const SceneDescription k = parseScene(
        dyn + wrap + edit(bristle, "mu: 0.4", "mu: 0.4, stiffness: 2e6") + "dynamics: {dt: 1e-3, t_end: 0.1}\n", "scene.yaml");
    EXPECT_DOUBLE_EQ(k.contacts[0].law.tangentialStiffness, 2e6);
    EXPECT_TRUE(failsWith(dyn + wrap + edit(bristle, "mu: 0.4", "mu: 0.4, slip_velocity: 0.1") + "dynamics: {dt: 1e-3, t_end: 0.1}\n",
                          12, "contact[0].friction.slip_velocity", "not used by law: bristle"));
  }
  const SceneDescription f = parseScene(
      edit(dyn, "speed: -1}", "speed: 2, inertia: 0.3, damping: 0.1, torque: {function: ramp, end: 1, value: 5}}") + dynTail,
      "scene.yaml");
  EXPECT_TRUE(f.pulleys[0].free());
  EXPECT_DOUBLE_EQ(f.pulleys[0].inertia, 0.3);
  EXPECT_DOUBLE_EQ(f.pulleys[0].damping, 0.1);
  EXPECT_DOUBLE_EQ(f.pulleys[0].torque.at(0.5).f, 2.5);
  EXPECT_TRUE(failsWith(edit(head, "speed: -1}", "speed: -1, inertia: 0.3}") + wrap + contact, 4, "pulleys[0].inertia",
                        "only with analysis: dynamic"));
  EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "speed: -1, damping: 0.1}") + dynTail, 4, "pulleys[0].damping",
                        "only for a pulley free to turn"));
  EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "speed: {function: linear, rate: 1}, inertia: 0.3}") + dynTail, 4,
                        "pulleys[0].speed", "a free pulley's speed is its initial speed"));
  // a tensioner: a free pulley on a spring-damper slide
  {
    const SceneDescription t = parseScene(
        edit(dyn, "speed: -1}",
             "inertia: 0.3, slide: {direction: [0, 2], mass: 1.5, stiffness: 1e4, damping: 20, preload: 300}}") + dynTail,
        "scene.yaml");
    ASSERT_TRUE(t.pulleys[0].hasSlide);
    EXPECT_DOUBLE_EQ(t.pulleys[0].slide.direction[1], 1.0);  // made a unit vector
    EXPECT_DOUBLE_EQ(t.pulleys[0].slide.mass, 1.5);
    EXPECT_DOUBLE_EQ(t.pulleys[0].slide.stiffness, 1e4);
    EXPECT_DOUBLE_EQ(t.pulleys[0].slide.damping, 20.0);
    EXPECT_DOUBLE_EQ(t.pulleys[0].slide.preload.at(1.0).f, 300.0);
    EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "speed: -1, slide: {direction: [0, 1], mass: 1}}") + dynTail, 4,
                          "pulleys[0].slide", "a tensioner's pulley turns freely: give the pulley an 'inertia'"));
    EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "inertia: 0.3, slide: {direction: [0, 0], mass: 1}}") + dynTail, 4,
                          "pulleys[0].slide.direction", "must not be the zero vector"));
    EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "inertia: 0.3, slide: {direction: [0, 1]}}") + dynTail, 4,
                          "pulleys[0].slide.mass", ""));
    EXPECT_TRUE(failsWith(edit(dyn, "speed: -1}", "inertia: 0.3, slide: {direction: [0, 1], mass: 1, spring: 3}}") + dynTail,
                          4, "pulleys[0].slide.spring", ""));
  }
  // a closed belt around two pulleys, pretensioned
  const std::string two = edit(head, "speed: -1}", "speed: -1}\n  - {name: idler, center: [2, 0], radius: 0.25}");  // line 5
  const std::string loop =
      "    initial_stretch: 1.01\n"                                                                                   // 11
      "    geometry: {kind: wrap, closed: true, around: [{pulley: drum, sense: ccw}, {pulley: idler, sense: ccw}]}\n";  // 12
  const SceneDescription c = parseScene(two + loop + "contact:\n  - {body: rope, stiffness: 1e7}\n", "scene.yaml");
  EXPECT_TRUE(c.bodies[0].geometry.closed);
  EXPECT_DOUBLE_EQ(c.bodies[0].initialStretch, 1.01);
  // external tangents of circles 0.5 and 0.25 at distance 2: 2 sqrt(4 - 0.0625) + the two arcs
  const double e = 0.25, D = 2.0, beta = std::asin(e / D), pi = std::acos(-1.0);
  strand::model::InitialGeometry closedPath(c.bodies[0].geometry, 2, {});
  EXPECT_NEAR(closedPath.length(), 2.0 * std::sqrt(D * D - e * e) + 0.5 * (pi + 2.0 * beta) + 0.25 * (pi - 2.0 * beta), 1e-12);
  const auto first = closedPath.at(0.0), last = closedPath.at(closedPath.length());
  EXPECT_NEAR(first.r[0], last.r[0], 1e-12);
  EXPECT_NEAR(first.r[1], last.r[1], 1e-12);
  EXPECT_NEAR(first.t[0], last.t[0], 1e-12);
  EXPECT_TRUE(failsWith(two + edit(loop, "closed: true,", "closed: true, start: [0, 0],") + "contact:\n  - {body: rope, stiffness: 1e7}\n",
                        12, "bodies[0].geometry.start", "a closed path has no ends"));
  EXPECT_TRUE(failsWith(two + edit(loop, ", {pulley: idler, sense: ccw}", "") + "contact:\n  - {body: rope, stiffness: 1e7}\n",
                        12, "bodies[0].geometry.around", "at least two pulleys"));
  EXPECT_TRUE(failsWith(edit(edit(two, "element: AncfCable2d", "element: AncfBeam2dShear"), "{E: 1e9, A: 1e-4, I: 1e-12, rho: 1000}",
                                 "{E: 1e9, rho: 1000, width: 0.01, height: 0.01}") +
                            loop + "contact:\n  - {body: rope, stiffness: 1e7}\n",
                        11, "bodies[0].initial_stretch", "not built yet"));
}
