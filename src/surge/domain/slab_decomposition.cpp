#include "surge/domain/slab_decomposition.hpp"

#include "surge/algo/algo.hpp"
#include "surge/domain/comm.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <type_traits>

namespace surge::domain {
namespace {

// One particle as it travels between processes: every state field (particles/
// particle_fields.hpp: what a step needs; rates are recomputed after every exchange), its
// bytes in the list's order, 62 bytes; the optional ones (the SPS stress) only where the
// run holds them (`optional`, alike on every process), 0 where a particle has none.
std::size_t record_size(bool optional) {
  std::size_t size = 0;
  particles::HostParticles h;
  particles::for_each_state_field(h, h, [&](const char*, auto& v, auto&, unsigned use, const auto*) {
    if (optional || !(use & particles::kOptional)) size += sizeof(typename std::decay_t<decltype(v)>::value_type);
  });
  return size;
}

void append(std::vector<char>& out, const particles::HostParticles& h, std::size_t i, bool optional) {
  particles::for_each_state_field(h, h, [&](const char*, const auto& v, const auto&, unsigned use, const auto*) {
    if (!optional && (use & particles::kOptional)) return;
    typename std::decay_t<decltype(v)>::value_type x{};
    if (!(use & particles::kOptional) || i < v.size()) x = v[i]; // an optional one not held: 0
    const auto at = out.size();
    out.resize(at + sizeof x);
    std::memcpy(out.data() + at, &x, sizeof x);
  });
}

// dst gets src's particle i (an optional field only where src holds it).
void push(particles::HostParticles& dst, const particles::HostParticles& src, std::size_t i, std::uint8_t halo) {
  particles::for_each_state_field(dst, src, [&](const char*, auto& d, const auto& s, unsigned use, const auto*) {
    if (!(use & particles::kOptional) || i < s.size()) d.push_back(s[i]);
  });
  dst.halo.push_back(halo);
}

void unpack(const std::vector<char>& in, particles::HostParticles& h, std::uint8_t halo, bool optional) {
  const std::size_t size = record_size(optional);
  for (std::size_t at = 0; at + size <= in.size();) {
    particles::for_each_state_field(h, h, [&](const char*, auto& v, auto&, unsigned use, const auto*) {
      if (!optional && (use & particles::kOptional)) return;
      typename std::decay_t<decltype(v)>::value_type x{};
      std::memcpy(&x, in.data() + at, sizeof x);
      at += sizeof x;
      v.push_back(x);
    });
    h.halo.push_back(halo);
  }
}

// The work a particle brings to its process: fluid sums over all its neighbours, wall and
// body particles over fluid ones only (about half).
double weight(std::uint8_t kind) {
  if (kind == static_cast<std::uint8_t>(Kind::Fluid)) return 1.0;
  return kind == static_cast<std::uint8_t>(Kind::Removed) ? 0.0 : 0.5;
}

bool removed(const particles::HostParticles& h, std::size_t i) {
  return h.kind[i] == static_cast<std::uint8_t>(Kind::Removed);
}
bool is_halo(const particles::HostParticles& h, std::size_t i) { return !h.halo.empty() && h.halo[i] != 0; }

void require_history(const particles::HostParticles& h) {
  if (h.vel_prev.size() != h.size() || h.rho_prev.size() != h.size())
    throw std::logic_error("slab exchange: particles without their integration history");
}

} // namespace

int longest_axis(const Vec3& lo, const Vec3& hi) {
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[a] - lo[a]) a = k;
  return a;
}

SlabDecomposition::SlabDecomposition(int axis, double lo, double hi, double reach, bool ring)
    : axis_(axis), ring_(ring), lo_(lo), hi_(std::max(hi, lo)), reach_(reach) {
  // Faces fall on bin edges; bins of an eighth of the reach keep the load even to a few
  // per cent without a histogram larger than 64 Ki bins.
  bin_ = std::max((hi_ - lo_) / 65536.0, reach_ / 8.0);
  if (!(bin_ > 0)) bin_ = 1;
  const int p = comm::size();
  cuts_.assign(static_cast<std::size_t>(p) + 1, 0.0);
  for (int r = 0; r <= p; ++r) cuts_[r] = lo_ + (hi_ - lo_) * r / p;
  cuts_.front() = -std::numeric_limits<double>::infinity();
  cuts_.back() = std::numeric_limits<double>::infinity();
  cuts_changed();
}

void SlabDecomposition::cuts_changed() {
  keep_ring_ends();
  par::upload(cuts_dev_, cuts_);
}

// In a ring only the first and last slabs take copies across the periodic faces (SlabView::
// needs): a middle slab whose reach crossed a face would miss the neighbours there (3
// processes along 0.1 m with fickian shifting's reach of 0.048 m gave results that changed
// from run to run). So the end slabs are kept at least a reach wide, in whole bins; the
// middle ones may be thin or empty, as on an open axis, where the halo walks past them.
void SlabDecomposition::keep_ring_ends() {
  const int p = comm::size();
  if (!ring_ || p < 3) return;
  const double span = std::ceil(reach_ / bin_) * bin_;
  const double first = std::min(lo_ + span, hi_), last = std::max(hi_ - span, first);
  for (int r = 1; r < p; ++r) cuts_[r] = std::clamp(cuts_[r], first, last);
}

