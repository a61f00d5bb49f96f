#include "strand/model/Model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "strand/core/Error.hpp"
#include "strand/model/InitialGeometry.hpp"

namespace strand::model {
namespace {

// The anchors of an ALE body's material_nodes, in node order: node, arc length, motion (or none);
// node 0 and the last node at the body's ends unless listed.
struct MaterialAnchor {
  int node;
  double arc;
  const MaterialNodeDesc* desc;  // null: held
};
std::vector<MaterialAnchor> materialAnchors(const BodyDesc& bd, int elements, double length) {
  std::vector<MaterialAnchor> a;
  for (const MaterialNodeDesc& m : bd.materialNodes) {
    const int n = m.node < 0 ? elements : static_cast<int>(m.node);
    a.push_back({n, m.hasAt ? m.at : length * n / elements, &m});
  }
  std::sort(a.begin(), a.end(), [](const MaterialAnchor& x, const MaterialAnchor& y) { return x.node < y.node; });
  if (a.empty() || a.front().node != 0) a.insert(a.begin(), {0, 0.0, nullptr});
  if (a.back().node != elements) a.push_back({elements, length, nullptr});
  return a;
}

std::vector<double> materialNodeArcs(const BodyDesc& bd, int elements, double length) {
  std::vector<double> arc(elements + 1);
  const std::vector<MaterialAnchor> a = materialAnchors(bd, elements, length);
  for (size_t k = 0; k + 1 < a.size(); ++k)
    for (int n = a[k].node; n <= a[k + 1].node; ++n) {
      const double w = static_cast<double>(n - a[k].node) / (a[k + 1].node - a[k].node);
      arc[n] = (1.0 - w) * a[k].arc + w * a[k + 1].arc;
    }
  return arc;
}

// Per node, the motions that move its material coordinate and their weights (material_nodes;
// empty without them).
using MaterialWeights = std::vector<std::vector<std::pair<TimeFunction, double>>>;
MaterialWeights materialNodeWeights(const BodyDesc& bd, int elements) {
  MaterialWeights out(elements + 1);
  if (bd.materialNodes.empty()) return out;
  const std::vector<MaterialAnchor> a = materialAnchors(bd, elements, 0.0);
  for (size_t k = 0; k + 1 < a.size(); ++k)
    for (int n = a[k].node; n <= a[k + 1].node; ++n) {
      if (n == a[k + 1].node && k + 2 < a.size()) break;  // the next interval's first node
      const double w = static_cast<double>(n - a[k].node) / (a[k + 1].node - a[k].node);
      if (a[k].desc && a[k].desc->hasMotion && w < 1.0) out[n].push_back({a[k].desc->motion, 1.0 - w});
      if (a[k + 1].desc && a[k + 1].desc->hasMotion && w > 0.0) out[n].push_back({a[k + 1].desc->motion, w});
    }
  return out;
}

int nodeIndex(const NodeRef& ref, const Body& b) {
  const long n = ref.node < 0 ? b.elements : ref.node;
  if (n > b.elements) throw InputError(ref.mark.where() + ": node " + std::to_string(n) + " out of range 0.." + std::to_string(b.elements));
  return static_cast<int>(n);
}

// Values of the constraint equations `eqs` over `blocks` at the coordinates q (model numbering).
std::vector<double> constraintValues(const std::vector<elements::ConstraintEq>& eqs, const std::vector<int>& blocks,
                                     const std::vector<double>& q, int dim) {
  const int n = static_cast<int>(blocks.size()) * dim;
  std::vector<double> qe(n), g, G(3 * n);
  for (size_t b = 0; b < blocks.size(); ++b)
    for (int i = 0; i < dim; ++i) qe[b * dim + i] = q[blocks[b] * dim + i];
  for (const elements::ConstraintEq& e : eqs) {
    double ge[3];
    const int m = dim == 2 ? elements::Constraint<2>::equations(e) : elements::Constraint<3>::equations(e);
    if (dim == 2) elements::Constraint<2>::evaluate(e, qe.data(), n, ge, G.data());
    else elements::Constraint<3>::evaluate(e, qe.data(), n, ge, G.data());
    g.insert(g.end(), ge, ge + m);
  }
  return g;
}

// Rodrigues: the rotation by `angle` about `axis` (normalized here), row-major.
std::array<double, 9> rotationMatrix(const Vec3& axis, double angle) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double e[3] = {axis[0] / len, axis[1] / len, axis[2] / len}, c = std::cos(angle), s = std::sin(angle);
  std::array<double, 9> R{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i * 3 + j] = (i == j ? c : 0.0) + (1.0 - c) * e[i] * e[j];
  R[0 * 3 + 1] -= s * e[2];
  R[0 * 3 + 2] += s * e[1];
  R[1 * 3 + 0] += s * e[2];
  R[1 * 3 + 2] -= s * e[0];
  R[2 * 3 + 0] -= s * e[1];
  R[2 * 3 + 1] += s * e[0];
  return R;
}

}  // namespace

// The scene and the name tables while the model is built.
struct Model::Build {
  const SceneDescription& scene;
  std::map<std::string, int> bodyIndex, rigidIndex;
  std::vector<InitialGeometry> curves;

  Body& body(std::vector<Body>& bodies, const std::string& name, const SourceMark& mark) const {
    auto it = bodyIndex.find(name);
    if (it == bodyIndex.end()) throw InputError(mark.where() + ": no body named '" + name + "'");
    return bodies[it->second];
  }
};

Model::Model(const SceneDescription& scene) : _dim(scene.dimension), _gravity(scene.loads.gravity), _rotation(scene.rotation) {
  Build b{scene, {}, {}, {}};
  addBodies(b);                     // 1. bodies and their node blocks
  mergeJunctions(b);                // 2. junction nodes share one position block
  addRigidBodiesAndMultipliers(b);  //    rigid bodies' blocks, joints' multiplier blocks
  addPulleyBlocks(b);               //    free pulleys' blocks
  placeInitialState(b);             // 3. q0, reference values, element groups
  addSupports(b);                   // 4. supports, multipliers, prescribed motion
  addLoads(b);                      // 5. loads
  addInitialVelocities(b);
  addJointEquations(b);             // 6. joint equations, checked at the initial state
  addCouplings();                   // 7. couplings: rigid bodies and joints
  addContacts(scene);               // 8. belt-pulley contact and the free pulleys' state
  addReelDrives();                  // 9. reels: driven angle or applied torque
}

