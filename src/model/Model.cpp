#include "strand/model/Model.hpp"

#include <cmath>
#include <map>

#include "strand/core/Error.hpp"
#include "strand/elements/AncfCable.hpp"
#include "strand/model/InitialGeometry.hpp"

namespace strand::model {
namespace {

int nodeIndex(const NodeRef& ref, const Body& b) {
  const long n = ref.node < 0 ? b.elements : ref.node;
  if (n > b.elements) throw InputError(ref.mark.where() + ": node " + std::to_string(n) + " out of range 0.." + std::to_string(b.elements));
  return static_cast<int>(n);
}

// Reference curvature of the interpolated initial shape at each Gauss point, so that the initial
// shape is exactly stress free ("stress_free: initial", 2D only; the axial reference is always the
// initial shape).
void referenceStrains(Body& body, const std::vector<double>& q0, int gaussPoints) {
  using E = elements::AncfCable2d;
  const elements::CableShapeTable tab(gaussPoints);
  body.kappa0.assign(body.elements * gaussPoints, 0.0);
  for (int e = 0; e < body.elements; ++e) {
    E::Geometry geo;
    geo.length = body.elementLength;
    geo.slopeScale[0] = body.slopeScale[e];
    geo.slopeScale[1] = body.slopeScale[e + 1];
    double q[E::kDof];
    const int blocks[4] = {body.posBlock[e], body.slopeBlock[e], body.posBlock[e + 1], body.slopeBlock[e + 1]};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 2; ++i) q[2 * a + i] = q0[2 * blocks[a] + i];
    for (int g = 0; g < gaussPoints; ++g) {
      double G[E::kG], kap[1];
      E::gather(E::slots(geo, tab.at[g]), q, G);
      E::curvature(G, kap);
      body.kappa0[e * gaussPoints + g] = kap[0];
    }
  }
}

}  // namespace

