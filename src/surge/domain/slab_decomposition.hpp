// The SPH particles cut into slabs along one axis, one slab per process (SPEC §6):
// which process owns a particle, the halo copies each process needs from the others,
// migration across slab faces, and faces moved to even out the work. Host-side: the
// run loop stages particles through HostParticles (device memory on the GPU build).
#pragma once
#include "surge/core/distribution.hpp"
#include "surge/particles/particle_store.hpp"

#include <cstddef>
#include <vector>

namespace surge::domain {

struct ExchangeStats {
  std::size_t migrated = 0;   // particles this process handed to another owner
  std::size_t halo_sent = 0;  // halo copies this process sent
  std::size_t bytes_sent = 0; // both, in bytes
  std::size_t owned = 0;      // particles this process owns after the exchange
  std::size_t halo = 0;       // halo copies it holds
};

class SlabDecomposition {
public:
  // Slabs along `axis` over [lo, hi] (local coordinates; particles beyond belong to the
  // first or last slab); halo copies reach `reach` beyond each face.
  SlabDecomposition(int axis, double lo, double hi, double reach);

  [[nodiscard]] int axis() const { return axis_; }
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
  // One step's exchange, in place: halo copies dropped, particles that crossed a face sent
  // to their new owner, fresh halo copies of the particles within reach of other slabs.
  ExchangeStats exchange(particles::HostParticles& local) const;
  // Moves the faces when the busiest process has more than `threshold` times the mean work;
  // collective. Returns whether they moved (the next exchange then migrates particles).
  bool rebalance(const particles::HostParticles& local, double threshold);
  // Rank 0: the owned particles of every process, ordered by id (the same arrays whatever
  // the number of processes); other ranks: empty. Collective.
  [[nodiscard]] particles::HostParticles gather(const particles::HostParticles& local) const;

private:
  [[nodiscard]] std::vector<double> histogram(const particles::HostParticles& h, bool owned_only) const;
  void cuts_from(const std::vector<double>& hist);
  ExchangeStats send_halos(particles::HostParticles& owned) const;
  int axis_;
  double lo_, hi_, reach_, bin_;
  std::vector<double> cuts_;
};

// The longest axis of [lo, hi] (0, 1 or 2).
[[nodiscard]] int longest_axis(const Vec3& lo, const Vec3& hi);

} // namespace surge::domain