// A reel's block (phi, padding): phi prescribed for a driven reel (speed control), free with its
// torque as a timed load otherwise (torque control); it starts at rest. The payout joint and
// the block are made with the material joints (addMaterialJoints).
void Model::addReelDrives() {
  for (size_t r = 0; r < _reels.size(); ++r) {
    const int dof = _reelBlock[r] * _dim;
    for (int i = 1; i < _dim; ++i) _fixed[dof + i] = 1;
    const ReelDesc& d = _reels[r];
    if (d.driven) {
      _fixed[dof] = 1;
      _prescribed.push_back({dof, d.rotation, 1.0});
      continue;
    }
    if (!(d.torque.kind == TimeFunction::Kind::Constant && d.torque.value == 0.0)) _timed.push_back({d.torque, {dof}, {1.0}});
  }
}

void Model::addPulleyBlocks(Build& build) {
  _reels = build.scene.reels;  // their blocks: with the material joints (addMaterialJoints)
  _reelBlock.assign(_reels.size(), -1);
  for (const ReelDesc& r : _reels) _reelBodyIndex.push_back(build.bodyIndex.at(r.body));
  _pulleys = build.scene.pulleys;
  for (const PulleyDesc& p : _pulleys) _pulleyBlock.push_back(p.free() ? _numBlocks++ : -1);
}

void Model::addContacts(const SceneDescription& scene) {
  // a free pulley's block (phi, x): phi starts at 0 with its initial speed; x, a tensioner's slide
  // displacement, at 0 at rest (held at zero without a slide); the torque and the slide's preload
  // are timed loads on phi and x
  auto isZero = [](const TimeFunction& f) { return f.kind == TimeFunction::Kind::Constant && f.value == 0.0; };
  for (size_t p = 0; p < _pulleys.size(); ++p) {
    const int blk = _pulleyBlock[p];
    if (blk < 0) continue;
    const PulleyDesc& d = _pulleys[p];
    if (!d.hasSlide) _fixed[blk * _dim + 1] = 1;
    _v0[blk * _dim] = d.speed.at(0.0).f;
    if (!isZero(d.torque)) _timed.push_back({d.torque, {blk * _dim}, {1.0}});
    if (d.hasSlide && !isZero(d.slide.preload)) _timed.push_back({d.slide.preload, {blk * _dim + 1}, {1.0}});
  }
  for (const ContactDesc& c : scene.contacts) {
    PulleyContactSet set;
    for (size_t b = 0; b < _bodies.size(); ++b)
      if (_bodies[b].name == c.body) set.body = static_cast<int>(b);
    for (const std::string& name : c.pulleys)
      for (size_t p = 0; p < _pulleys.size(); ++p)
        if (_pulleys[p].name == name) set.pulleys.push_back(static_cast<int>(p));
    set.law = c.law;
    set.points = c.points;
    // each element of the body couples to each free pulley it may touch (exact preallocation: the
    // pattern is reserved once, whatever the contact does)
    for (int p : set.pulleys) {
      if (_pulleyBlock[p] < 0) continue;
      for (const ElementGroup& g : _groups)
        for (int e = 0; e < g.size(); ++e) {
          if (g.body[e] != set.body) continue;
          Coupling cpl;
          cpl.pulley = p;
          cpl.blocks.assign(g.blocksOf(e), g.blocksOf(e) + g.blocksPerElement);
          cpl.blocks.push_back(_pulleyBlock[p]);
          _couplings.push_back(std::move(cpl));
        }
    }
    _contacts.push_back(std::move(set));
  }
}

int Model::numElements() const {
  int n = 0;
  for (const ElementGroup& g : _groups) n += g.size();
  return n;
}

bool Model::constantMass() const {
  for (const Body& b : _bodies)
    if (!b.info().constantMass) return false;
  return true;
}

bool Model::velocityDependent() const {
  for (const Body& b : _bodies)
    if (b.velocityDependent) return true;
  for (const ReelDesc& r : _reels)
    if (r.damping > 0.0) return true;
  for (const PulleyContactSet& c : _contacts)  // contact damping and friction depend on the belt's velocity
    if (c.law.damping > 0.0 || c.law.friction != contact::FrictionLaw::None) return true;
  for (const PulleyDesc& p : _pulleys)
    if (p.free() && (p.damping > 0.0 || (p.hasSlide && p.slide.damping > 0.0))) return true;
  return false;
}

void Model::addBodies(Build& build) {
  const SceneDescription& scene = build.scene;
  for (const BodyDesc& bd : scene.bodies) {
    Body b;
    b.name = bd.name;
    b.kind = bd.kind;
    const elements::KindInfo& info = b.info();
    b.elements = bd.elements;
    build.curves.emplace_back(bd.geometry, _dim, scene.loads.gravity);
    b.length = build.curves.back().length();
    const bool ale = info.materialBlock() >= 0;  // material coordinates: slopes are dr/dp = lambda0 dr/ds (never scaled by l)
    // a pretension: the material of the initial curve stretched by lambda0 (ALE kinds: through p)
    b.elementLength = b.length / b.elements / (ale ? 1.0 : bd.initialStretch);
    b.closed = bd.geometry.closed;
    b.section = bd.section;
    b.properties = info.properties(bd.section);
    b.discretization = {b.elementLength,
                        ale ? bd.initialStretch : scene.discretization.slopeScaling ? b.elementLength : 1.0,
                        scene.discretization.gaussPoints, ale ? 1.0 : bd.initialStretch};
    b.velocityDependent = info.velocityDependent(bd.section, b.discretization);
    b.nodeArc = materialNodeArcs(bd, b.elements, b.length);
    b.blocksPerNode = info.blocksPerNode;
    for (int n = 0; n <= b.elements; ++n)
      for (int k = 0; k < b.blocksPerNode; ++k) {
        if (k == 0) b.posBlock.push_back(_numBlocks);
        b.nodeBlocks.push_back(_numBlocks++);
      }
    for (int k = 0; k < 3; ++k) b.loadPerLength[k] = b.properties.rhoA * scene.loads.gravity[k];
    for (const PointMassDesc& pm : bd.pointMasses) {
      const double x = std::min(std::max(pm.at, 0.0), b.length);
      const double u = x / b.length * b.elements;  // in elements
      const int e = std::min(static_cast<int>(u), b.elements - 1);
      b.pointMasses.push_back({e, u - e, pm.mass});
    }
    if (_bodies.empty()) _scales = {b.length, b.properties.rhoA, b.properties.EI, b.properties.EA};
    build.bodyIndex[b.name] = static_cast<int>(_bodies.size());
    _bodies.push_back(std::move(b));
  }
}

