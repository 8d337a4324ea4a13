#include "surge/sim/distributed_run.hpp"

#include "surge/domain/comm.hpp"

#include <chrono>
#include <limits>
#include <sstream>

namespace surge::sim {

namespace {
// A face moves when the busiest process computed 5 % longer than the mean over the last
// 25 steps (a dam-break front crosses a slab in thousands of steps).
constexpr double rebalance_threshold = 1.05;
constexpr long rebalance_every = 25;
} // namespace

DistributedRun::DistributedRun(const Case& c, sph::WcsphSolver& solver, coupling::SphDemCoupling* coupling)
    : solver_(solver) {
  if (!domain::comm::built_with_mpi()) return;
  const Vec3 lo{}, hi(c.domain.max - c.domain.min);
  // Slabs along the longest axis; on a periodic axis they form a ring (the first slab
  // takes halo copies of what lies near the hi face, the last of what lies near lo, and
  // each process's images move them a period).
  const int axis = domain::longest_axis(lo, hi);
  slabs_.emplace(axis, 0.0, static_cast<double>(hi[axis]), solver.dependency_reach(),
                 c.periodic[static_cast<std::size_t>(axis)]);
  slabs_->carry_optional(solver.store().optional());
  dist_ = slabs_->distribution();
  solver.set_distribution(dist_);
  if (coupling) coupling->set_distribution(dist_, c.coupling.force_sum == "per_sphere");
}

bool DistributedRun::root() { return domain::comm::rank() == 0; }
int DistributedRun::ranks() { return domain::comm::size(); }

bool DistributedRun::enabled() { return domain::comm::built_with_mpi(); }

void DistributedRun::start(particles::HostParticles all, long steps) {
  if (!active()) {
    if (steps >= 0) solver_.restore(all, steps);
    return;
  }
  if (all.vel_prev.size() != all.size()) all.vel_prev = all.vel;
  if (all.rho_prev.size() != all.size()) all.rho_prev = all.rho;
  all.halo.clear();
  slabs_->balance(all);
  const auto s = slabs_->distribute(all);
  traffic_.halo_now = static_cast<long>(s.halo);
  if (steps >= 0)
    solver_.restore(all, steps);
  else
    solver_.replace(all);
  stale_ = false;
}

void DistributedRun::sync() {
  if (!active() || !stale_) return;
  stale_ = false;
  if (ranks() == 1) return; // nothing to send or receive
  const auto t0 = std::chrono::steady_clock::now();
  domain::ExchangeStats s;
  if (solver_.step_count() % rebalance_every == 0) {
    // Busy time since the last check: wall time less the time spent in collective calls
    // (waiting for the others included). The first check, without timings, uses counts.
    const auto now = std::chrono::steady_clock::now();
    const double coll = domain::comm::collective_seconds();
    domain::SlabDecomposition::Balance b;
    b.threshold = rebalance_threshold;
    if (balance_checked_)
      b.busy_seconds = std::max(1e-9, std::chrono::duration<double>(now - last_check_).count() - (coll - last_coll_));
    s = slabs_->exchange(solver_.store(), &b);
    balance_checked_ = true;
    last_check_ = std::chrono::steady_clock::now();
    last_coll_ = domain::comm::collective_seconds();
  } else {
    s = slabs_->exchange(solver_.store());
  }
  solver_.invalidate(); // particles came and went: rates are recomputed before they are read
  ++traffic_.exchanges;
  if (s.rebalanced) ++traffic_.rebalances;
  traffic_.bytes_sent += static_cast<double>(s.bytes_sent);
  traffic_.halo_now = static_cast<long>(s.halo);
  traffic_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void DistributedRun::gather(particles::HostParticles& out, bool history) {
  if (!active()) {
    solver_.download(out, history);
    return;
  }
  particles::HostParticles local;
  solver_.download(local, true);
  out = slabs_->gather(local);
  if (!history) {
    out.vel_prev.clear();
    out.rho_prev.clear();
  }
}

void DistributedRun::combine(sph::StepStats& s, bool& stop, bool& checkpoint_due) const {
  if (!active()) return;
  double n[5] = {static_cast<double>(s.removed_domain), static_cast<double>(s.removed_density),
                 static_cast<double>(s.non_finite), stop ? 1.0 : 0.0, checkpoint_due ? 1.0 : 0.0};
  domain::comm::sum(n, 5);
  const bool where = s.removed_domain + s.removed_density > 0;
  const double inf = std::numeric_limits<double>::infinity();
  double box[6];
  for (int k = 0; k < 3; ++k) {
    box[k] = where ? static_cast<double>(s.removed_lo[k]) : inf;
    box[3 + k] = where ? -static_cast<double>(s.removed_hi[k]) : inf;
  }
  domain::comm::min(box, 6);
  s.removed_domain = static_cast<int>(n[0]);
  s.removed_density = static_cast<int>(n[1]);
  s.non_finite = static_cast<int>(n[2]);
  stop = n[3] > 0;
  checkpoint_due = n[4] > 0;
  if (s.removed_domain + s.removed_density > 0)
    for (int k = 0; k < 3; ++k) {
      s.removed_lo[k] = static_cast<Real>(box[k]);
      s.removed_hi[k] = static_cast<Real>(-box[3 + k]);
    }
}

long DistributedRun::owned_particles() {
  const double n = solver_.owned_count();
  return static_cast<long>(active() ? domain::comm::sum(n) : n);
}

double DistributedRun::total(double per_process) { return domain::comm::sum(per_process); }

void DistributedRun::measure_waits() {
  if (!active()) return;
  const double mine = domain::comm::collective_seconds();
  wait_min_ = domain::comm::min(mine);
  wait_max_ = domain::comm::max(mine);
}

std::string DistributedRun::summary_json() const {
  std::ostringstream j;
  j.precision(6);
  const double steps = traffic_.exchanges > 0 ? static_cast<double>(traffic_.exchanges) : 1.0;
  j << "{\"ranks\": " << ranks();
  if (active()) {
    j << ", \"axis\": \""
      << "xyz"[slabs_->axis()] << "\", \"halo_reach\": " << slabs_->reach()
      << ", \"rebalances\": " << traffic_.rebalances << ", \"rank0\": {\"exchanges\": " << traffic_.exchanges
      << ", \"exchange_seconds\": " << traffic_.seconds
      << ", \"bytes_sent_per_exchange\": " << traffic_.bytes_sent / steps
      << ", \"halo_particles\": " << traffic_.halo_now << "}, \"collective_seconds\": {\"min\": " << wait_min_
      << ", \"max\": " << wait_max_ << "}";
  }
  j << "}";
  return j.str();
}

} // namespace surge::sim
