#include "surge/sph/wcsph_solver.hpp"
#if defined(SURGE_SIMD)
#include "surge/sph/wcsph_rates_simd.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace surge::sph {

namespace detail {
// The loops of one SPH step, as free functions: nvcc's extended lambdas may not
// live in private member functions.

// EOS then per-particle rates (continuity, momentum, signal speed); with the no-penetration
// condition (out.faces not null) which wall plane each fluid particle would reach first, with
// shifting (out.shift) its sums. On CPUs the batched pair loop (wcsph_rates_simd.hpp) unless
// built or asked without it.
void compute_rates(const WcsphParams& prm, const WallHoldView& gh, const neighbour::GridView& g,
                   const particles::ParticleView& p, const RatesOut& out) {
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) { p.press[i] = prm.eos.pressure(p.rho[i]); });
#if defined(SURGE_SIMD)
  if (const RatesFn batched = batched_rates()) {
    // Blocks of consecutive particles (one cell's share its candidates in the AVX2 copy).
    for_each_rates_block(p.n, [=](int begin, int end) { batched(prm, g, p, gh, out, begin, end); });
    return;
  }
#endif
  par::parallel_for_uneven(
      p.n, SURGE_LAMBDA(int i) { store_rates(p, out, i, wcsph_rates(prm, g, p, i, gh)); });
}

// min over owned fluid of min(sqrt(h/|a|), h/(c0 + vsig)) (SPEC §2.5), without the CFL
// factor; the largest Real when there is none.
Real min_dt(const WcsphParams& prm, const particles::ParticleView& p) {
  const Real h = prm.kernel.h, c0 = prm.eos.c0;
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const Real inf = std::numeric_limits<Real>::max();
  return par::parallel_reduce(
      p.n, inf,
      SURGE_LAMBDA(int i) {
        if (p.kind[i] != fluid || !p.owned(i)) return inf;
        const Real a = norm(p.acc[i]);
        const Real dtf = a > 0 ? std::sqrt(h / a) : inf;
        const Real dtcv = h / (c0 + p.vsig[i]);
        return dtf < dtcv ? dtf : dtcv;
      },
      par::Min{});
}

// Flags owned fluid particles outside [lo, hi], with density outside [rmin, rmax] or
// non-finite as Removed (a halo copy is its owner's to judge). Returns counts packed as non-finite << 42 | density <<
// 21 | domain.
long long flag_removals(const particles::ParticleView& p, Vec3 lo, Vec3 hi, Real rmin, Real rmax) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid), removed = static_cast<std::uint8_t>(Kind::Removed);
  return par::parallel_reduce(
      p.n, 0LL,
      SURGE_LAMBDA(int i)->long long {
        if (p.kind[i] != fluid || !p.owned(i)) return 0;
        const Vec3 x = p.pos[i];
        const Real rho = p.rho[i];
        const bool finite = std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && std::isfinite(rho) &&
                            std::isfinite(p.vel[i].x) && std::isfinite(p.vel[i].y) && std::isfinite(p.vel[i].z);
        long long code = 0;
        if (!finite)
          code = 1LL << 42;
        else if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z)
          code = 1;
        else if (rho < rmin || rho > rmax)
          code = 1LL << 21;
        if (code) p.kind[i] = removed;
        return code;
      },
      par::Sum{});
}

// What the updates read beyond the rates: the wall choices (no penetration) and the
// shifting sums (each null when off), and the parameters that go with them.
struct UpdateExtras {
  WallHoldView gh;
  const WallChoice* faces = nullptr;
  Real dmin = 0; // keep_off_distance
  const ShiftSums* shift = nullptr;
  ShiftParams shifting;
  Real h = 0;
};

// Where fluid particle i goes: x, moved by dt at velocity u by the integrator, shifted
// (shifting.hpp) and then kept dmin in front of the wall face it would reach first
// (no_penetration.hpp; the plane rebuilt where the rates saw it, from x_rates, and moved
// to where it will be at the step's end). v (and v_prev) lose their motion into that plane.
SURGE_HD inline void finish_move(const UpdateExtras& e, const particles::ParticleView& p, int i, const Vec3& x_rates,
                                 const Vec3& u, Real dt, Vec3& x, Vec3& v, Vec3* v_prev = nullptr) {
  if (e.shift) x += shift_displacement(e.shifting, e.shift[i], u, e.h, dt);
  if (e.faces) keep_off_face(held_plane(e.gh, p, e.faces[i], x_rates, e.dmin).after(dt), e.dmin, x, v, v_prev);
}