void Model::mergeJunctions(Build& build) {
  // the listed nodes share one position block (union-find over blocks)
  std::vector<int> parent(_numBlocks);
  for (int k = 0; k < _numBlocks; ++k) parent[k] = k;
  auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const Body& b : _bodies)  // a loop's last node is its first: every block
    if (b.closed)
      for (int k = 0; k < b.blocksPerNode; ++k) {
        const int first = root(b.block(0, k)), last = root(b.block(b.elements, k));
        parent[std::max(first, last)] = std::min(first, last);
      }
  for (const JunctionDesc& j : build.scene.junctions) {
    if (j.nodes.size() < 2) throw InputError(j.mark.where() + ": a junction needs at least two nodes");
    const Body& b0 = build.body(_bodies, j.nodes[0].body, j.nodes[0].mark);
    const int first = root(b0.posBlock[nodeIndex(j.nodes[0], b0)]);
    for (size_t k = 1; k < j.nodes.size(); ++k) {
      const Body& bk = build.body(_bodies, j.nodes[k].body, j.nodes[k].mark);
      const int other = root(bk.posBlock[nodeIndex(j.nodes[k], bk)]);
      const int r0 = root(first);
      parent[std::max(r0, other)] = std::min(r0, other);
    }
  }
  // compact numbering of the surviving blocks
  std::vector<int> compact(_numBlocks, -1);
  int next = 0;
  for (int k = 0; k < _numBlocks; ++k)
    if (root(k) == k) compact[k] = next++;
  for (Body& b : _bodies) {
    for (int& blk : b.posBlock) blk = compact[root(blk)];
    for (int& blk : b.nodeBlocks) blk = compact[root(blk)];
  }
  _numBlocks = next;
}

void Model::addRigidBodiesAndMultipliers(Build& build) {
  // rigid bodies: 2D position block, rotation block (phi, unused); 3D centre of mass and three
  // frame blocks. Joints: their multiplier blocks (the scene's, then the 3D bodies' frames)
  const SceneDescription& scene = build.scene;
  for (const RigidBodyDesc& rd : scene.rigidBodies) {
    if (build.bodyIndex.count(rd.name) || build.rigidIndex.count(rd.name))
      throw InputError(rd.mark.where() + ": the name '" + rd.name + "' is already used by another body");
    build.rigidIndex[rd.name] = static_cast<int>(_rigid.size());
    RigidBody rb;
    rb.name = rd.name;
    rb.mass = rd.mass;
    rb.inertia = rd.inertia;
    rb.posBlock = _numBlocks;
    rb.rotBlock = _numBlocks + 1;
    if (_dim == 3) {  // Jbar = 1/2 tr(I) 1 - I for principal body axes
      const Vec3& I = rd.principalInertia;
      for (int k = 0; k < 3; ++k) rb.frameInertia[4 * k] = 0.5 * (I[0] + I[1] + I[2]) - I[k];
      rb.torque = rd.torque;
    }
    _numBlocks += rb.blocks(_dim);
    _rigid.push_back(rb);
  }
  for (const JointDesc& jd : scene.joints) {
    const int count = jd.type == JointType::Pin ? _dim : jd.type == JointType::Distance ? 1 : 2 * _dim - 1;
    Joint j;
    j.label = jd.mark.where();
    j.count = count;
    for (int k = 0; k < (count + _dim - 1) / _dim; ++k) j.lambdaBlocks.push_back(_numBlocks++);
    _joints.push_back(std::move(j));
  }
  for (size_t r = 0; r < _rigid.size() && _dim == 3; ++r) {
    // a driven frame is prescribed (a turning hub of its three axes, in addSupports): no equations
    if (scene.rigidBodies[r].driven) continue;
    // a_k . a_k = 1 as |a_k| - 1 = 0 (Distance to the origin), a_k . a_l = 0 (Orthogonal)
    Joint j;
    j.label = scene.rigidBodies[r].mark.where() + " (orthonormal body frame)";
    j.count = 6;
    const int a = _rigid[r].rotBlock;
    j.blocks = {a, a + 1, a + 2};
    for (int k = 0; k < 3; ++k) {
      elements::ConstraintEq unit;
      unit.form = elements::ConstraintForm::Distance;
      unit.a.kind = elements::JointField::Kind::Block;
      unit.a.block = k;
      unit.length = 1.0;
      j.equations.push_back(unit);
    }
    for (int k = 0; k < 3; ++k) {
      elements::ConstraintEq normal;
      normal.form = elements::ConstraintForm::Orthogonal;
      normal.a.kind = normal.b.kind = elements::JointField::Kind::Block;
      normal.a.block = k;
      normal.b.block = (k + 1) % 3;
      j.equations.push_back(normal);
    }
    j.lambdaBlocks = {_numBlocks, _numBlocks + 1};
    _numBlocks += 2;
    _rigid[r].frameJoint = static_cast<int>(_joints.size());
    _joints.push_back(std::move(j));
  }
}

