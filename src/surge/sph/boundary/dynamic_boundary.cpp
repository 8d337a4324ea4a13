// The dynamic boundary (SPEC §2.6, the paper's; Crespo et al. 2007): wall and body
// particles sum continuity over their fluid neighbours in the rates pass like fluid
// particles, their density clamped at rho0, and do not move by it. Their pressure holds
// the water about a spacing off (the "gap"). Nothing to prepare, nothing to keep.
#include "surge/sph/boundary/boundary_model.hpp"

namespace surge::sph {

namespace {
class DynamicBoundary final : public BoundaryModel {
public:
  void prepare(const WcsphParams&, const neighbour::GridView&, const particles::ParticleView&) override {}
  [[nodiscard]] bool prepares() const override { return false; }
  [[nodiscard]] double extra_reach() const override { return 0; }
  [[nodiscard]] Vec3* ghost_offsets() override { return nullptr; }
  [[nodiscard]] std::size_t bytes() const override { return 0; }
};
} // namespace

std::unique_ptr<BoundaryModel> make_dynamic_boundary(const InitialState& /*init*/, const WcsphParams& /*prm*/) {
  return std::make_unique<DynamicBoundary>();
}

} // namespace surge::sph