// Verlet (Monaghan 1989): v+ = v- + 2 dt a, r+ = r + dt v + dt^2/2 a, rho+ = rho- + 2 dt drho;
// an Euler step when `euler`. Boundary densities are clamped at rho0. Fluid is then shifted
// and held off the walls (finish_move).
void verlet_update(const particles::ParticleView& p, Real dt, Real rho0, bool euler, const UpdateExtras& e) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        const Real rho_old = p.rho_prev[i];
        const Real rho_now = p.rho[i];
        Real rho_new = euler ? rho_now + dt * p.drho[i] : rho_old + 2 * dt * p.drho[i];
        if (p.kind[i] == fluid) {
          const Vec3 v_now = p.vel[i];
          const Vec3 a = p.acc[i];
          const Vec3 x_now = p.pos[i];
          Vec3 x = x_now + (v_now * dt + a * (dt * dt / 2)); // the association of the plain update
          Vec3 v = euler ? v_now + a * dt : p.vel_prev[i] + a * (2 * dt);
          Vec3 v_prev = v_now;
          finish_move(e, p, i, x_now, v_now, dt, x, v, &v_prev);
          p.pos[i] = x;
          p.vel[i] = v;
          p.vel_prev[i] = v_prev;
        } else {
          rho_new = boundary_density(rho_new, rho0);
        }
        p.rho_prev[i] = rho_now;
        p.rho[i] = rho_new;
      });
}

// Symplectic position-Verlet, first half: state n saved in *_prev, advanced by dt/2.
void symplectic_predict(const particles::ParticleView& p, Real dt, Real rho0, const UpdateExtras& e) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const Real half = dt / 2;
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        p.rho_prev[i] = p.rho[i];
        Real rho = p.rho[i] + half * p.drho[i];
        if (p.kind[i] == fluid) {
          // A state the last corrector left past the plane is put back first: the corrector
          // starts from it again.
          Vec3 x0 = p.pos[i], v0 = p.vel[i];
          const WallPlane face = e.faces ? held_plane(e.gh, p, e.faces[i], x0, e.dmin) : WallPlane{};
          if (e.faces) keep_off_face(face, e.dmin, x0, v0);
          p.pos_prev[i] = x0;
          p.vel_prev[i] = v0;
          Vec3 x = x0 + v0 * half;
          Vec3 v = v0 + p.acc[i] * half;
          if (e.faces) keep_off_face(face.after(half), e.dmin, x, v);
          p.pos[i] = x;
          p.vel[i] = v;
        } else {
          rho = boundary_density(rho, rho0);
        }
        p.rho[i] = rho;
      });
}

// Second half, with the rates at n + 1/2: v+ = v + dt a, r+ = r + dt (v + v+)/2; then
// shifted (with the sums and the velocity at n + 1/2) and held off the walls.
void symplectic_correct(const particles::ParticleView& p, Real dt, Real rho0, const UpdateExtras& e) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  const Real half = dt / 2;
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        Real rho = p.rho_prev[i] + dt * p.drho[i];
        if (p.kind[i] == fluid) {
          const Vec3 v0 = p.vel_prev[i];
          Vec3 v1 = v0 + p.acc[i] * dt;
          Vec3 x = p.pos_prev[i] + (v0 + v1) * half;
          // The rates were at pos (walls where they stood at the step's start).
          finish_move(e, p, i, p.pos[i], p.vel[i], dt, x, v1);
          p.vel[i] = v1;
          p.pos[i] = x;
        } else {
          rho = boundary_density(rho, rho0);
        }
        p.rho[i] = rho;
      });
}
// Absorbing zones: each owned fluid particle's velocity times its zones' factor.
void damp(const particles::ParticleView& p, DampingZones zones, Real dt) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.kind[i] != fluid || !p.owned(i)) return;
        const Real f = zones.factor(p.pos[i], dt);
        if (f != 1) p.vel[i] = p.vel[i] * f;
      });
}

// Each particle's free-surface flag (1: fluid at the surface).
void mark_surface(const WcsphParams& prm, const neighbour::GridView& g, const particles::ParticleView& p) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  par::parallel_for_uneven(
      p.n, SURGE_LAMBDA(int i) {
        p.surface[i] = p.kind[i] == fluid && at_free_surface(prm, g, p, i) ? std::uint8_t{1} : std::uint8_t{0};
      });
}