void Model::placeInitialState(Build& build) {
  // each node's blocks from its point on the initial curve, by role: the position, the slope
  // gradientScale t, the cross-section vector n (t turned by +90 degrees, 2D); junction nodes
  // must coincide
  const SceneDescription& scene = build.scene;
  _q0.assign(numDofs(), 0.0);
  std::vector<char> placed(_numBlocks, 0);
  for (size_t bi = 0; bi < _bodies.size(); ++bi) {
    Body& b = _bodies[bi];
    const elements::KindInfo& info = b.info();
    for (int n = 0; n <= b.elements; ++n) {
      const CurvePoint p = build.curves[bi].at(b.nodeArc[n]);
      const int pb = b.posBlock[n];
      for (int i = 0; i < _dim; ++i) {
        if (placed[pb] && std::fabs(_q0[pb * _dim + i] - p.r[i]) > 1e-9 * std::max(1.0, b.length))
          throw InputError(scene.bodies[bi].mark.where() + ": node " + std::to_string(n) +
                           " of a junction does not coincide with the other nodes of the junction");
        _q0[pb * _dim + i] = p.r[i];
      }
      placed[pb] = 1;
      for (int k = 1; k < b.blocksPerNode; ++k) {
        const int blk = b.block(n, k);
        double* q = &_q0[blk * _dim];
        switch (info.layout[k]) {
          case elements::BlockRole::AxialGradient: {  // dr/dx = lambda0 t (ALE kinds: in their gradientScale)
            const double stretch = info.materialBlock() >= 0 ? 1.0 : scene.bodies[bi].initialStretch;
            for (int i = 0; i < _dim; ++i) q[i] = b.blockScale(k) * stretch * p.t[i];
            break;
          }
          case elements::BlockRole::TransverseGradient:
            if (_dim != 2) throw std::logic_error("Model: a transverse gradient block needs a 3D section frame");
            q[0] = -p.t[1];
            q[1] = p.t[0];
            break;
          case elements::BlockRole::MaterialCoordinate:  // the unstretched arc length from node 0; padding 0
          case elements::BlockRole::MaterialSpin:        // and the spin angle 0
            q[0] = b.nodeArc[n] / b.discretization.gradientScale;
            break;
          case elements::BlockRole::Position:
            throw std::logic_error("Model: one position block per node");
        }
        placed[blk] = 1;
      }
    }
    const int perElement = b.blocksPerNode * 2;
    if (scene.bodies[bi].stressFreeInitial) {
      std::vector<double> q0e(static_cast<size_t>(b.elements) * perElement * _dim);
      for (int e = 0; e < b.elements; ++e)
        for (int a = 0; a < perElement; ++a)
          for (int i = 0; i < _dim; ++i)
            q0e[(static_cast<size_t>(e) * perElement + a) * _dim + i] = _q0[b.nodeBlocks[e * b.blocksPerNode + a] * _dim + i];
      b.referenceValues = info.referenceValues(b.section, b.discretization, q0e.data(), b.elements);
    }
    ElementGroup* group = nullptr;
    for (ElementGroup& g : _groups)
      if (g.kind == b.kind) group = &g;
    if (!group) {
      _groups.push_back({b.kind, perElement, {}, {}, {}});
      group = &_groups.back();
    }
    for (int e = 0; e < b.elements; ++e) {
      group->body.push_back(static_cast<int>(bi));
      group->index.push_back(e);
      for (int a = 0; a < perElement; ++a) group->blocks.push_back(b.nodeBlocks[e * b.blocksPerNode + a]);
    }
  }
  for (size_t r = 0; r < _rigid.size(); ++r) {
    const RigidBodyDesc& rd = scene.rigidBodies[r];
    for (int i = 0; i < _dim; ++i) _q0[_rigid[r].posBlock * _dim + i] = rd.position[i];
    if (_dim == 2) {
      _q0[_rigid[r].rotBlock * 2] = rd.angle;
      continue;
    }
    const std::array<double, 9> A = rotationMatrix(rd.axis, rd.angle);  // a_k = column k
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) _q0[(_rigid[r].rotBlock + k) * 3 + i] = A[i * 3 + k];
  }
}

// A clamp on a cable-like kind (whose orientation block is the slope r_x) holds the slope's
// direction and leaves its length, the axial stretch at the support, free: a rotating beam's root
// carries the centrifugal tension, a rod's root the end load (issue 36: holding the length forced
// zero root strain, 2.5 % on a chordwise frequency at 26 % strain). A beam's cross-section vector
// (shear kinds) is held whole. On a turning hub the held direction turns with it: see
// addClampDirectionJoints.
namespace {
bool orientedBySlope(const Body& b) { return b.info().layout[b.info().orientationBlock] == elements::BlockRole::AxialGradient; }
}  // namespace

bool Model::clampsSlopeDirection(const SupportDesc& s, const Body& b) const {
  return s.type == SupportType::Clamped && orientedBySlope(b);
}

// The unit normals of the direction t (2D: one, 3D: two, orthonormal).
std::vector<Vec3> Model::normalsOf(const Vec3& t) const {
  if (_dim == 2) return {{-t[1], t[0], 0.0}};
  const int k0 = std::fabs(t[0]) < 0.9 ? 0 : 1;  // a helper axis not parallel to t
  Vec3 e{};
  e[k0] = 1.0;
  Vec3 n1{t[1] * e[2] - t[2] * e[1], t[2] * e[0] - t[0] * e[2], t[0] * e[1] - t[1] * e[0]};
  const double l1 = std::sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
  for (double& x : n1) x /= l1;
  return {n1, {t[1] * n1[2] - t[2] * n1[1], t[2] * n1[0] - t[0] * n1[2], t[0] * n1[1] - t[1] * n1[0]}};
}