Model::Model(const SceneDescription& scene)
    : _dim(scene.dimension), _gaussPoints(scene.discretization.gaussPoints), _gravity(scene.loads.gravity),
      _rotation(scene.rotation) {
  std::map<std::string, int> bodyIndex;
  std::vector<InitialGeometry> curves;
  std::vector<double> q0;
  std::vector<CurvePoint> nodePoints;
  // 1. bodies and their blocks
  for (const BodyDesc& bd : scene.bodies) {
    Body b;
    b.name = bd.name;
    b.elements = bd.elements;
    curves.emplace_back(bd.geometry, _dim, scene.loads.gravity);
    b.length = curves.back().length();
    b.elementLength = b.length / b.elements;
    b.section = {bd.E * bd.A, bd.E * bd.I, bd.rho * bd.A, bd.dampAxial, bd.dampBending};
    for (int n = 0; n <= b.elements; ++n) {
      b.posBlock.push_back(_numBlocks++);
      b.slopeBlock.push_back(_numBlocks++);
      b.slopeScale.push_back(scene.discretization.slopeScaling ? b.elementLength : 1.0);
    }
    for (int k = 0; k < 3; ++k) b.loadPerLength[k] = b.section.rhoA * scene.loads.gravity[k];
    for (const PointMassDesc& pm : bd.pointMasses) {
      const double x = std::min(std::max(pm.at, 0.0), b.length);
      const int e = std::min(static_cast<int>(x / b.elementLength), b.elements - 1);
      b.pointMasses.push_back({e, x / b.elementLength - e, pm.mass});
    }
    if (_bodies.empty()) _scales = {b.length, b.section.rhoA, b.section.EI, b.section.EA};
    bodyIndex[b.name] = static_cast<int>(_bodies.size());
    _bodies.push_back(std::move(b));
  }
  auto findBody = [&](const std::string& name, const SourceMark& mark) -> Body& {
    auto it = bodyIndex.find(name);
    if (it == bodyIndex.end()) throw InputError(mark.where() + ": no body named '" + name + "'");
    return _bodies[it->second];
  };
  // 2. junctions: the listed nodes share one position block (union-find over blocks)
  std::vector<int> parent(_numBlocks);
  for (int k = 0; k < _numBlocks; ++k) parent[k] = k;
  auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const JunctionDesc& j : scene.junctions) {
    if (j.nodes.size() < 2) throw InputError(j.mark.where() + ": a junction needs at least two nodes");
    const Body& b0 = findBody(j.nodes[0].body, j.nodes[0].mark);
    const int first = root(b0.posBlock[nodeIndex(j.nodes[0], b0)]);
    for (size_t k = 1; k < j.nodes.size(); ++k) {
      const Body& bk = findBody(j.nodes[k].body, j.nodes[k].mark);
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
    for (int& blk : b.slopeBlock) blk = compact[root(blk)];
  }
  _numBlocks = next;
  // 3. initial coordinates; junction nodes must coincide
  _q0.assign(numDofs(), 0.0);
  std::vector<char> placed(_numBlocks, 0);
  for (size_t bi = 0; bi < _bodies.size(); ++bi) {
    Body& b = _bodies[bi];
    for (int n = 0; n <= b.elements; ++n) {
      const CurvePoint p = curves[bi].at(n * b.elementLength);
      const int pb = b.posBlock[n], sb = b.slopeBlock[n];
      for (int i = 0; i < _dim; ++i) {
        if (placed[pb] && std::fabs(_q0[pb * _dim + i] - p.r[i]) > 1e-9 * std::max(1.0, b.length))
          throw InputError(scene.bodies[bi].mark.where() + ": node " + std::to_string(n) +
                           " of a junction does not coincide with the other nodes of the junction");
        _q0[pb * _dim + i] = p.r[i];
        _q0[sb * _dim + i] = b.slopeScale[n] * p.t[i];
      }
      placed[pb] = placed[sb] = 1;
    }
    if (scene.bodies[bi].stressFreeInitial) referenceStrains(b, _q0, _gaussPoints);
    for (int e = 0; e < b.elements; ++e)
      _elements.push_back({static_cast<int>(bi), e, {b.posBlock[e], b.slopeBlock[e], b.posBlock[e + 1], b.slopeBlock[e + 1]}});
  }
  // 4. supports
  _fixed.assign(numDofs(), 0);
  for (const SupportDesc& s : scene.supports) {
    const Body& b = findBody(s.at.body, s.at.mark);
    const int n = nodeIndex(s.at, b);
    const int pb = b.posBlock[n], sb = b.slopeBlock[n];
    for (int i = 0; i < _dim; ++i) {
      if (s.type == SupportType::Clamped || s.type == SupportType::Pinned) _fixed[pb * _dim + i] = 1;
      if (s.type == SupportType::Clamped) _fixed[sb * _dim + i] = 1;
    }
    if (s.type == SupportType::Fixed)
      for (int c : s.dofs) _fixed[(c < _dim ? pb : sb) * _dim + c % _dim] = 1;
    if (s.hub.present) {
      HubMotion h{s.hub.center, s.hub.axis, s.hub.angle, {pb}, {0}};
      if (s.type == SupportType::Clamped) {
        h.blocks.push_back(sb);
        h.slope.push_back(1);
      }
      for (const HubMotion& other : _hubs)
        for (int blk : other.blocks)
          if (blk == pb) throw InputError(s.hub.mark.where() + ": this node is already moved by another hub");
      _hubs.push_back(std::move(h));
    }
  }
  // 5. loads
  _nodalForce.assign(numDofs(), 0.0);
  for (const NodalLoadDesc& l : scene.loads.nodal) {
    const Body& b = findBody(l.at.body, l.at.mark);
    const int n = nodeIndex(l.at, b);
    for (int i = 0; i < _dim; ++i) _nodalForce[b.posBlock[n] * _dim + i] += l.force[i];
    if (l.moment[0] != 0.0 || l.moment[1] != 0.0 || l.moment[2] != 0.0) _moments.push_back({b.slopeBlock[n], l.moment});
  }
  for (const DistributedLoadDesc& l : scene.loads.distributed) {
    Body& b = findBody(l.body, l.mark);
    for (int k = 0; k < 3; ++k) b.loadPerLength[k] += l.forcePerLength[k];
  }
}

double ReferenceScales::time() const { return std::sqrt(rhoA * length * length * length * length / EI); }
double ReferenceScales::slenderness() const { return std::sqrt(EA * length * length / EI); }

}  // namespace strand::model
