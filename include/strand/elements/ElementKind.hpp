// What every element kind declares about itself, and the types its kernel uses to talk to the rest
// of the program (docs/architecture.md, "Element kinds"; the checklist there says how to add one).
//
// A kind is a kernel class (include/strand/elements/<Kind>.hpp): pure functions of one element's
// data, no PETSc. Its static members (name, dimension, node layout, section keys, options) are
// read into a KindInfo by the registry (ElementKinds.hpp); its typed functions (force, tangent,
// slot mass, interpolation) are called by the assembler's loop for that kind (KernelFamily<K>).
#pragma once
#include <limits>
#include <map>
#include <string>

namespace strand::elements {

// The most blocks an element of any kind has (2 nodes x 4 blocks: the 3D beam r, r_x, r_y, r_z).
inline constexpr int kMaxBlocksPerElement = 8;

// What a block of a node holds. Every block has `dim` coordinates (the BAIJ block size).
enum class BlockRole {
  Position,            // r: the node's position (junctions share it, pins hold it, forces act on it)
  AxialGradient,       // r_x = dr/dx along the reference arc length (the cable's slope)
  TransverseGradient,  // r_y = dr/dy across the section (a shear-deformable beam's cross-section vector)
  MaterialCoordinate,  // p: the material (unstretched arc-length) coordinate of an ALE node, in component 0;
                       // the other components are padding, held at zero
  MaterialSpin,        // p in component 0 and the spin angle theta of the section about the centerline
                       // in component 1 (a beam-shaft); the other components are padding
};

// A block that carries the node's material coordinate p (component 0): an ALE kind's node.
inline constexpr bool isMaterialBlock(BlockRole r) {
  return r == BlockRole::MaterialCoordinate || r == BlockRole::MaterialSpin;
}
// How many leading components of a block of role r are coordinates (the rest is padding, held).
inline constexpr int usedComponents(BlockRole r, int dim) {
  return r == BlockRole::MaterialCoordinate ? 1 : r == BlockRole::MaterialSpin ? 2 : dim;
}

inline constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// A numeric section key: name, whether the scene must give it, its value when not given, and its
// admissible range (lower < value, or <= when lowerClosed; value < upper).
struct SectionKey {
  const char* name;
  const char* meaning;   // for docs and messages, with the unit
  bool required;
  double fallback;       // used when not required and not given
  double lower;          // admissible range
  bool lowerClosed;
  double upper;          // +inf: none
};

// An option of a kind's formulation: the values it may take, the first being the default.
struct OptionKey {
  static constexpr int kMaxValues = 4;
  const char* name;
  const char* meaning;
  const char* values[kMaxValues];  // null-terminated when fewer
};

// The section and formulation of one body as the scene gives them (SI), keys as the kind declares.
struct SectionValues {
  std::map<std::string, double> numbers;       // the `section` map
  std::map<std::string, std::string> options;  // the `formulation` map (defaults filled in by the reader)

  double number(const std::string& key, double fallback = 0.0) const {
    const auto it = numbers.find(key);
    return it == numbers.end() ? fallback : it->second;
  }
  std::string option(const std::string& key, const std::string& fallback = "") const {
    const auto it = options.find(key);
    return it == options.end() ? fallback : it->second;
  }
  void set(const std::string& key, double value) { numbers[key] = value; }
};

// Section resultants every kind derives from its section: reference scales (seed 003's
// dimensionless speed and mass ratio), gravity per length, and the energy monitor's floor.
struct BeamProperties {
  double EA = 0.0;    // axial stiffness [N]
  double EI = 0.0;    // bending stiffness [N m^2]
  double rhoA = 0.0;  // mass per unit length [kg/m]
};

// The discretization of one body that a kernel needs beyond its section: uniform elements.
struct BodyDiscretization {
  double elementLength = 0.0;  // reference length of each element [m]
  double gradientScale = 1.0;  // AxialGradient coordinates are gradientScale * dr/dx (the cable's slope scaling)
  int gaussPoints = 5;         // discretization.gauss_points (the cable's elastic rule)
  double initialStretch = 1.0; // kinds without material coordinates: the initial shape is the material
                               // stretched by this (their strain starts at (lambda0^2 - 1) / 2)
};

}  // namespace strand::elements