// For each support that holds a slope's direction (clampsSlopeDirection): along a coordinate axis
// the slope's other components are held (returned per support, eliminated like any fixed
// coordinate); along any other direction t the equations r_x . n = 0 for t's normals n hold it,
// with multipliers (a joint of dim - 1 equations on the slope block, appended to _joints).
// On a turning hub the normals turn with it, n(t) = R(psi(t)) n0: each is a block of its own (no
// element, no mass), all of its coordinates held and moved by the hub as a slope block is
// (addSupports), and the joint is r_x . n = 0 with n a Block field. So the rheonomic constraint
// needs nothing new from the joints or the integrators: it is the clamp joint to a driven rigid
// body's frame with the frame reduced to the normals.
Model::ClampDirections Model::addClampDirectionJoints(Build& build) {
  const SceneDescription& scene = build.scene;
  ClampDirections out;
  out.heldSlopeComponents.resize(scene.supports.size());
  out.turningNormals.resize(scene.supports.size());
  std::vector<std::pair<int, Vec3>> normalValues;  // block, n0
  for (size_t si = 0; si < scene.supports.size(); ++si) {
    const SupportDesc& s = scene.supports[si];
    const Body& b = build.body(_bodies, s.at.body, s.at.mark);
    if (!clampsSlopeDirection(s, b)) continue;
    const int ob = b.orientationBlock(nodeIndex(s.at, b));
    Vec3 t{};
    double len = 0.0;
    for (int i = 0; i < _dim; ++i) len += _q0[ob * _dim + i] * _q0[ob * _dim + i];
    len = std::sqrt(len);
    if (!(len > 0.0)) throw InputError(s.mark.where() + ": the clamped node's slope is zero; it has no direction to hold");
    int along = 0, nonzero = 0;
    for (int i = 0; i < _dim; ++i) {
      t[i] = _q0[ob * _dim + i] / len;
      if (std::fabs(t[i]) > 1e-14) ++nonzero, along = i;
    }
    if (nonzero == 1 && !s.hub.present) {
      for (int i = 0; i < _dim; ++i)
        if (i != along) out.heldSlopeComponents[si].push_back(i);
      continue;
    }
    Joint j;
    j.label = s.mark.where() + " (clamped: slope direction)";
    j.count = _dim - 1;
    j.blocks = {ob};
    j.lambdaBlocks = {_numBlocks++};
    for (const Vec3& nrm : normalsOf(t)) {
      elements::ConstraintEq o;
      o.form = elements::ConstraintForm::Orthogonal;
      o.a.kind = elements::JointField::Kind::Block;
      o.a.block = 0;
      if (s.hub.present) {  // n(t): a held block the hub turns
        o.b.kind = elements::JointField::Kind::Block;
        o.b.block = static_cast<int>(j.blocks.size());
        j.blocks.push_back(_numBlocks);
        out.turningNormals[si].push_back(_numBlocks);
        normalValues.emplace_back(_numBlocks++, nrm);
      } else {
        o.b.kind = elements::JointField::Kind::Constant;
        o.b.c = nrm;
      }
      j.equations.push_back(o);
    }
    _joints.push_back(std::move(j));
  }
  _q0.resize(numDofs(), 0.0);
  for (const auto& [block, n0] : normalValues)
    for (int i = 0; i < _dim; ++i) _q0[block * _dim + i] = n0[i];
  return out;
}

// A `sliding` support (an ALE body's inner node held in space while material slides through it:
// a guide, a ring, a sleeve) leaves the node's material coordinate p free; so does a reel at its
// exit node. The nodes between such a node and the next anchor on either side (an end, whose p is
// held, or another free node) keep their material spacing equal (seed 000 Eq. 51):
// p_n - (1 - w) p_a - w p_c = 0, w = (n - a) / (c - a), a linear joint (ConstraintForm::Linear)
// over the three material blocks with one multiplier. A reel's block (phi, padding) ties its exit
// node: p_exit - p_exit(0) = -/+ R phi (node 0: the body grows at its start, p falls; the last
// node: p rises). A payout on a body with sliding nodes prescribes node 0's p alone, the joints
// spreading it. Returns the material dofs left free (model numbering).
std::vector<int> Model::addMaterialJoints(Build& build) {
  const SceneDescription& scene = build.scene;
  std::vector<int> freeDofs;
  for (size_t bi = 0; bi < _bodies.size(); ++bi) {
    const Body& b = _bodies[bi];
    const int k = b.info().materialBlock();
    if (k < 0) continue;
    std::vector<int> anchors{0, b.elements};
    std::vector<char> sliding(b.elements + 1, 0);
    for (const SupportDesc& s : scene.supports)
      if (s.type == SupportType::Sliding && s.at.body == b.name) {
        const int n = nodeIndex(s.at, b);
        sliding[n] = 1;
        anchors.push_back(n);
      }
    for (size_t r = 0; r < _reels.size(); ++r) {
      if (_reels[r].body != b.name) continue;
      const int n = _reels[r].node == 0 ? 0 : b.elements;
      sliding[n] = 1;
      _reelBlock[r] = _numBlocks++;
      Joint jt;
      jt.label = "reel '" + _reels[r].name + "' (payout at node " + std::to_string(n) + ")";
      jt.count = 1;
      jt.blocks = {b.block(n, k), _reelBlock[r]};
      jt.lambdaBlocks = {_numBlocks++};
      elements::ConstraintEq e;
      e.form = elements::ConstraintForm::Linear;
      e.a.c = {1.0, (n == 0 ? 1.0 : -1.0) * _reels[r].radius, 0.0};
      e.length = _q0[b.block(n, k) * _dim];
      jt.equations.push_back(e);
      _joints.push_back(std::move(jt));
    }
    // (a payout with sliding nodes: every stretch between anchors has a sliding end, so its nodes get
    // joints; node 0's p alone is prescribed, addSupports)
    std::sort(anchors.begin(), anchors.end());
    anchors.erase(std::unique(anchors.begin(), anchors.end()), anchors.end());
    for (size_t j = 0; j + 1 < anchors.size(); ++j) {
      const int a = anchors[j], c = anchors[j + 1];
      if (!sliding[a] && !sliding[c]) continue;
      for (int n = a + 1; n < c; ++n) {
        const double w = static_cast<double>(n - a) / (c - a);
        Joint jt;
        jt.label = b.name + " node " + std::to_string(n) + " (equal material spacing)";
        jt.count = 1;
        jt.blocks = {b.block(n, k), b.block(a, k), b.block(c, k)};
        jt.lambdaBlocks = {_numBlocks++};
        elements::ConstraintEq e;
        e.form = elements::ConstraintForm::Linear;
        e.a.c = {1.0, -(1.0 - w), -w};
        jt.equations.push_back(e);
        _joints.push_back(std::move(jt));
        freeDofs.push_back(b.block(n, k) * _dim);
      }
    }
    for (int n = 0; n <= b.elements; ++n)
      if (sliding[n]) freeDofs.push_back(b.block(n, k) * _dim);
  }
  _q0.resize(numDofs(), 0.0);
  return freeDofs;
}

