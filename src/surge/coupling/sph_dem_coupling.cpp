#include "surge/coupling/sph_dem_coupling.hpp"

#include "surge/domain/images.hpp"

#include <cmath>
#include <stdexcept>

namespace surge::coupling {
namespace detail {
// Free functions: nvcc's extended lambdas may not live in private member functions.

// acc[id - first], pos[id - first] of every body particle this process owns (ids are
// unique, so each particle writes its own entry; the rest stay as they were, zero).
void collect_bodies(const particles::ParticleView& p, std::uint32_t first, Vec3* acc, Vec3* pos) {
  const auto body = static_cast<std::uint8_t>(Kind::Body);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] != body || !p.owned(i)) return;
        acc[p.id[i] - first] = p.acc[i];
        pos[p.id[i] - first] = p.pos[i];
      });
}

// (Periodic axes: a body particle lies in the domain, its sphere's centre up to half a
// period beyond a face; the arm goes to the nearest image.)
void sum_per_sphere(const Vec3* acc, const Vec3* pos, Real mass, const std::uint32_t* start,
                    const dem::RigidState* state, int n_spheres, domain::PeriodicAxes per, Vec3* force, Vec3* moment) {
  par::parallel_for(
      n_spheres, SURGE_LAMBDA(int k) {
        Vec3 f{}, m{};
        const Vec3 xk = state[k].pos;
        for (std::uint32_t b = start[k]; b < start[k + 1]; ++b) {
          const Vec3 fb = acc[b] * mass; // body accelerations carry no gravity (wcsph_rates)
          f += fb;
          m += cross(per.rel(pos[b], xk), fb);
        }
        force[k] = f;
        moment[k] = m;
      });
}

// Body particles from their spheres' states; with mDBC (ghost_out not null) their ghost
// offsets turn with them (ghost_out[id - first_boundary]). On periodic axes each lies in
// the domain (its sphere may straddle a face); periodic and mirrored images are left to
// the SPH's refresh, which moves them with their particles.
void place(const particles::ParticleView& p, std::uint32_t first, const Vec3* offset, const std::uint32_t* owner,
           const dem::RigidState* state, const Vec3* ghost0, Vec3* ghost_out, std::uint32_t first_boundary,
           domain::PeriodicAxes per) {
  const auto body = static_cast<std::uint8_t>(Kind::Body);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] != body || (p.halo && p.halo[i] >= domain::image_flag)) return;
        const std::uint32_t b = p.id[i] - first;
        const dem::RigidState& s = state[owner[b]];
        const dem::RigidPoint r = dem::rigid_point(s, offset[b]);
        Vec3 x = r.pos;
        per.wrap(x);
        p.pos[i] = x;
        p.vel[i] = r.vel;
        if (ghost_out) ghost_out[p.id[i] - first_boundary] = dem::rotate(s.q, ghost0[b]);
      });
}
} // namespace detail

SphDemCoupling::SphDemCoupling(const BodyLayout& layout, int n_spheres, Real dt_dem)
    : first_id_(layout.first_id), n_body_(layout.size()), n_spheres_(n_spheres), dt_dem_(dt_dem) {
  if (layout.start.size() != static_cast<std::size_t>(n_spheres) + 1)
    throw std::invalid_argument("body layout does not match the number of spheres");
  if (!(dt_dem > 0)) throw std::invalid_argument("the DEM time step must be positive");
  par::upload(offset_, layout.offset);
  par::upload(ghost_, layout.ghost);
  par::upload(owner_, layout.owner);
  par::upload(start_, layout.start);
  body_acc_.resize(n_body_);
  body_pos_.resize(n_body_);
}

namespace {
// b's vectors combined across processes by `sum` (a Distribution member), through the host.
void combine(par::Buffer<Vec3>& b, const std::function<void(Real*, std::size_t)>& sum) {
  std::vector<Vec3> h;
  par::download(h, b, b.size());
  sum(reinterpret_cast<Real*>(h.data()), 3 * h.size());
  par::upload(b, h);
}
} // namespace

void SphDemCoupling::reduce_forces(sph::WcsphSolver& sph, dem::DemSolver& dem) {
  sph.refresh(); // accelerations must describe the current body positions
  sum_forces(sph, dem);
}

void SphDemCoupling::sum_forces(sph::WcsphSolver& sph, dem::DemSolver& dem) {
  const auto t = par::timed(par::Phase::Coupling);
  // One process holds every body particle and writes every entry; a distributed one holds
  // some, and the entries of the others must read zero.
  if (dist_.distributed()) {
    par::fill(body_acc_, Vec3{});
    par::fill(body_pos_, Vec3{});
  }
  detail::collect_bodies(sph.view(), first_id_, body_acc_.data(), body_pos_.data());
  if (dist_.distributed() && !per_sphere_) {
    // Every body particle's acceleration and position from the process that owns it: each
    // sphere then sums the same values in the same order as one process would.
    for (auto* b : {&body_acc_, &body_pos_}) combine(*b, dist_.sum_exact);
  }
  dem.rigid_states(state_);
  // Written straight into the DEM's held external force and moment.
  detail::sum_per_sphere(body_acc_.data(), body_pos_.data(), sph.params().mass, start_.data(), state_.data(),
                         n_spheres_, dem.periodic(), dem.external_force().data(), dem.external_torque().data());
  if (dist_.distributed() && per_sphere_) {
    // Each process summed the body particles it owns (the others are zero); the per-sphere
    // sums are added in rank order, the same on every process.
    for (auto* b : {&dem.external_force(), &dem.external_torque()}) combine(*b, dist_.sum_ordered);
  }
}

void SphDemCoupling::place_bodies(sph::WcsphSolver& sph, dem::DemSolver& dem) {
  const auto t = par::timed(par::Phase::Coupling);
  dem.rigid_states(state_);
  detail::place(sph.view(), first_id_, offset_.data(), owner_.data(), state_.data(), ghost_.data(), sph.ghost_offsets(),
                sph.first_boundary_id(), dem.periodic());
  sph.invalidate();
}

int SphDemCoupling::after_fluid_step(sph::WcsphSolver& sph, dem::DemSolver& dem, double dt,
                                     const std::function<void(int, double)>& after_sub) {
  // The arrays still hold the rates of this step's start (the fluid has moved since,
  // the body particles have not): no refresh here.
  sum_forces(sph, dem);
  const int n_sub = std::max(1, static_cast<int>(std::ceil(dt / static_cast<double>(dt_dem_) - 1e-9)));
  const auto h = static_cast<Real>(dt / n_sub);
  for (int k = 0; k < n_sub; ++k) {
    dem.step(h);
    if (after_sub) after_sub(k, static_cast<double>(h));
  }
  place_bodies(sph, dem);
  return n_sub;
}

} // namespace surge::coupling
