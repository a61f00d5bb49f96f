#include "strand/io/Frames.hpp"

#include "strand/math/Hermite.hpp"

namespace strand::io {

std::vector<BodyLayout> bodyLayouts(const model::Model& model, int samplesPerElement) {
  std::vector<BodyLayout> out;
  for (const model::Body& b : model.bodies()) {
    BodyLayout l;
    l.name = b.name;
    l.elementType = model.dim() == 2 ? "AncfCable2d" : "AncfCable3d";
    l.elements = b.elements;
    l.nodes = b.elements + 1;
    l.coordsPerNode = 2 * model.dim();
    l.pointsPerBody = b.elements * samplesPerElement + 1;
    out.push_back(l);
  }
  return out;
}

model::Vec3 positionOnBody(const model::Model& model, const std::vector<double>& q, int body, int e, double eta) {
  const model::Body& b = model.bodies()[body];
  const int d = model.dim();
  const math::HermiteValues h = math::hermite(eta);
  const double l = b.elementLength;
  const int blocks[4] = {b.posBlock[e], b.slopeBlock[e], b.posBlock[e + 1], b.slopeBlock[e + 1]};
  const double coef[4] = {h.s[0], h.s[1] * l / b.slopeScale[e], h.s[2], h.s[3] * l / b.slopeScale[e + 1]};
  model::Vec3 r{0, 0, 0};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < d; ++i) r[i] += coef[a] * q[blocks[a] * d + i];
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
    // nodal coordinates: position and the unscaled slope dr/dx
    for (int n = 0; n <= b.elements; ++n) {
      for (int i = 0; i < d; ++i) f.coordinates.push_back(q[b.posBlock[n] * d + i]);
      for (int i = 0; i < d; ++i) f.coordinates.push_back(q[b.slopeBlock[n] * d + i] / b.slopeScale[n]);
    }
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace strand::io
