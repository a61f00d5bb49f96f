// The element kinds at run time, by index and by name: what the scene reader, the model and the
// output need to know of a kind without its kernel (the kernels are in ElementKinds.hpp).
#pragma once
#include <string>
#include <vector>

#include "strand/elements/ElementKind.hpp"

namespace strand::elements {

struct KindInfo {
  const char* name = nullptr;
  int dim = 0;
  int blocksPerNode = 0;
  const BlockRole* layout = nullptr;  // blocksPerNode roles; block 0 is the position
  int orientationBlock = 0;           // the node block a clamp holds (with the position) and a moment turns
  bool stressFreeInitial = false;     // accepts stress_free: initial
  bool initialStretch = false;        // accepts initial_stretch (a pretensioned initial state)
  bool constantMass = true;           // M does not depend on the coordinates (every integrator assumes it today)
  const SectionKey* sectionKeys = nullptr;
  int sectionKeyCount = 0;
  const OptionKey* options = nullptr;
  int optionCount = 0;
  BeamProperties (*properties)(const SectionValues&) = nullptr;
  // whether the internal force depends on velocities (damping): the integrators' D matrix
  bool (*velocityDependent)(const SectionValues&, const BodyDiscretization&) = nullptr;
  // centerline position weights w (2 blocksPerNode) at eta in [0, 1]: r(eta) = sum_a w_a q_a
  void (*interpolation)(const BodyDiscretization&, double eta, double* w) = nullptr;
  // the same at the element's current coordinates qElement (2 blocksPerNode x dim): an ALE
  // element's slopes weigh with its current material length
  void (*interpolationAt)(const BodyDiscretization&, const double* qElement, double eta, double* w) = nullptr;
  // stress_free: initial: kind-defined reference values of `elements` elements from their initial
  // coordinates q0 (elements x (2 blocksPerNode dim) values, element-major)
  std::vector<double> (*referenceValues)(const SectionValues&, const BodyDiscretization&, const double* q0,
                                         int elements) = nullptr;
  // the axial (tension) force at eta of an element at coordinates qElement, elastic part (null: the
  // kind does not provide it; the output then has no axial_force field)
  double (*axialForce)(const SectionValues&, const BodyDiscretization&, const double* qElement, double eta) = nullptr;
  int blocksPerElement() const { return 2 * blocksPerNode; }
  // The node block with this role (-1: none); the block holding a material coordinate (ALE kinds).
  int blockWith(BlockRole role) const {
    for (int k = 0; k < blocksPerNode; ++k)
      if (layout[k] == role) return k;
    return -1;
  }
  int materialBlock() const {
    for (int k = 0; k < blocksPerNode; ++k)
      if (isMaterialBlock(layout[k])) return k;
    return -1;
  }
};

int kindCount();
const KindInfo& kindInfo(int kind);
int findKind(const std::string& name);  // -1 when there is no such kind
std::vector<std::string> kindNames();

}  // namespace strand::elements
