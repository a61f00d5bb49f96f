// Probes (scene key `probes`, model::ProbeDesc): points whose position, velocity and support force
// are written every step as scalar series /series/probe_<name>_<q><axis>, q = "" (position), "v"
// (velocity), "f" (force), axis = x, y (, z) of the probe's frame. Cheap: one scatter of the few
// coordinates the probes need to rank 0 per step, no gather of the state.
//
// Frames: an origin c(t) and axes a_k(t) with their rates; a point x, v, f is written as
//   x_k = a_k . (x - c),   v_k = da_k/dt . (x - c) + a_k . (v - dc/dt),   f_k = a_k . f
// (v_k: the rate of x_k, the velocity seen in that frame). world: c = 0, a_k = e_k; hub: the hub
// that turns the probe's body, c its center, a_k = R(psi(t) - psi(0)) e_k; a rigid body: its
// position and body axes (2D: angle phi).
// A point along a body (`at`) is interpolated at a fixed element coordinate (for ALE kinds a mesh
// point, not a material point) and moves with v = sum_a w_a v_a.
#pragma once
#include <petscvec.h>

#include <string>
#include <vector>

#include "strand/io/OutputWriter.hpp"
#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::io {

class Probes {
public:
  // Resolves the scene's probes against the model; throws InputError (file, line, key, reason)
  // for a force probe on a node no support holds or a hub frame where no hub turns the body.
  Probes(const model::SceneDescription& scene, const model::Model& model, const model::DofMap& dofs);
  ~Probes();
  Probes(const Probes&) = delete;
  Probes& operator=(const Probes&) = delete;

  bool empty() const { return _probes.empty(); }
  bool needForce() const;
  // Collective. X: displacements u = q - q0 (the solvers' vectors); V: velocities or null (statics:
  // no velocity series); F: support forces (Dynamics::supportForce) or null; t: time or load factor.
  PetscErrorCode write(OutputWriter& out, double t, Vec X, Vec V, Vec F);

private:
  enum class FrameKind { World, Hub, Rigid };
  struct Probe {
    std::string name;
    model::ProbeDesc::Kind kind;
    std::vector<int> slots;  // the point's blocks as indices into the gathered values
    int body = -1;           // Along: the body, its element and eta
    double eta = 0.0;
    model::Vec3 point{};     // RigidPoint: body-frame offset
    int rigidSlot = -1;      // RigidPoint: slot of the rigid body's position block (frame blocks follow)
    FrameKind frame = FrameKind::World;
    int hub = -1;            // Hub: index into Model::hubMotions()
    int frameSlot = -1;      // Rigid frame: slot of its position block (frame blocks follow)
    bool force = false;
  };
  struct Frame {
    model::Vec3 c{}, dc{}, a[3]{}, da[3]{};
  };
  int slotOf(int block);
  int rigidSlots(int rigid);  // the rigid body's position block and its frame blocks, consecutive
  Frame frameOf(const Probe& p, double t, const std::vector<double>& q, const std::vector<double>& v) const;
  void pointOf(const Probe& p, const std::vector<double>& q, const std::vector<double>& v, model::Vec3* x,
               model::Vec3* xv) const;
  PetscErrorCode gather(Vec from, bool addReference, std::vector<double>* values);

  const model::Model& _model;
  const model::DofMap& _dofs;
  int _dim;
  std::vector<Probe> _probes;
  std::vector<int> _blocks;  // the gathered model blocks, in slot order
  VecScatter _scatter = nullptr;
  Vec _local = nullptr;
};

}  // namespace strand::io
