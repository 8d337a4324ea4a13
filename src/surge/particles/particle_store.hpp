// Structure-of-arrays store of SPH particles (fluid, wall, body) in the
// execution space, and the plain view kernels receive.
#pragma once
#include "surge/neighbour/uniform_grid.hpp"
#include "surge/par/parallel.hpp"
#include "surge/particles/particle_fields.hpp"

#include <cstdint>
#include <vector>

namespace surge::particles {

// What kernels see: raw pointers and a count. Each loop index writes only to itself.
struct ParticleView {
  int n = 0;
  Vec3* pos = nullptr;
  Vec3* vel = nullptr;
  Vec3* vel_prev = nullptr; // v^{n-1} (Verlet) or v^n (symplectic predictor)
  Vec3* pos_prev = nullptr; // r^n for the symplectic scheme (scratch within a step; null unless reserved)
  Vec3* acc = nullptr;
  Real* rho = nullptr;
  Real* rho_prev = nullptr;
  Real* drho = nullptr;
  Real* press = nullptr;
  Real* vsig = nullptr; // max_j |h v_ij.r_ij/(r^2+0.01h^2)| for the time step
  std::uint8_t* kind = nullptr;
  std::uint32_t* id = nullptr;
  std::uint8_t* surface = nullptr; // 1 at the free surface, where marked (output frames)
  SymTensor* sps = nullptr;        // the SPS stress tau/rho (sph.viscosity: laminar_sps; else null)
  // halo[i] != 0 for a copy whose state is this process's only to read: 1 a copy of a
  // particle another process owns (a distributed run), 2 and up a periodic or mirrored image
  // (domain/images.hpp). Null: every particle is owned.
  const std::uint8_t* halo = nullptr;
  [[nodiscard]] SURGE_HD bool owned(int i) const { return !halo || !halo[i]; }
};

class ParticleStore {
public:
  // Replaces the contents with host data; without vel_prev / rho_prev the
  // current values also become v^{n-1} and rho^{n-1}.
  void upload(const HostParticles& h);
  // The same, releasing h's memory field by field as it goes (h ends empty).
  void upload(HostParticles&& h);
  // A distributed store carries the halo flag of every particle and sorts each cell by
  // particle id (UniformGrid::sort), so that its sums do not depend on the distribution.
  void set_distributed(bool on) { distributed_ = on; }
  // A store with periodic or mirrored images carries the halo flag too (not the sort by id).
  void set_images(bool on) { images_ = on; }
  // Whether the optional state fields (particle_fields.hpp: kOptional) are held: set before
  // the first upload. Held, a field the host does not give starts as 0.
  void set_optional(bool on) { optional_ = on; }
  [[nodiscard]] bool optional() const { return optional_; }
  [[nodiscard]] bool distributed() const { return distributed_; }
  // The halo flags, writable (periodic images mark their own; null without halos).
  [[nodiscard]] std::uint8_t* halo_flags() { return halos() ? halo_.data() : nullptr; }
  // Copies the current state to the host (pressure included); with `history`
  // also vel_prev and rho_prev (for checkpoints).
  void download(HostParticles& h, bool history = false) const;

  [[nodiscard]] int size() const { return n_; }

  // A distributed run's exchange, moving only what crosses between processes (device
  // memory on the GPU build): every particle's coordinate along `axis` and its state
  // (0 owned fluid, 1 halo copy, 2 marked Removed, 3 owned wall or body; drho and cls serve as the scratch: both are
  // rebuilt before they are read again); the particles at `idx`, copied to the host with
  // their integration history; the particles at `idx` marked Removed (the next sort drops
  // them); particles appended at the end.
  void coordinates(int axis, std::vector<Real>& x, std::vector<std::uint8_t>& state);
  void extract(const std::vector<std::uint32_t>& idx, HostParticles& out);
  // Two per-particle scratch arrays for an exchange's selection (the sort's own scratch,
  // free between sorts): a byte and a 32-bit word per particle.
  struct Scratch {
    std::uint8_t* byte;
    std::uint32_t* word;
  };
  Scratch exchange_scratch();
  void remove(const std::vector<std::uint32_t>& idx);
  void append(const HostParticles& h);
  // Appends copies of the m particles at idx (execution space) at the end, every state field
  // and the halo flag copied (the caller then marks and moves them); returns the first copy's index.
  int append_copies(const std::uint32_t* idx, int m);
  // Allocates pos_prev (scratch of the symplectic scheme; null in views until then).
  void reserve_position_scratch();
  [[nodiscard]] ParticleView view();
  // Sorts by cell, reorders every field and drops particles marked Removed.
  // Returns the number of particles dropped.
  int sort(neighbour::UniformGrid& grid);
  // Whoever marks particles Removed in the execution space says how many, so that the
  // sort knows the live count without reading it back from the device.
  void add_removed(int k) { removed_pending_ += k; }
  // Bytes held in the execution space, grid excluded.
  [[nodiscard]] std::size_t bytes() const;

private:
  void begin_upload(const HostParticles& h);
  void finish_upload(const HostParticles& h);
  // An optional field from the host: empty unless held, 0 where the host gives none.
  template <class T>
  void upload_optional(par::Buffer<T>& buf, const std::vector<T>& host, unsigned use);
  // The state fields (particle_fields.hpp), one buffer each, named as in HostParticles.
  struct Fields {
    par::Buffer<Vec3> pos, vel, vel_prev;
    par::Buffer<Real> rho, rho_prev, press;
    par::Buffer<std::uint8_t> kind;
    par::Buffer<std::uint32_t> id;
    par::Buffer<std::uint8_t> surface;
    par::Buffer<SymTensor> sps;
  };
  // Whether a field of these uses is held (an optional one only when asked).
  [[nodiscard]] bool held(unsigned use) const { return !(use & kOptional) || optional_; }
  template <class T>
  void reorder(par::Buffer<T>& field, par::Buffer<T>& tmp, const std::uint32_t* perm);
  // The sort's gather scratch for a field of each type: buffers rebuilt after every sort.
  par::Buffer<Vec3>& scratch(par::Buffer<Vec3>& /*field*/) { return acc_; }
  par::Buffer<Real>& scratch(par::Buffer<Real>& /*field*/) { return drho_; }
  par::Buffer<std::uint8_t>& scratch(par::Buffer<std::uint8_t>& /*field*/) { return cls_; }
  par::Buffer<SymTensor>& scratch(par::Buffer<SymTensor>& /*field*/) { return sps_scratch_; }
  int n_ = 0;
  int removed_pending_ = 0; // marked Removed since the last sort
  Fields f_;
  par::Buffer<Vec3> pos_prev_, acc_;
  par::Buffer<Real> drho_, vsig_;
  // Carries halo_ when distributed or with images.
  [[nodiscard]] bool halos() const { return distributed_ || images_; }
  bool distributed_ = false; // sorts by id
  bool images_ = false;
  bool optional_ = false;
  par::Buffer<SymTensor> sps_scratch_; // the sort's gather scratch of the SPS stress (held with it)
  par::Buffer<std::uint8_t> cls_, halo_;
  par::Buffer<std::uint32_t> tmpu_;    // the exchange's scratch (distributed runs only)
  par::Buffer<std::uint32_t> idx_;     // the exchange's selection
  par::Buffer<unsigned char> extract_; // its gathered fields, one at a time
};

} // namespace surge::particles