void Model::addSupports(Build& build) {
  const SceneDescription& scene = build.scene;
  const ClampDirections clampDirections = addClampDirectionJoints(build);
  const std::vector<int> freeMaterial = addMaterialJoints(build);
  _freeMaterial = !freeMaterial.empty();
  std::vector<char> materialFree(numDofs(), 0);
  for (int dof : freeMaterial) materialFree[dof] = 1;
  _fixed.assign(numDofs(), 0);
  _multiplier.assign(numDofs(), 0);
  for (size_t r = 0; r < _rigid.size(); ++r) {
    if (_dim == 3) {  // x, y, z of the centre of mass; the frame is free or driven
      for (int c : scene.rigidBodies[r].fixed) _fixed[_rigid[r].posBlock * 3 + c] = 1;
      if (scene.rigidBodies[r].driven) {  // a_k(t) = R(rotation(t) - rotation(0)) a_k(0): three "slope" blocks
        const int a = _rigid[r].rotBlock;
        for (int i = 0; i < 9; ++i) _fixed[a * 3 + i] = 1;
        _hubs.push_back({{}, scene.rigidBodies[r].rotationAxis, scene.rigidBodies[r].rotation, {a, a + 1, a + 2}, {1, 1, 1}});
      }
      continue;
    }
    _fixed[_rigid[r].rotBlock * 2 + 1] = 1;  // the unused coordinate of the rotation block
    for (int c : scene.rigidBodies[r].fixed) _fixed[(c < 2 ? _rigid[r].posBlock * 2 + c : _rigid[r].rotBlock * 2)] = 1;
    if (scene.rigidBodies[r].driven) {  // phi = angle + rotation(t): the unknown u = rotation(t)
      _fixed[_rigid[r].rotBlock * 2] = 1;
      _prescribed.push_back({_rigid[r].rotBlock * 2, scene.rigidBodies[r].rotation});
    }
  }
  for (const Joint& j : _joints)
    for (size_t k = 0; k < j.lambdaBlocks.size(); ++k)
      for (int i = 0; i < _dim; ++i) {
        const bool used = static_cast<int>(k) * _dim + i < j.count;
        (used ? _multiplier : _fixed)[j.lambdaBlocks[k] * _dim + i] = 1;
      }
  // ALE bodies: the padding of the material-coordinate blocks is held; the material coordinate
  // too, or it follows the body's material_motion (a prescribed coordinate)
  for (size_t bi = 0; bi < _bodies.size(); ++bi) {
    const Body& b = _bodies[bi];
    const int k = b.info().materialBlock();
    if (k < 0) continue;
    const MaterialWeights weights = materialNodeWeights(scene.bodies[bi], b.elements);
    for (int n = 0; n <= b.elements; ++n) {
      const int dof = b.block(n, k) * _dim;
      _fixed[dof] = !materialFree[dof];
      for (int i = elements::usedComponents(b.info().layout[k], _dim); i < _dim; ++i) _fixed[dof + i] = 1;
      if (scene.bodies[bi].hasMaterialMotion) _prescribed.push_back({dof, scene.bodies[bi].materialMotion, 1.0});
      if (scene.bodies[bi].hasPayout && n < b.elements && !materialFree[dof]) {
        // equal spacing: node n moves by -(N - n)/N of it (with sliding nodes only node 0 is
        // prescribed, by all of it: the others are free, spread by spacing joints)
        _prescribed.push_back({dof, scene.bodies[bi].payout, -static_cast<double>(b.elements - n) / b.elements});
      }
      // material_nodes: a listed node moves by its motion; the ones between two listed nodes a < n < c
      // by (1 - w) of a's and w of c's, w = (n - a) / (c - a) (equal spacing, Eq. 51)
      for (const auto& [function, scale] : weights[n]) _prescribed.push_back({dof, function, scale});
    }
  }
  // clamped: the position and the orientation block's direction (a cable's slope: its length, the
  // axial stretch, stays free; addClampDirectionJoints) or the whole block (a beam's cross-section
  // vector; clamped_unstretched); pinned: the position; fixed: the listed node
  // coordinates, block by block
  for (size_t si = 0; si < scene.supports.size(); ++si) {
    const SupportDesc& s = scene.supports[si];
    const Body& b = build.body(_bodies, s.at.body, s.at.mark);
    const int n = nodeIndex(s.at, b);
    const int pb = b.posBlock[n], ob = b.orientationBlock(n);
    const bool wholeOrientation = s.type == SupportType::ClampedUnstretched ||
                                  (s.type == SupportType::Clamped && !clampsSlopeDirection(s, b));
    for (int i = 0; i < _dim; ++i) {
      if (s.type != SupportType::Fixed) _fixed[pb * _dim + i] = 1;
      if (wholeOrientation) _fixed[ob * _dim + i] = 1;
    }
    for (int c : clampDirections.heldSlopeComponents[si]) _fixed[ob * _dim + c] = 1;
    for (int k : clampDirections.turningNormals[si])
      for (int i = 0; i < _dim; ++i) _fixed[k * _dim + i] = 1;
    if (s.type == SupportType::Fixed)
      for (int c : s.dofs) _fixed[b.block(n, c / _dim) * _dim + c % _dim] = 1;
    if (s.hub.present) {
      HubMotion h{s.hub.center, s.hub.axis, s.hub.angle, {pb}, {0}};
      if (wholeOrientation) {
        h.blocks.push_back(ob);
        h.slope.push_back(1);
      }
      for (int k : clampDirections.turningNormals[si]) {  // turned as slopes are
        h.blocks.push_back(k);
        h.slope.push_back(1);
      }
      for (const HubMotion& other : _hubs)
        for (int blk : other.blocks)
          if (blk == pb) throw InputError(s.hub.mark.where() + ": this node is already moved by another hub");
      _hubs.push_back(std::move(h));
    }
  }
}