// laminar_sps: each fluid particle's stress tau/rho from the strain rate its last rates
// pass summed (sps_turbulence.hpp); 0 for the others. Images take theirs from their
// particles at the next refresh.
void set_sps_stress(const SpsParams& sps, const particles::ParticleView& p, const SymTensor* strain) {
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) { p.sps[i] = p.kind[i] == fluid ? sps_stress(sps, strain[i]) : SymTensor{}; });
}

// An axis-aligned box and its merge, for the reduction below (nvcc's extended lambdas
// may not use types local to a function).
struct Box2 {
  Vec3 lo, hi;
};
struct MergeBoxes {
  SURGE_HD Box2 operator()(const Box2& a, const Box2& b) const {
    Box2 r;
    for (int k = 0; k < 3; ++k) {
      r.lo[k] = a.lo[k] < b.lo[k] ? a.lo[k] : b.lo[k];
      r.hi[k] = a.hi[k] > b.hi[k] ? a.hi[k] : b.hi[k];
    }
    return r;
  }
};

// Bounding box of the particles flagged Removed this step whose positions are finite.
std::pair<Vec3, Vec3> removed_bounds(const particles::ParticleView& p) {
  const auto removed = static_cast<std::uint8_t>(Kind::Removed);
  const Real big = std::numeric_limits<Real>::max();
  const Box2 empty{{big, big, big}, {-big, -big, -big}};
  const Box2 b = par::parallel_reduce(
      p.n, empty,
      SURGE_LAMBDA(int i) {
        const Vec3 x = p.pos[i];
        if (p.kind[i] != removed || !std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return empty;
        return Box2{x, x};
      },
      MergeBoxes{});
  return {b.lo, b.hi};
}
} // namespace detail

namespace {
// The configuration with the particle mass of an exactly filled box (InitialState::particle_mass).
SolverConfig with_mass(SolverConfig cfg, const InitialState& init) {
  if (init.particle_mass > 0) cfg.prm.mass = static_cast<Real>(init.particle_mass);
  return cfg;
}
} // namespace

WcsphSolver::WcsphSolver(const SolverConfig& cfg, const InitialState& init, const particles::HostParticles* held)
    : WcsphSolver(cfg, init, Unloaded{}) {
  store_.upload(held ? *held : init.particles);
}

WcsphSolver::WcsphSolver(const SolverConfig& cfg, InitialState&& init) : WcsphSolver(cfg, init, Unloaded{}) {
  store_.upload(std::move(init.particles));
}

WcsphSolver::WcsphSolver(const SolverConfig& cfg, const InitialState& init, Unloaded /*unused*/)
    : cfg_(with_mass(cfg, init)), boundary_(cfg_.boundary->make(init, cfg_.prm)),
      first_boundary_id_(init.first_boundary_id), dom_lo_(init.fluid_lo), dom_hi_(init.fluid_hi) {
  store_.set_optional(cfg_.prm.viscosity == Viscosity::LaminarSps); // the SPS stress
  if (cfg.no_penetration) hold_ = WallHold(init, boundary_->ghost_offsets());
  if (!init.moving.empty()) moving_ = MovingWalls(init, boundary_->ghost_offsets() != nullptr);
  set_up_images(init);
  // The grid covers that region and every particle.
  Vec3 lo = dom_lo_, hi = dom_hi_;
  for (const auto& p : init.particles.pos)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::fmin(lo[k], p[k]);
      hi[k] = std::fmax(hi[k], p[k]);
    }
  grid_.set_spec(neighbour::make_grid(lo, hi, cfg_.prm.kernel.support(), 2)); // cells of h: 125 h^3 scanned, not 216
}

