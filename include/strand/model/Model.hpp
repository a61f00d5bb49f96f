// The discrete model built from a scene: bodies, DOF blocks, supports and loads. No PETSc here.
//
// Every unknown belongs to a block of `dim` coordinates: a cable node owns a position block and a
// slope block; a junction makes several bodies' nodes share one position block. Blocks are numbered
// here in scene order ("model numbering"); DofMap renumbers them for the parallel layout.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "strand/elements/CableSection.hpp"
#include "strand/model/HubMotion.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::model {

struct PointMass {
  int element;  // element index within the body
  double eta;   // local coordinate in [0, 1]
  double mass;  // [kg]
};

struct Body {
  std::string name;
  int elements = 0;
  double length = 0.0, elementLength = 0.0;
  elements::CableSection section;
  std::vector<int> posBlock, slopeBlock;  // per node, model numbering
  std::vector<double> slopeScale;         // per node: slope coordinates are sigma * dr/dx
  std::vector<double> kappa0;             // 2D reference curvature per element x Gauss point (empty: straight)
  std::vector<PointMass> pointMasses;
  Vec3 loadPerLength{};                   // gravity rho A g plus distributed loads [N/m]
};

// One element of the global element list: its body and its four blocks [r1, r1', r2, r2'].
struct ElementRef {
  int body;
  int index;
  std::array<int, 4> blocks;
};

// Scales of the first body for dimensionless input and output (seed 003): length L, rho A, E I,
// E A; T* = sqrt(rho A L^4 / (E I)) turns omega into gamma = omega T* and omega_bar = omega T*.
struct ReferenceScales {
  double length = 1.0, rhoA = 1.0, EI = 1.0, EA = 1.0;
  double time() const;
  double slenderness() const;  // mu = sqrt(A L^2 / I) = sqrt(EA L^2 / EI)
};

struct NodalMomentLoad {
  int slopeBlock;
  Vec3 moment;
};

class Model {
public:
  explicit Model(const SceneDescription& scene);

  int dim() const { return _dim; }
  int numBlocks() const { return _numBlocks; }
  int numDofs() const { return _numBlocks * _dim; }
  int gaussPoints() const { return _gaussPoints; }
  const std::vector<Body>& bodies() const { return _bodies; }
  const std::vector<ElementRef>& elements() const { return _elements; }
  // Reference coordinates q0 (model numbering): the initial shape, axially unstretched; the
  // unknowns are displacements u = q - q0.
  const std::vector<double>& initialCoordinates() const { return _q0; }
  const std::vector<char>& fixedDofs() const { return _fixed; }          // 1 where a support holds the DOF
  // Supports on turning hubs (their DOFs are among fixedDofs; the others stay at zero displacement).
  const std::vector<HubMotion>& hubMotions() const { return _hubs; }
  const std::vector<double>& nodalForces() const { return _nodalForce; } // constant nodal forces per DOF
  const std::vector<NodalMomentLoad>& nodalMoments() const { return _moments; }
  const Vec3& gravity() const { return _gravity; }  // also acts on point masses
  // Rotating frame (absent: omega 0). The angular speed may be changed between solves (sweeps).
  const RotationDesc& rotation() const { return _rotation; }
  void setAngularSpeed(double omega) { _rotation.omega = omega; }
  const ReferenceScales& scales() const { return _scales; }

private:
  int _dim = 3, _numBlocks = 0, _gaussPoints = 5;
  std::vector<Body> _bodies;
  std::vector<ElementRef> _elements;
  std::vector<double> _q0, _nodalForce;
  std::vector<char> _fixed;
  std::vector<NodalMomentLoad> _moments;
  std::vector<HubMotion> _hubs;
  Vec3 _gravity{};
  RotationDesc _rotation;
  ReferenceScales _scales;
};

}  // namespace strand::model
