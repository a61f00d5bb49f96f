// Turn a coordinate vector (model numbering, gathered on rank 0) into output frames:
// centerline points sampled along each body and the nodal coordinates (r, r') per node.
#pragma once
#include <vector>

#include "strand/io/OutputWriter.hpp"
#include "strand/model/Model.hpp"

namespace strand::io {

std::vector<BodyLayout> bodyLayouts(const model::Model& model, int samplesPerElement);
// q: full coordinate vector in model numbering (rank 0); returns one frame per body.
std::vector<BodyFrame> makeFrames(const model::Model& model, const std::vector<double>& q, int samplesPerElement);
// Position of a point of a body at local coordinate eta of element e (Hermite interpolation).
model::Vec3 positionOnBody(const model::Model& model, const std::vector<double>& q, int body, int element, double eta);

}  // namespace strand::io