void Model::addLoads(Build& build) {
  const SceneDescription& scene = build.scene;
  if (scene.loads.timed) _loadFunction = scene.loads.function;
  _nodalForce.assign(numDofs(), 0.0);
  for (const NodalLoadDesc& l : scene.loads.nodal) {
    const Body& b = build.body(_bodies, l.at.body, l.at.mark);
    const int n = nodeIndex(l.at, b);
    // a torque about the centerline is the generalized force on the spin angle (component 1 of the
    // MaterialSpin block): its virtual work is T delta theta (seed 000 Eq. 45-46)
    const int spinBlock = b.info().blockWith(elements::BlockRole::MaterialSpin);
    const int spinDof = spinBlock < 0 ? -1 : b.block(n, spinBlock) * _dim + 1;
    if (l.timed) {
      TimedLoad t{l.function, {}, {}};
      for (int i = 0; i < _dim; ++i) {
        t.dofs.push_back(b.posBlock[n] * _dim + i);
        t.values.push_back(l.force[i]);
      }
      if (spinDof >= 0 && l.spinTorque != 0.0) {
        t.dofs.push_back(spinDof);
        t.values.push_back(l.spinTorque);
      }
      _timed.push_back(std::move(t));
      continue;
    }
    for (int i = 0; i < _dim; ++i) _nodalForce[b.posBlock[n] * _dim + i] += l.force[i];
    if (spinDof >= 0) _nodalForce[spinDof] += l.spinTorque;
    if (l.moment[0] != 0.0 || l.moment[1] != 0.0 || l.moment[2] != 0.0) _moments.push_back({b.orientationBlock(n), l.moment});
  }
  for (const DistributedLoadDesc& l : scene.loads.distributed) {
    Body& b = build.body(_bodies, l.body, l.mark);
    for (int k = 0; k < 3; ++k) b.loadPerLength[k] += l.forcePerLength[k];
    b.spinTorquePerLength += l.spinTorquePerLength;
  }
  for (size_t r = 0; r < _rigid.size(); ++r) {
    const RigidBodyDesc& rd = scene.rigidBodies[r];
    const RigidBody& rb = _rigid[r];
    for (int i = 0; i < _dim; ++i) _nodalForce[rb.posBlock * _dim + i] += rd.mass * _gravity[i] + rd.force[i];
    if (_dim == 2) _nodalForce[rb.rotBlock * 2] += rd.torque[2];
  }
}

void Model::addInitialVelocities(Build& build) {
  const SceneDescription& scene = build.scene;
  _v0.assign(numDofs(), 0.0);
  for (size_t r = 0; r < _rigid.size(); ++r) {
    const RigidBodyDesc& rd = scene.rigidBodies[r];
    const RigidBody& rb = _rigid[r];
    for (int i = 0; i < _dim; ++i) _v0[rb.posBlock * _dim + i] = rd.velocity[i];
    if (_dim == 2) {
      _v0[rb.rotBlock * 2] = rd.angularVelocity[2];
      continue;
    }
    const Vec3& w = rd.angularVelocity;  // a_k' = w x a_k
    for (int k = 0; k < 3; ++k) {
      const double* a = &_q0[(rb.rotBlock + k) * 3];
      double* da = &_v0[(rb.rotBlock + k) * 3];
      da[0] = w[1] * a[2] - w[2] * a[1];
      da[1] = w[2] * a[0] - w[0] * a[2];
      da[2] = w[0] * a[1] - w[1] * a[0];
    }
  }
  // bodies: a rigid motion v = v_lin + w x (r - c) of the positions; gradient blocks turn with it,
  // w x (their coordinates)
  for (size_t bi = 0; bi < scene.bodies.size(); ++bi) {
    const BodyDesc& bd = scene.bodies[bi];
    if (!bd.hasInitialVelocity) continue;
    const Body& b = _bodies[bi];
    const Vec3& w = bd.angularVelocity;
    auto cross = [&](const double* r, double* out) {  // w x r in dim coordinates (2D: w = w_z e_z)
      if (_dim == 2) {
        out[0] = -w[2] * r[1];
        out[1] = w[2] * r[0];
      } else {
        out[0] = w[1] * r[2] - w[2] * r[1];
        out[1] = w[2] * r[0] - w[0] * r[2];
        out[2] = w[0] * r[1] - w[1] * r[0];
      }
    };
    for (int n = 0; n <= b.elements; ++n) {
      double r[3], v[3];
      for (int i = 0; i < _dim; ++i) r[i] = _q0[b.posBlock[n] * _dim + i] - bd.velocityCenter[i];
      cross(r, v);
      for (int i = 0; i < _dim; ++i) _v0[b.posBlock[n] * _dim + i] = bd.linearVelocity[i] + v[i];
      for (int k = 1; k < b.blocksPerNode; ++k) {
        const int blk = b.block(n, k);
        cross(&_q0[blk * _dim], v);
        for (int i = 0; i < _dim; ++i) _v0[blk * _dim + i] = v[i];
      }
    }
  }
  // ALE bodies with material_nodes: the material starts at rest (or at the body's initial
  // velocity) while the nodes move through it at their material rate pdot: a node's velocity is
  // the material's plus r' pdot (seed 000 Eq. 13 at the node, xi = 0). The slopes' own rate
  // r'' pdot is left out: exact for the straight initial shapes these bodies take.
  for (size_t bi = 0; bi < scene.bodies.size(); ++bi) {
    const Body& b = _bodies[bi];
    if (scene.bodies[bi].materialNodes.empty()) continue;
    const int slopeBlock = b.info().blockWith(elements::BlockRole::AxialGradient);
    if (b.info().materialBlock() < 0 || slopeBlock < 0) continue;
    const MaterialWeights weights = materialNodeWeights(scene.bodies[bi], b.elements);
    for (int n = 0; n <= b.elements; ++n) {
      double pdot = 0.0;
      for (const auto& [function, scale] : weights[n]) pdot += scale * function.at(0.0).df;
      for (int i = 0; i < _dim; ++i)
        _v0[b.posBlock[n] * _dim + i] += _q0[b.block(n, slopeBlock) * _dim + i] * pdot;
    }
  }
  for (int i = 0; i < numDofs(); ++i)  // supports hold their coordinates (hubs: the prescribed rate)
    if (_fixed[i]) _v0[i] = 0.0;
}

