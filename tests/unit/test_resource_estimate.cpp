// requirement (issue 32 item 9): the memory a scene needs is estimated from the SceneDescription
// before anything is allocated, conservatively (12 coordinates per node, the measured cost per
// element doubled, io/ResourceEstimate.hpp), and a scene that cannot be represented or does not fit
// is refused with an InputError naming the body, the estimate and the limit, on every rank alike.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <string>

#include "strand/core/Error.hpp"
#include "strand/elements/ElementRegistry.hpp"
#include "strand/io/ResourceEstimate.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::io;

namespace {

std::string refusal(const model::SceneDescription& sc, bool modal, double limit) {
  try {
    checkResources(PETSC_COMM_WORLD, sc, modal, limit);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

model::SceneDescription cable(int elements) {
  auto sc = strand::testing::cantilever(3, elements);
  sc.file = "scene.yaml";
  sc.bodies[0].mark = {"scene.yaml", 4, "bodies[0]"};
  return sc;
}

}  // namespace

TEST(ResourceEstimate, GrowsWithTheModelAndCoversTheMeasuredRuns) {
  const auto small = estimateResources(cable(10), false, 1, 1), big = estimateResources(cable(100000), false, 1, 1);
  EXPECT_EQ(small.coordinates, 11 * 6.0);  // two blocks of 3 per node
  // a kind with more blocks per node: AleBeamShaft3d has r, r' and (p, theta) per node
  auto shaft = cable(10);
  shaft.bodies[0].kind = elements::findKind("AleBeamShaft3d");
  const auto s = estimateResources(shaft, false, 1, 1);
  EXPECT_EQ(s.coordinates, 11 * 9.0);
  EXPECT_GT(s.bytes - 1e8, 2.0 * (small.bytes - 1e8));  // (18 / 12)^2 = 2.25 times the per-element bytes
  EXPECT_LT(small.bytes, 2e8);
  // measured: 489 MB (generalized-alpha) and 753 MB (BDF) peak at 1e5 elements of a 3D cable
  EXPECT_GT(big.bytes, 2 * 753e6);
  EXPECT_LT(big.bytes, 4e9);
  EXPECT_GT(estimateResources(cable(100000), true, 1, 1).bytes, big.bytes);
  EXPECT_EQ(big.largest.where(), "scene.yaml:4: bodies[0].elements");
  // two ranks on one host hold the replicated part twice but share the rest
  const double two = estimateResources(cable(100000), false, 2, 2).bytes;
  EXPECT_GT(two, big.bytes);
  EXPECT_LT(two, 2 * big.bytes);
}

TEST(ResourceEstimate, RefusesWhatCannotBeRepresentedOrDoesNotFit) {
  EXPECT_EQ(refusal(cable(1000), false, 1e12), "");
  std::string why = refusal(cable(2147483647), false, 1e30);
  EXPECT_EQ(why.rfind("scene.yaml:4: bodies[0].elements: the scene has up to 12884901888 coordinates", 0), 0u) << why;
  why = refusal(cable(1000000), false, 1e9);
  EXPECT_EQ(why.rfind("scene.yaml:4: bodies[0].elements: this run needs about ", 0), 0u) << why;
  EXPECT_NE(why.find("more than the 1 GB of -max_memory"), std::string::npos) << why;
  auto samples = cable(32);
  samples.output.samplesPerElement = 100000000;
  why = refusal(samples, false, 1e30);
  EXPECT_NE(why.find("32 elements x output.samples_per_element 100000000 is more output points"), std::string::npos)
      << why;
  model::SceneDescription hub;
  hub.file = "hub.yaml";
  hub.hubBeam.present = true;
  hub.hubBeam.mark = {"hub.yaml", 2, "hub_beam"};
  hub.hubBeam.elements = 20000000;
  why = refusal(hub, false, 0.0);  // the machine's memory
  EXPECT_EQ(why.rfind("hub.yaml:2: hub_beam.discretization: this run needs about", 0), 0u) << why;
}

TEST(ResourceEstimate, ParsesSizes) {
  EXPECT_EQ(parseBytes("64G"), 64.0 * 1024 * 1024 * 1024);
  EXPECT_EQ(parseBytes("512m"), 512.0 * 1024 * 1024);
  EXPECT_EQ(parseBytes("2e9"), 2e9);
  EXPECT_EQ(parseBytes("1TB"), 1024.0 * 1024 * 1024 * 1024);
  for (const char* bad : {"", "G", "-1G", "12X", "nan", "1GiB"}) EXPECT_LT(parseBytes(bad), 0.0) << bad;
  EXPECT_GT(availableMemory(), 0.0);
}
