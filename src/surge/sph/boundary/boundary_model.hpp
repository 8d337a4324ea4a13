// SPH wall models (sph.boundary): how wall and body particles get the density whose
// pressure holds the water off. The solver sees only this interface; each model is one
// file of this folder (dynamic_boundary.cpp, mdbc_boundary.cpp) and one line of the
// registry (boundary_model.cpp). The no-penetration condition that keeps water in front
// of the wall faces works with any model (wall_hold.hpp).
#pragma once
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/particles/particle_store.hpp"
#include "surge/sph/initial_state.hpp"
#include "surge/sph/wcsph_rates.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::sph {

class BoundaryModel {
public:
  virtual ~BoundaryModel() = default;
  // Before the EOS and the rates: the boundary particles' densities at the current
  // positions (each boundary particle writes only its own).
  virtual void prepare(const WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& p) = 0;
  // Whether prepare does anything (the solver then skips its timed phase: two events a
  // step on a GPU).
  [[nodiscard]] virtual bool prepares() const { return true; }
  // How much further than one kernel support a boundary particle's density reads
  // (a distributed run's halo grows by it).
  [[nodiscard]] virtual double extra_reach() const = 0;
  // Its ghost offsets in the execution space, per boundary particle by id - first boundary
  // id (wall then body particles): the coupling turns the body ones with their spheres, the
  // no-penetration condition reads the wall ones; null if the model keeps none.
  [[nodiscard]] virtual Vec3* ghost_offsets() = 0;
  // Bytes it holds in the execution space.
  [[nodiscard]] virtual std::size_t bytes() const = 0;
};

// A model as the case file names it.
struct BoundaryModelInfo {
  const char* name;
  std::unique_ptr<BoundaryModel> (*make)(const InitialState& init, const WcsphParams& prm);
};

// Every model, in the order of the case schema's choices for sph.boundary (a test
// checks that both list the same names).
const std::vector<BoundaryModelInfo>& boundary_models();
// The model called `name`; std::invalid_argument naming the known ones if there is none
// (the case reader has rejected such a name already).
const BoundaryModelInfo& boundary_model(const std::string& name);

} // namespace surge::sph