void Model::addJointEquations(Build& build) {
  // joint equations (directions from the initial state), checked at the initial state
  const SceneDescription& scene = build.scene;
  auto end = [&](const JointEndDesc& e, Joint& j, int* orientationBlock) -> elements::JointField {
    elements::JointField f;
    auto addBlock = [&](int blk) {
      j.blocks.push_back(blk);
      return static_cast<int>(j.blocks.size()) - 1;
    };
    switch (e.kind) {
      case JointEndDesc::Kind::Ground:
        f.kind = elements::JointField::Kind::Constant;
        f.c = e.point;
        break;
      case JointEndDesc::Kind::CableNode: {
        const Body& b = build.body(_bodies, e.body, e.mark);
        const int n = nodeIndex({e.body, e.node, e.mark}, b);
        f.kind = elements::JointField::Kind::Block;
        f.block = addBlock(b.posBlock[n]);
        if (orientationBlock) *orientationBlock = b.orientationBlock(n);
        break;
      }
      case JointEndDesc::Kind::RigidPoint: {
        auto it = build.rigidIndex.find(e.body);
        if (it == build.rigidIndex.end()) throw InputError(e.mark.where() + ": no rigid body named '" + e.body + "'");
        const RigidBody& rb = _rigid[it->second];
        f.kind = elements::JointField::Kind::RigidPoint;
        f.block = addBlock(rb.posBlock);
        for (int k = 1; k < rb.blocks(_dim); ++k) addBlock(rb.posBlock + k);
        f.c = e.point;
        break;
      }
    }
    return f;
  };
  for (size_t k = 0; k < scene.joints.size(); ++k) {
    const JointDesc& jd = scene.joints[k];
    Joint& j = _joints[k];
    int slope = -1;
    elements::ConstraintEq eq;
    eq.form = jd.type == JointType::Distance ? elements::ConstraintForm::Distance : elements::ConstraintForm::Equal;
    eq.a = end(jd.a, j, jd.type == JointType::Clamp ? &slope : nullptr);
    eq.b = end(jd.b, j, nullptr);
    if (jd.type == JointType::Clamp && (jd.a.kind != JointEndDesc::Kind::CableNode || jd.b.kind == JointEndDesc::Kind::CableNode))
      throw InputError(jd.mark.where() + ": a clamp holds a cable node (end a) to the ground or a rigid body (end b)");
    if (jd.type == JointType::Distance) {  // with length 0 the equation's value is the distance
      eq.length = jd.length >= 0.0 ? jd.length : constraintValues({eq}, j.blocks, _q0, _dim)[0];
      if (eq.length <= 0.0) throw InputError(jd.mark.where() + ": a distance joint needs ends apart (length > 0)");
    }
    j.equations.push_back(eq);
    if (jd.type == JointType::Clamp) {
      // the orientation vector (the cable's slope, a beam's r_y) keeps its initial direction t:
      // t' . n = 0 for the normals n of t (2D: one, 3D: two)
      const int sb = static_cast<int>(j.blocks.size());
      j.blocks.push_back(slope);
      Vec3 t{};
      double len = 0.0;
      for (int i = 0; i < _dim; ++i) len += _q0[slope * _dim + i] * _q0[slope * _dim + i];
      for (int i = 0; i < _dim; ++i) t[i] = _q0[slope * _dim + i] / std::sqrt(len);
      for (const Vec3& nrm : normalsOf(t)) {
        elements::ConstraintEq o;
        o.form = elements::ConstraintForm::Orthogonal;
        o.a.kind = elements::JointField::Kind::Block;
        o.a.block = sb;
        if (jd.b.kind == JointEndDesc::Kind::Ground) {
          o.b.kind = elements::JointField::Kind::Constant;
          o.b.c = nrm;
        } else if (_dim == 3) {  // the normal in the rigid body's frame: c_k = a_k(0) . n
          o.b.kind = elements::JointField::Kind::RigidDirection;
          o.b.block = eq.b.block + 1;
          for (int a = 0; a < 3; ++a) {
            const double* ak = &_q0[j.blocks[eq.b.block + 1 + a] * 3];
            o.b.c[a] = ak[0] * nrm[0] + ak[1] * nrm[1] + ak[2] * nrm[2];
          }
        } else {  // the normal in the rigid body's frame: R(phi0)^T n
          const double phi = _q0[j.blocks[eq.b.block + 1] * _dim], c = std::cos(phi), s = std::sin(phi);
          o.b.kind = elements::JointField::Kind::RigidDirection;
          o.b.block = eq.b.block + 1;
          o.b.c = {c * nrm[0] + s * nrm[1], -s * nrm[0] + c * nrm[1], 0.0};
        }
        j.equations.push_back(o);
      }
    }
    // the initial state must satisfy the joint
    const std::vector<double> g = constraintValues(j.equations, j.blocks, _q0, _dim);
    for (int r = 0; r < j.count; ++r)
      if (std::fabs(g[r]) > 1e-9 * std::max(1.0, _scales.length))
        throw InputError(jd.mark.where() + ": the initial state violates this joint by " + std::to_string(g[r]) +
                         " (equation " + std::to_string(r) + "); place its ends together (pin, clamp) or omit `length` (distance)");
  }
}

void Model::addCouplings() {
  for (size_t r = 0; r < _rigid.size(); ++r) {
    Coupling c{static_cast<int>(r), -1, {}};
    for (int k = 0; k < _rigid[r].blocks(_dim); ++k) c.blocks.push_back(_rigid[r].posBlock + k);
    _couplings.push_back(std::move(c));
  }
  for (size_t k = 0; k < _joints.size(); ++k) {
    Coupling c{-1, static_cast<int>(k), _joints[k].lambdaBlocks};
    c.blocks.insert(c.blocks.end(), _joints[k].blocks.begin(), _joints[k].blocks.end());
    _couplings.push_back(std::move(c));
  }
}

double ReferenceScales::time() const { return std::sqrt(rhoA * length * length * length * length / EI); }
double ReferenceScales::slenderness() const { return std::sqrt(EA * length * length / EI); }

}  // namespace strand::model
