// The per-particle fields that carry an SPH particle's state, declared once. The store's
// upload, download, sort and exchange (particle_store.cpp), the checkpoint
// (io/checkpoint.cpp) and a distributed run's records (domain/slab_decomposition.cpp)
// walk for_each_state_field; a new field is a member of HostParticles, a buffer of the
// same name in ParticleStore::Fields and one line of the list.
#pragma once
#include "surge/core/sym_tensor.hpp"
#include "surge/core/types.hpp"

#include <cstdint>
#include <vector>

namespace surge::particles {

// Host-side copy of particle data, used to create particles and to write output.
struct HostParticles {
  std::vector<Vec3> pos, vel;
  std::vector<Real> rho, press;
  std::vector<std::uint8_t> kind;
  std::vector<std::uint32_t> id;
  // Time-integration history (Verlet's v^{n-1}, rho^{n-1}); filled for checkpoints only.
  std::vector<Vec3> vel_prev;
  std::vector<Real> rho_prev;
  // 1 at the free surface (WcsphSolver::mark_surface, for output frames; 0 until marked).
  std::vector<std::uint8_t> surface;
  // sph.viscosity: laminar_sps only (empty otherwise): the SPS stress tau/rho the next rates
  // pass reads (sph/sps_turbulence.hpp), from the strain rate of the last one.
  std::vector<SymTensor> sps;
  // Distributed runs: 1 for a halo copy of a particle another process owns (empty: all owned).
  std::vector<std::uint8_t> halo;
  [[nodiscard]] std::size_t size() const { return pos.size(); }
  void push(const Vec3& p, const Vec3& v, Real density, Kind k, std::uint32_t ident) {
    pos.push_back(p);
    vel.push_back(v);
    rho.push_back(density);
    press.push_back(0);
    kind.push_back(static_cast<std::uint8_t>(k));
    id.push_back(ident);
    surface.push_back(0);
  }
};

// How a field travels.
enum FieldUse : unsigned {
  kSorted = 1,     // carried through the store's sort (the others are recomputed after it)
  kCheckpoint = 2, // written to checkpoints (the others restart as zero)
  kHistory = 4,    // integration history: downloaded only when asked, and when not
                   // given on upload it starts as `from` (the current value)
  kOptional = 8,   // held only where a model asks for it (ParticleStore::set_optional):
                   // empty elsewhere, on the host and in the store alike
};

// Calls f(name, a.field, b.field, uses, from) for every field, in checkpoint order, on two
// objects with members of these names (HostParticles, the store's buffers; the same object
// twice where one is enough); `from` is a pointer to a's field a history field starts
// from, or null.
template <class A, class B, class F>
void for_each_state_field(A& a, B& b, F&& f) {
  using V3 = decltype(&a.pos);
  using R = decltype(&a.rho);
  f("pos", a.pos, b.pos, kSorted | kCheckpoint, V3{});
  f("vel", a.vel, b.vel, kSorted | kCheckpoint, V3{});
  f("vel_prev", a.vel_prev, b.vel_prev, kSorted | kCheckpoint | kHistory, &a.vel);
  f("rho", a.rho, b.rho, kSorted | kCheckpoint, R{});
  f("rho_prev", a.rho_prev, b.rho_prev, kSorted | kCheckpoint | kHistory, &a.rho);
  f("press", a.press, b.press, 0U, R{});
  f("kind", a.kind, b.kind, kSorted | kCheckpoint, decltype(&a.kind){});
  f("id", a.id, b.id, kSorted | kCheckpoint, decltype(&a.id){});
  f("surface", a.surface, b.surface, 0U, decltype(&a.kind){});
  f("sps", a.sps, b.sps, kSorted | kCheckpoint | kOptional, decltype(&a.sps){});
}

// Keeps the particles i with keep(i), in order (every field that holds one value per
// particle, the halo flags included).
template <class K>
void keep_if(HostParticles& h, K&& keep) {
  const std::size_t n = h.size();
  std::vector<char> k(n);
  for (std::size_t i = 0; i < n; ++i) k[i] = keep(i) ? 1 : 0;
  auto filter = [&](auto& v) {
    if (v.size() != n) return;
    std::size_t o = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (k[i]) v[o++] = v[i];
    v.resize(o);
  };
  for_each_state_field(h, h, [&](const char*, auto& v, auto&, unsigned, const auto*) { filter(v); });
  filter(h.halo);
}

} // namespace surge::particles