SlabView SlabDecomposition::host_view() const {
  return {cuts_.data(), comm::size(), comm::rank(), reach_, ring_ ? 1 : 0, lo_, hi_};
}

int SlabDecomposition::owner(Real x) const { return host_view().owner(x); }

bool SlabDecomposition::owns(const Vec3& p) const { return owner(p[axis_]) == comm::rank(); }

Distribution SlabDecomposition::distribution() const {
  Distribution d;
  d.owns_point = [this](const Vec3& x) { return owns(x); };
  d.sum_exact = [](Real* x, std::size_t n) { comm::sum(x, n); };
  d.sum_ordered = [](Real* x, std::size_t n) { comm::sum_in_rank_order(x, n); };
  d.min = [](double x) { return comm::min(x); };
  return d;
}

template <class X, class W>
std::vector<double> SlabDecomposition::histogram(std::size_t n, X x, W weight) const {
  const auto nb = static_cast<std::size_t>(std::clamp(std::ceil((hi_ - lo_) / bin_), 1.0, 65536.0));
  std::vector<double> hist(nb, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x(i);
    if (!std::isfinite(xi)) continue;
    const auto b =
        static_cast<std::size_t>(std::clamp(std::floor((xi - lo_) / bin_), 0.0, static_cast<double>(nb - 1)));
    hist[b] += weight(i);
  }
  return hist;
}

void SlabDecomposition::cuts_from(const std::vector<double>& hist) {
  const int p = comm::size();
  const double total = std::accumulate(hist.begin(), hist.end(), 0.0);
  double cum = 0;
  std::size_t b = 0;
  for (int r = 1; r < p; ++r) {
    const double target = total * r / p;
    while (b < hist.size() && cum + hist[b] <= target) cum += hist[b++];
    // Face at the edge of the bin where the cumulative work passes the target (whichever
    // side of that bin is nearer).
    const bool take = b < hist.size() && target - cum > cum + hist[b] - target;
    if (take) cum += hist[b++];
    cuts_[r] = lo_ + static_cast<double>(b) * bin_;
  }
  cuts_changed();
}

void SlabDecomposition::balance(const particles::HostParticles& all) {
  cuts_from(histogram(
      all.size(), [&](std::size_t i) { return static_cast<double>(all.pos[i][axis_]); },
      [&](std::size_t i) { return weight(all.kind[i]); }));
}

bool SlabDecomposition::rebalance(const std::vector<Real>& x, const std::vector<std::uint8_t>& state,
                                  const Balance& b) {
  // state: 0 owned fluid, 1 halo copy, 2 removed, 3 owned wall or body (ParticleStore::coordinates).
  const auto counted = [&](std::size_t i) { return state[i] == 0 ? 1.0 : (state[i] == 3 ? 0.5 : 0.0); };
  double mine = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mine += counted(i);
  // Work: measured seconds when given (every process must give them), else the counts.
  const double work = b.busy_seconds > 0 ? b.busy_seconds : mine;
  const double busiest = comm::max(work), mean = comm::sum(work) / comm::size();
  if (!(busiest > b.threshold * mean)) return false;
  const double per_count = mine > 0 ? work / mine : 0.0;
  auto hist = histogram(
      x.size(), [&](std::size_t i) { return static_cast<double>(x[i]); },
      [&](std::size_t i) { return counted(i) * per_count; });
  comm::sum(hist.data(), hist.size());
  cuts_from(hist);
  return true;
}

ExchangeStats SlabDecomposition::distribute(particles::HostParticles& all) const {
  require_history(all);
  const SlabView sv = host_view();
  particles::HostParticles mine, halo;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (removed(all, i)) continue;
    const Real x = all.pos[i][axis_];
    if (sv.owner(x) == sv.me)
      push(mine, all, i, 0);
    else if (sv.needs(x, sv.me))
      push(halo, all, i, 1);
  }
  ExchangeStats s;
  s.halo = halo.size();
  for (std::size_t i = 0; i < halo.size(); ++i) push(mine, halo, i, 1);
  all = std::move(mine);
  return s;
}

void SlabDecomposition::halo_records(const particles::HostParticles& h, std::vector<std::vector<char>>& out) const {
  const SlabView sv = host_view();
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Real x = h.pos[i][axis_];
    // Slabs are ordered: walk away from this one while x is within reach; in a ring, the
    // first and last slabs too, unless the walk reached them.
    int first = sv.me, last = sv.me;
    for (int r = sv.me - 1; r >= 0 && sv.in_reach_of(x, r); --r) append(out[first = r], h, i, optional_);
    for (int r = sv.me + 1; r < sv.ranks && sv.in_reach_of(x, r); ++r) append(out[last = r], h, i, optional_);
    if (first > 0 && sv.needs(x, 0)) append(out[0], h, i, optional_);
    if (last < sv.ranks - 1 && sv.needs(x, sv.ranks - 1)) append(out[sv.ranks - 1], h, i, optional_);
  }
}

