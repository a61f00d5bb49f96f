// Scenes and closed forms for the 2D shear-deformable ANCF beams (AncfBeam2dShear, AncfBeam2dLinear;
// seed 004 ch. 2): a cantilever of rectangular section built in code, and Timoshenko beam theory.
#pragma once
#include <cmath>
#include <string>

#include "support/Scenes.hpp"

namespace strand::testing {

struct RectangleSection {
  double E = 2.1e11, nu = 0.3, rho = 7850.0, width = 0.1, height = 0.1;
  double area() const { return width * height; }
  double inertia() const { return width * height * height * height / 12.0; }
  double shearModulus() const { return E / (2.0 * (1.0 + nu)); }
  // Cowper (J. Appl. Mech. 33, 1966) for a rectangle: the elements' default with decoupled elasticity
  double shearFactor() const { return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu); }
};

// A body of `kind` along +x from `start` with the section s and the formulation options.
inline model::BodyDesc shearBeamBody(const std::string& name, const std::string& kind, int elements, model::Vec3 start,
                                     model::Vec3 end, const RectangleSection& s,
                                     const std::string& integration = "selective",
                                     const std::string& elasticity = "decoupled") {
  model::BodyDesc b;
  b.name = name;
  b.kind = elements::findKind(kind);
  b.elements = elements;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = start;
  b.geometry.end = end;
  b.section.numbers = {{"E", s.E}, {"nu", s.nu}, {"rho", s.rho}, {"width", s.width}, {"height", s.height},
                       {"shear_factor", 0.0}, {"damping", 0.0}};
  b.section.options = {{"integration", integration}, {"elasticity", elasticity}};
  return b;
}

// A cantilever of length L along +x, clamped at node 0 (the whole end section held: r and r_y).
inline model::SceneDescription shearCantilever(const std::string& kind, int elements, double L,
                                               const RectangleSection& s, const std::string& integration = "selective",
                                               const std::string& elasticity = "decoupled") {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.bodies.push_back(shearBeamBody("beam", kind, elements, {0, 0, 0}, {L, 0, 0}, s, integration, elasticity));
  model::SupportDesc clamp;
  clamp.at.body = "beam";
  clamp.at.node = 0;
  clamp.type = model::SupportType::Clamped;
  sc.supports.push_back(clamp);
  return sc;
}

// Timoshenko: tip deflection of a cantilever under a tip force F, F L^3 / (3 E I) + F L / (k G A).
inline double timoshenkoTipDeflection(double F, double L, const RectangleSection& s) {
  return F * L * L * L / (3.0 * s.E * s.inertia()) + F * L / (s.shearFactor() * s.shearModulus() * s.area());
}

}  // namespace strand::testing