void WcsphSolver::set_up_images(const InitialState& init) {
  // Images refreshed before every rates pass need the reach of one evaluation across a
  // face: a support for the water, and for a wall model with ghost nodes (mdbc) the ghosts'
  // longest offset along that axis plus a support around them (a floor's ghosts lie above
  // it: they add nothing across a vertical face); half an h more for what moves within a
  // step after the rebuild.
  const double support = cfg_.prm.kernel.support(), margin = 0.5 * static_cast<double>(cfg_.prm.kernel.h);
  domain::ImageFrame f;
  for (std::size_t a = 0; a < 3; ++a) {
    f.periodic[a] = init.periodic[a];
    f.mirror_lo[a] = init.symmetry[2 * a];
    f.mirror_hi[a] = init.symmetry[2 * a + 1];
  }
  if (!f.any()) return;
  std::uint32_t max_id = 0;
  for (const std::uint32_t id : init.particles.id) max_id = std::max(max_id, id + 1);
  for (int k = 0; k < 3; ++k) {
    f.hi[k] = init.domain_hi[k];
    f.len[k] = f.hi[k] - f.lo[k];
    if (!f.has_images(k)) continue;
    double ghost = 0;
    for (const Vec3& g : init.boundary_ghost) ghost = std::max(ghost, std::fabs(static_cast<double>(g[k])));
    const double reach = init.boundary_ghost.empty() ? support : ghost + support;
    f.band[k] = static_cast<Real>(reach + margin);
    if (f.periodic[k] && 3 * f.len[k] < f.band[k])
      throw std::invalid_argument("a periodic length shorter than a third of the image band");
    // Fluid beyond a periodic or symmetry face is brought back at the next rebuild, not removed.
    if (f.periodic[k] || f.mirror_lo[k]) dom_lo_[k] = std::fmin(dom_lo_[k], f.lo[k] - f.band[k]);
    if (f.periodic[k] || f.mirror_hi[k]) dom_hi_[k] = std::fmax(dom_hi_[k], f.hi[k] + f.band[k]);
  }
  images_ = domain::Images(f, max_id);
  store_.set_images(true);
}

void WcsphSolver::download(particles::HostParticles& h, bool history) const {
  store_.download(h, history);
  if (!sps_primed_) h.sps.clear(); // no stress carried yet: whoever restores from h sets it
  if (!images_.on()) return;
  particles::keep_if(h, [&](std::size_t i) { return h.halo[i] < domain::image_flag; });
  if (!store_.distributed()) h.halo.clear();
}

void WcsphSolver::set_distribution(const Distribution& d) {
  dist_ = d;
  store_.set_distributed(d.distributed());
}

double WcsphSolver::dependency_reach() const {
  // laminar_sps: a run's first rates pass sets the stress from the strain rate before the
  // pass is done again, so that stress reads its neighbours' neighbours: one support more.
  const double sps = cfg_.prm.viscosity == Viscosity::LaminarSps ? static_cast<double>(cfg_.prm.kernel.support()) : 0;
  const double per_evaluation = static_cast<double>(cfg_.prm.kernel.support()) + boundary_->extra_reach() + sps;
  return (cfg_.integrator == Integrator::Symplectic ? 2 : 1) * per_evaluation;
}

void WcsphSolver::replace(const particles::HostParticles& h) {
  store_.upload(h);
  fresh_ = false;
}

int WcsphSolver::owned_count() {
  const auto p = store_.view();
  return par::parallel_reduce(
      p.n, 0,
      SURGE_LAMBDA(int i) { return p.kind[i] != static_cast<std::uint8_t>(Kind::Removed) && p.owned(i) ? 1 : 0; },
      par::Sum{});
}

void WcsphSolver::sort_and_rates() {
  {
    const auto t = par::timed(par::Phase::Sort);
    if (images_.on()) images_.rebuild(store_);
    store_.sort(grid_);
    if (images_.on()) images_.link(store_);
  }
  rates();
  fresh_ = true;
}

void WcsphSolver::rates() {
  const auto p = store_.view();
  const auto g = grid_.view(p.pos, p.kind);
  images_.refresh(p); // the images hold their particles' state (after a predictor step too)
  if (boundary_->prepares()) {
    const auto t = par::timed(par::Phase::Boundary);
    boundary_->prepare(cfg_.prm, g, p);
    images_.refresh(p); // ... and their wall densities (those of the images' own ghosts are not whole)
  }
  RatesOut out;
  out.faces = hold_.choices(p.n);
  if (cfg_.prm.shift.on()) {
    shift_.resize(static_cast<std::size_t>(p.n));
    out.shift = shift_.data();
  }
  if (p.sps) {
    strain_.resize(static_cast<std::size_t>(p.n));
    out.strain = strain_.data();
  }
  const auto t = par::timed(par::Phase::Rates);
  detail::compute_rates(cfg_.prm, hold_.view(), g, p, out);
  if (p.sps && !sps_primed_) {
    // The particles do not carry a stress yet (a new run): the one of this state, then the
    // rates again with it.
    set_sps_stress();
    images_.refresh(p);
    detail::compute_rates(cfg_.prm, hold_.view(), g, p, out);
  }
}

