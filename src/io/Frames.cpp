#include "strand/io/Frames.hpp"

namespace strand::io {

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

std::vector<BodyFrame> makeFrames(const model::Model& model, const std::vector<double>& q, int samplesPerElement) {
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

}  // namespace strand::io
