// The SPH particles cut into slabs along one axis, one slab per process (SPEC §6):
// which process owns a particle, the halo copies each process needs from the others,
// migration across slab faces, and faces moved to even out the work. Host-side: the
// run loop stages particles through HostParticles (device memory on the GPU build).
#pragma once
#include "surge/core/distribution.hpp"
#include "surge/particles/particle_store.hpp"

#include <cmath>
#include <cstddef>
#include <vector>

namespace surge::domain {

// The slab faces as a kernel sees them (cuts in the execution space): who owns x, and
// whether x is within reach of another process's slab. One definition for host and device.
// On a periodic axis the slabs form a ring: the first continues beyond the domain's hi
// face, the last beyond its lo face.
struct SlabView {
  const double* cuts = nullptr; // ranks + 1 entries; cuts[0] = -inf, cuts[ranks] = +inf
  int ranks = 1, me = 0;
  double reach = 0;
  int ring = 0;                    // 1: the axis is periodic
  double lo_face = 0, hi_face = 0; // the domain's faces along the axis
  [[nodiscard]] SURGE_HD int owner(Real x) const {
    if (!std::isfinite(x)) return me; // diverged: kept where it is, for the step's checks to see
    const auto xd = static_cast<double>(x);
    int lo = 0, hi = ranks - 1; // the number of inner faces at or below x
    while (lo < hi) {
      const int mid = (lo + hi + 1) / 2;
      if (cuts[mid] <= xd)
        lo = mid;
      else
        hi = mid - 1;
    }
    return lo;
  }
  // x lies within reach of slab r: process r needs a halo copy of it.
  [[nodiscard]] SURGE_HD bool in_reach_of(Real x, int r) const {
    const auto xd = static_cast<double>(x);
    return xd >= cuts[r] - reach && xd < cuts[r + 1] + reach;
  }
  // Process r needs a copy of x: x lies within reach of slab r or, in a ring, within reach
  // of the face across which slab r continues (the first slab takes what lies near hi, the
  // last what lies near lo, where they are: each process's images move them a period).
  [[nodiscard]] SURGE_HD bool needs(Real x, int r) const {
    if (in_reach_of(x, r)) return true;
    const auto xd = static_cast<double>(x);
    return ring != 0 && ((r == 0 && xd >= hi_face - reach) || (r == ranks - 1 && xd < lo_face + reach));
  }
  // x, owned here, is needed by another slab (slabs are ordered, so by a neighbour, or in
  // a ring by the first or last).
  [[nodiscard]] SURGE_HD bool near_other(Real x) const {
    return (me > 0 && needs(x, me - 1)) || (me + 1 < ranks && needs(x, me + 1)) ||
           (ring != 0 && ((me > 1 && needs(x, 0)) || (me + 2 < ranks && needs(x, ranks - 1))));
  }
};

struct ExchangeStats {
  std::size_t bytes_sent = 0; // leavers and halo copies this process sent, in bytes
  std::size_t halo = 0;       // halo copies it holds
  bool rebalanced = false;    // the faces moved before this exchange
};

class SlabDecomposition {
public:
  // Slabs along `axis` over [lo, hi] (local coordinates; particles beyond belong to the
  // first or last slab); halo copies reach `reach` beyond each face. `ring`: the axis is
  // periodic, the slabs form a ring (SlabView). Water that crossed the periodic face needs
  // nothing here: until the next exchange moves it, its owner's images bring it back (as
  // on one process) and its halo copy, sent across the ring, is brought back alike.
  SlabDecomposition(int axis, double lo, double hi, double reach, bool ring = false);
  [[nodiscard]] int axis() const { return axis_; }
  // Whether particles carry the optional state fields (ParticleStore::optional), alike on
  // every process.
  void carry_optional(bool on) { optional_ = on; }
  [[nodiscard]] double reach() const { return reach_; }
  // Slab faces: process r owns [cuts[r], cuts[r+1]) along the axis.
  [[nodiscard]] const std::vector<double>& cuts() const { return cuts_; }
  [[nodiscard]] int owner(Real x) const;
  [[nodiscard]] bool owns(const Vec3& p) const;
  // The physics modules' view of this decomposition (owns_point, sum_exact, min).
  [[nodiscard]] Distribution distribution() const;

  // Faces that give every process about the same work, from particles every process
  // holds alike (the initial state or a checkpoint).
  void balance(const particles::HostParticles& all);
  // Keeps of `all` (held alike by every process) what this process owns, plus halo copies.
  ExchangeStats distribute(particles::HostParticles& all) const;
  // One step's exchange, in the store: halo copies dropped, particles that crossed a face
  // sent to their new owner, fresh halo copies of the particles within reach of other
  // slabs. Only the coordinate along the axis (and a state byte) of every particle comes
  // to the host; full records only for the particles that leave or are near a face.
  // With `balance` (collective, every process alike), the faces first move if the busiest
  // process has more than balance->threshold times the mean work (see Balance).
  struct Balance {
    double threshold = 1.1;
    // Seconds this process computed (not waiting) since the last check; with them each
    // process's particles are weighted by its measured cost per unit of counted work, so
    // that faces follow time rather than counts. 0: counts only (fluid 1, boundary 1/2).
    double busy_seconds = 0;
  };
  ExchangeStats exchange(particles::ParticleStore& store, const Balance* balance = nullptr);
  // Rank 0: the owned particles of every process, ordered by id (the same arrays whatever
  // the number of processes); other ranks: empty. Collective.
  [[nodiscard]] particles::HostParticles gather(const particles::HostParticles& local) const;

private:
  // Work per bin along the axis: weight(i) at coordinate x(i) for i < n.
  template <class X, class W>
  [[nodiscard]] std::vector<double> histogram(std::size_t n, X x, W weight) const;
  bool rebalance(const std::vector<Real>& x, const std::vector<std::uint8_t>& state, const Balance& b);
  void cuts_from(const std::vector<double>& hist);
  // cuts_ chosen: held to the ring's rule (keep_ring_ends), then the execution-space copy
  // follows (once per change, not per exchange).
  void cuts_changed();
  // On a periodic axis with 3 or more slabs: the end slabs at least a reach wide.
  void keep_ring_ends();
  // Appends to `out[r]` the records of the particles of `h` within reach of slab r != this one.
  void halo_records(const particles::HostParticles& h, std::vector<std::vector<char>>& out) const;
  [[nodiscard]] SlabView host_view() const;
  // The exchange's selection, made on the device: indices of halo copies and leavers to
  // drop, of leavers, and of owned particles near a face.
  void select(particles::ParticleStore& store, std::vector<std::uint32_t>& drop, std::vector<std::uint32_t>& leave,
              std::vector<std::uint32_t>& near);
  par::Buffer<double> cuts_dev_;         // cuts_ in the execution space
  par::Buffer<std::uint32_t> sel_index_; // the exchange's selection: particle indices
  par::Buffer<std::uint8_t> sel_code_;   // ... and what each one does
  int axis_;
  bool ring_;             // the axis is periodic: the slabs form a ring
  bool optional_ = false; // records carry the optional state fields (carry_optional)
  double lo_, hi_, reach_, bin_;
  std::vector<double> cuts_;
};

// The longest axis of [lo, hi] (0, 1 or 2).
[[nodiscard]] int longest_axis(const Vec3& lo, const Vec3& hi);

} // namespace surge::domain