namespace detail {
// What each particle does in an exchange: 0 nothing (owned, away from faces, or marked
// Removed), 1 halo copy to drop, 2 leaves for another slab, 3 owned and near a face (copied).
// flag[i] = (code != 0), for the compaction's scan. Free functions: nvcc's extended lambdas.
void classify(const particles::ParticleView& p, int axis, SlabView s, std::uint8_t* code, std::uint32_t* flag) {
  const auto removed = static_cast<std::uint8_t>(Kind::Removed);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        std::uint8_t c = 0;
        if (p.kind[i] != removed) {
          const Real x = p.pos[i][axis];
          if (!p.owned(i))
            c = 1;
          else if (s.owner(x) != s.me)
            c = 2;
          else if (s.near_other(x))
            c = 3;
        }
        code[i] = c;
        flag[i] = c != 0 ? 1U : 0U;
      });
}
// The selected particles, in index order: at[i] is i's place among them (an exclusive scan).
void compact(int n, const std::uint8_t* code, const std::uint32_t* at, std::uint32_t* index, std::uint8_t* what) {
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        if (code[i] == 0) return;
        index[at[i]] = static_cast<std::uint32_t>(i);
        what[at[i]] = code[i];
      });
}
} // namespace detail

void SlabDecomposition::select(particles::ParticleStore& store, std::vector<std::uint32_t>& drop,
                               std::vector<std::uint32_t>& leave, std::vector<std::uint32_t>& near) {
  const int n = store.size();
  SlabView sv = host_view();
  sv.cuts = cuts_dev_.data();
  const auto scratch = store.exchange_scratch();
  detail::classify(store.view(), axis_, sv, scratch.byte, scratch.word);
  const std::uint32_t m = algo::exclusive_scan(scratch.word, scratch.word, n);
  sel_index_.resize(m);
  sel_code_.resize(m);
  detail::compact(n, scratch.byte, scratch.word, sel_index_.data(), sel_code_.data());
  std::vector<std::uint32_t> index;
  std::vector<std::uint8_t> code;
  par::download(index, sel_index_, m);
  par::download(code, sel_code_, m);
  for (std::uint32_t k = 0; k < m; ++k) {
    if (code[k] == 1 || code[k] == 2) drop.push_back(index[k]);
    if (code[k] == 2) leave.push_back(index[k]);
    if (code[k] == 3) near.push_back(index[k]);
  }
}

ExchangeStats SlabDecomposition::exchange(particles::ParticleStore& store, const Balance* balance) {
  const int p = comm::size();
  ExchangeStats s;
  if (balance) {
    // Rebalancing needs every particle's coordinate (a histogram); only then are they all
    // copied to the host.
    std::vector<Real> x;
    std::vector<std::uint8_t> state;
    store.coordinates(axis_, x, state);
    s.rebalanced = rebalance(x, state, *balance);
  }
  // On the device: which particles leave, are halo copies to drop, or are near a face;
  // only those indices come to the host (a few per cent of the particles).
  std::vector<std::uint32_t> drop, leave, near;
  select(store, drop, leave, near);
  particles::HostParticles leaving, staying;
  store.extract(leave, leaving);
  store.extract(near, staying);
  std::vector<std::vector<char>> out(static_cast<std::size_t>(p));
  for (std::size_t i = 0; i < leaving.size(); ++i) append(out[owner(leaving.pos[i][axis_])], leaving, i, optional_);
  for (const auto& o : out) s.bytes_sent += o.size();
  particles::HostParticles arrived, halo;
  for (const auto& in : comm::all_to_all(out)) unpack(in, arrived, 0, optional_);
  // Halo copies of what stays and of what just arrived (it may be near another face).
  for (auto& o : out) o.clear();
  halo_records(staying, out);
  halo_records(arrived, out);
  for (const auto& o : out) s.bytes_sent += o.size();
  for (const auto& in : comm::all_to_all(out)) unpack(in, halo, 1, optional_);
  s.halo = halo.size();
  for (std::size_t i = 0; i < halo.size(); ++i) push(arrived, halo, i, 1);
  store.remove(drop);
  store.append(arrived);
  return s;
}

particles::HostParticles SlabDecomposition::gather(const particles::HostParticles& local) const {
  std::vector<char> mine;
  for (std::size_t i = 0; i < local.size(); ++i)
    if (!is_halo(local, i) && !removed(local, i)) append(mine, local, i, optional_);
  const std::vector<char> all = comm::gather(mine);
  particles::HostParticles unordered, h;
  unpack(all, unordered, 0, optional_);
  std::vector<std::size_t> order(unordered.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return unordered.id[a] < unordered.id[b]; });
  for (std::size_t i : order) push(h, unordered, i, 0);
  h.halo.clear();
  return h;
}

} // namespace surge::domain
