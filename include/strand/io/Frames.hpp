// Turn a coordinate vector (model numbering, gathered on rank 0) into output frames:
// centerline points sampled along each body and the nodal coordinates (r, r') per node.
#pragma once
#include <vector>

#include "strand/io/OutputWriter.hpp"
#include "strand/model/Model.hpp"

namespace strand::io {

// The bodies' frame layouts, with their cell fields: axial_force [N] where the kind provides it
// (KindInfo::axialForce), and on a body in contact with pulleys contact_pressure [N per m of
// reference length, summed over the pulleys, averaged over the element's contact points] and
// contact_state (0 off the pulleys, 1 touching and sticking, 2 a point of the element slipping).
std::vector<BodyLayout> bodyLayouts(const model::Model& model, int samplesPerElement);

// Per body and element, what the contact law found (ElementContact::add collects it; sum the
// pressures and take the largest state over ranks): the fields contact_pressure and contact_state.
struct ElementContact {
  std::vector<std::vector<double>> pressure, state;  // [body][element]
  std::vector<int> points;                            // [body]: contact points per element (0: no contact)
  explicit ElementContact(const model::Model& model);
  // a contact point: its pressure, whether it touches and whether it sticks
  void add(int body, int element, double pressure, bool touching, bool sticking);
};

// q: full coordinate vector in model numbering (rank 0); returns one frame per body, with the
// layout's cell fields (contact: those of `contact`, null: none touching).
std::vector<BodyFrame> makeFrames(const model::Model& model, const std::vector<double>& q, int samplesPerElement,
                                  const ElementContact* contact = nullptr);
// Mode shapes: the frames without cell fields.
std::vector<BodyFrame> makeShapes(const model::Model& model, const std::vector<double>& q, int samplesPerElement);
// Position of a point of a body at local coordinate eta of element e (Hermite interpolation).
model::Vec3 positionOnBody(const model::Model& model, const std::vector<double>& q, int body, int element, double eta);

}  // namespace strand::io
