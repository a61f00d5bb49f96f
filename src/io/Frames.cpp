#include "strand/io/Frames.hpp"

#include <algorithm>

namespace strand::io {

namespace {
bool inContact(const model::Model& model, int body) {
  for (const model::PulleyContactSet& c : model.contacts())
    if (c.body == body) return true;
  return false;
}
}  // namespace

ElementContact::ElementContact(const model::Model& model) : points(model.bodies().size(), 0) {
  for (const model::Body& b : model.bodies()) {
    pressure.emplace_back(b.elements, 0.0);
    state.emplace_back(b.elements, 0.0);
  }
  for (const model::PulleyContactSet& c : model.contacts()) points[c.body] = c.points;
}

void ElementContact::add(int body, int element, double p, bool touching, bool sticking) {
  pressure[body][element] += p / points[body];
  double& s = state[body][element];
  if (touching) s = std::max(s, sticking ? 1.0 : 2.0);
}

std::vector<BodyLayout> bodyLayouts(const model::Model& model, int samplesPerElement) {
  std::vector<BodyLayout> out;
  for (const model::Body& b : model.bodies()) {
    BodyLayout l;
    l.name = b.name;
    l.elementType = b.info().name;
    l.elements = b.elements;
    l.nodes = b.elements + 1;
    l.coordsPerNode = b.blocksPerNode * model.dim();
    l.pointsPerBody = b.elements * samplesPerElement + 1;
    if (b.info().axialForce) l.cellFields.push_back("axial_force");
    if (inContact(model, static_cast<int>(out.size()))) {
      l.cellFields.push_back("contact_pressure");
      l.cellFields.push_back("contact_state");
    }
    out.push_back(l);
  }
  return out;
}

model::Vec3 positionOnBody(const model::Model& model, const std::vector<double>& q, int body, int e, double eta) {
  const model::Body& b = model.bodies()[body];
  const int d = model.dim();
  const int perElement = 2 * b.blocksPerNode;
  double w[elements::kMaxBlocksPerElement];  // the kind's centerline interpolation weights, one per element slot
  double qe[elements::kMaxBlocksPerElement * 3];
  for (int a = 0; a < perElement; ++a)
    for (int i = 0; i < d; ++i) qe[a * d + i] = q[b.nodeBlocks[e * b.blocksPerNode + a] * d + i];
  b.info().interpolationAt(b.discretization, qe, eta, w);
  model::Vec3 r{0, 0, 0};
  for (int a = 0; a < perElement; ++a)
    for (int i = 0; i < d; ++i) r[i] += w[a] * qe[a * d + i];
  return r;
}

std::vector<BodyFrame> makeShapes(const model::Model& model, const std::vector<double>& q, int samplesPerElement) {
  std::vector<BodyFrame> frames;
  const int d = model.dim();
  for (int bi = 0; bi < static_cast<int>(model.bodies().size()); ++bi) {
    const model::Body& b = model.bodies()[bi];
    BodyFrame f;
    f.centerline.reserve(3 * (b.elements * samplesPerElement + 1));
    for (int e = 0; e < b.elements; ++e)
      for (int s = 0; s < samplesPerElement; ++s) {
        const model::Vec3 r = positionOnBody(model, q, bi, e, static_cast<double>(s) / samplesPerElement);
        f.centerline.insert(f.centerline.end(), r.begin(), r.end());
      }
    const model::Vec3 end = positionOnBody(model, q, bi, b.elements - 1, 1.0);
    f.centerline.insert(f.centerline.end(), end.begin(), end.end());
    // nodal coordinates, block by block in the kind's layout; gradients unscaled (dr/dx, dr/dy)
    for (int n = 0; n <= b.elements; ++n)
      for (int k = 0; k < b.blocksPerNode; ++k) {
        const int blk = b.block(n, k);
        for (int i = 0; i < d; ++i) f.coordinates.push_back(q[blk * d + i] / b.blockScale(k));
      }
    frames.push_back(std::move(f));
  }
  return frames;
}

std::vector<BodyFrame> makeFrames(const model::Model& model, const std::vector<double>& q, int samplesPerElement,
                                  const ElementContact* contact) {
  std::vector<BodyFrame> frames = makeShapes(model, q, samplesPerElement);
  const int d = model.dim();
  for (int bi = 0; bi < static_cast<int>(model.bodies().size()); ++bi) {
    const model::Body& b = model.bodies()[bi];
    BodyFrame& f = frames[bi];
    const size_t segments = static_cast<size_t>(b.elements) * samplesPerElement;
    if (b.info().axialForce) {  // at each segment's middle
      std::vector<double> force(segments);
      const int perElement = 2 * b.blocksPerNode;
      double qe[elements::kMaxBlocksPerElement * 3];
      for (int e = 0; e < b.elements; ++e) {
        for (int a = 0; a < perElement; ++a)
          for (int i = 0; i < d; ++i) qe[a * d + i] = q[b.nodeBlocks[e * b.blocksPerNode + a] * d + i];
        for (int s = 0; s < samplesPerElement; ++s)
          force[static_cast<size_t>(e) * samplesPerElement + s] =
              b.info().axialForce(b.section, b.discretization, qe, (s + 0.5) / samplesPerElement);
      }
      f.cellFields.push_back(std::move(force));
    }
    if (inContact(model, bi))
      for (int k = 0; k < 2; ++k) {
        std::vector<double> field(segments, 0.0);
        if (contact)
          for (int e = 0; e < b.elements; ++e)
            for (int s = 0; s < samplesPerElement; ++s)
              field[static_cast<size_t>(e) * samplesPerElement + s] = (k == 0 ? contact->pressure : contact->state)[bi][e];
        f.cellFields.push_back(std::move(field));
      }
  }
  return frames;
}

}  // namespace strand::io
