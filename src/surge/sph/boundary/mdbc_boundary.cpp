// The modified dynamic boundary (English et al. 2022; the formulas in mdbc_density.hpp):
// each wall and body particle takes the fluid's density at its ghost node, x_b + offset,
// before the rates. It keeps the offsets (12 B per boundary particle); the coupling turns
// the body particles' ones with their spheres.
#include "surge/sph/boundary/boundary_model.hpp"
#include "surge/sph/boundary/mdbc_density.hpp"
#if defined(SURGE_SIMD)
#include "surge/sph/wcsph_rates_simd.hpp"
#endif

#include <cmath>

namespace surge::sph {

namespace detail {
// Each boundary particle's density from the fluid at its ghost node (a free function:
// nvcc's extended lambdas may not live in private member functions).
void mdbc_densities(const WcsphParams& prm, const Vec3* offset, std::uint32_t first_id, const neighbour::GridView& g,
                    const particles::ParticleView& p) {
#if defined(SURGE_SIMD)
  if (const MdbcFn batched = batched_mdbc()) { // the CPU's: 8 neighbours at a time
    for_each_rates_block(p.n, [=](int begin, int end) { batched(prm, g, p, offset, first_id, begin, end); });
    return;
  }
#endif
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const Real rho0 = prm.eos.rho0;
  par::parallel_for_uneven(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] == fluid) return;
        const Vec3 xb = p.pos[i];
        const Real rho = mdbc_density(prm, g, p, xb, xb + offset[p.id[i] - first_id], p.rho[i]);
        p.rho[i] = boundary_density(rho, rho0);
      });
}
} // namespace detail

namespace {
class MdbcBoundary final : public BoundaryModel {
public:
  MdbcBoundary(const InitialState& init, double support) : first_id_(init.first_boundary_id), support_(support) {
    par::upload(offset_, init.boundary_ghost);
    for (const auto& o : init.boundary_ghost) longest_ = std::fmax(longest_, static_cast<double>(norm(o)));
  }
  void prepare(const WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& p) override {
    detail::mdbc_densities(prm, offset_.data(), first_id_, g, p);
  }
  // The ghost node lies up to the longest offset away, and its density reads a kernel
  // support around it.
  [[nodiscard]] double extra_reach() const override { return longest_ + support_; }
  [[nodiscard]] Vec3* ghost_offsets() override { return offset_.data(); }
  [[nodiscard]] std::size_t bytes() const override { return offset_.bytes(); }

private:
  std::uint32_t first_id_;
  double support_;
  par::Buffer<Vec3> offset_;
  double longest_ = 0;
};
} // namespace

std::unique_ptr<BoundaryModel> make_mdbc_boundary(const InitialState& init, const WcsphParams& prm) {
  return std::make_unique<MdbcBoundary>(init, static_cast<double>(prm.kernel.support()));
}

} // namespace surge::sph