void WcsphSolver::set_sps_stress() {
  const auto p = store_.view();
  if (!p.sps) return;
  detail::set_sps_stress(cfg_.sps, p, strain_.data());
  sps_primed_ = true;
}

void WcsphSolver::move_walls(const std::vector<RigidState>& states) {
  if (!moving_.any()) return;
  moving_.place(store_.view(), states, boundary_->ghost_offsets(), first_boundary_id_);
  hold_.turn(states);
  fresh_ = false;
}

void WcsphSolver::restore(const particles::HostParticles& h, long steps) {
  store_.upload(h);
  sps_primed_ = h.sps.size() == h.size(); // a checkpoint written before laminar_sps carried it: 0
  steps_ = steps;
  fresh_ = false;
}

void WcsphSolver::refresh() {
  if (!fresh_) sort_and_rates();
}

void WcsphSolver::mark_surface() {
  refresh();
  const auto p = store_.view();
  detail::mark_surface(cfg_.prm, grid_.view(p.pos, p.kind), p);
}

double WcsphSolver::dt_from_rates() {
  const auto t = par::timed(par::Phase::TimeStep);
  const double inf = std::numeric_limits<Real>::max();
  const double dt = dist_.minimum(static_cast<double>(detail::min_dt(cfg_.prm, store_.view())));
  // No fluid anywhere: the sound speed's step.
  return cfg_.cfl * (dt == inf ? static_cast<double>(cfg_.prm.kernel.h / cfg_.prm.eos.c0) : dt);
}

double WcsphSolver::stable_dt() {
  refresh();
  return dt_from_rates();
}

int WcsphSolver::flag_removals(StepStats& s) {
  const auto t = par::timed(par::Phase::Removal);
  const long long packed = detail::flag_removals(store_.view(), dom_lo_, dom_hi_, cfg_.rho_min, cfg_.rho_max);
  s.removed_domain = static_cast<int>(packed & ((1LL << 21) - 1));
  s.removed_density = static_cast<int>((packed >> 21) & ((1LL << 21) - 1));
  s.non_finite = static_cast<int>(packed >> 42);
  const int flagged = s.removed_domain + s.removed_density + s.non_finite;
  store_.add_removed(flagged);
  return flagged;
}

StepStats WcsphSolver::step(double dt_max) {
  refresh();
  StepStats s;
  const double dt_d = std::fmin(dt_from_rates(), dt_max);
  s.dt = dt_d;
  const Real dt = static_cast<Real>(dt_d);
  const Real rho0 = cfg_.prm.eos.rho0;
  const bool symplectic = cfg_.integrator == Integrator::Symplectic;
  if (symplectic) store_.reserve_position_scratch();
  const auto p = store_.view();
  detail::UpdateExtras e;
  e.gh = hold_.view();
  e.faces = hold_.choices();
  e.dmin = keep_off_distance(cfg_.prm.dp);
  e.shift = cfg_.prm.shift.on() ? shift_.data() : nullptr;
  e.shifting = cfg_.prm.shift;
  e.h = cfg_.prm.kernel.h;
  if (!symplectic) {
    const auto t = par::timed(par::Phase::Integrate);
    detail::verlet_update(p, dt, rho0, steps_ % cfg_.euler_every == 0, e);
  } else {
    {
      const auto t = par::timed(par::Phase::Integrate);
      detail::symplectic_predict(p, dt, rho0, e);
    }
    rates();
    const auto t = par::timed(par::Phase::Integrate);
    detail::symplectic_correct(p, dt, rho0, e);
  }
  if (cfg_.damping.n > 0) {
    const auto t = par::timed(par::Phase::Integrate);
    detail::damp(p, cfg_.damping, dt);
  }
  set_sps_stress(); // the new state's stress: from the strain rate of this step's (last) rates
  ++steps_;
  fresh_ = false;
  if (flag_removals(s) > 0) {
    const auto [lo, hi] = detail::removed_bounds(store_.view());
    s.removed_lo = lo;
    s.removed_hi = hi;
  }
  return s;
}

} // namespace surge::sph
