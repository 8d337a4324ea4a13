#include "surge/particles/particle_store.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace surge::particles {

void ParticleStore::upload(const HostParticles& h) {
  n_ = static_cast<int>(h.size());
  const auto n = h.size();
  removed_pending_ =
      static_cast<int>(std::count(h.kind.begin(), h.kind.end(), static_cast<std::uint8_t>(Kind::Removed)));
  par::upload(pos_, h.pos);
  par::upload(vel_, h.vel);
  par::upload(vel_prev_, h.vel_prev.size() == n ? h.vel_prev : h.vel);
  par::upload(rho_, h.rho);
  par::upload(rho_prev_, h.rho_prev.size() == n ? h.rho_prev : h.rho);
  par::upload(press_, h.press);
  par::upload(kind_, h.kind);
  par::upload(id_, h.id);
  if (distributed_) {
    if (h.halo.size() == n)
      par::upload(halo_, h.halo);
    else {
      halo_.resize(n);
      par::fill(halo_, std::uint8_t{0});
    }
  }
  acc_.resize(n);
  drho_.resize(n);
  vsig_.resize(n);
  cls_.resize(n);
  par::fill(acc_, Vec3{});
  par::fill(drho_, Real(0));
  par::fill(vsig_, Real(0));
}

void ParticleStore::download(HostParticles& h, bool history) const {
  const auto n = static_cast<std::size_t>(n_);
  par::download(h.pos, pos_, n);
  par::download(h.vel, vel_, n);
  par::download(h.rho, rho_, n);
  par::download(h.press, press_, n);
  par::download(h.kind, kind_, n);
  par::download(h.id, id_, n);
  if (history) {
    par::download(h.vel_prev, vel_prev_, n);
    par::download(h.rho_prev, rho_prev_, n);
  } else {
    h.vel_prev.clear();
    h.rho_prev.clear();
  }
  if (distributed_)
    par::download(h.halo, halo_, n);
  else
    h.halo.clear();
}

void ParticleStore::reserve_position_scratch() { pos_prev_.resize(static_cast<std::size_t>(n_)); }

ParticleView ParticleStore::view() {
  return {n_,
          pos_.data(),
          vel_.data(),
          vel_prev_.data(),
          pos_prev_.data(),
          acc_.data(),
          rho_.data(),
          rho_prev_.data(),
          drho_.data(),
          press_.data(),
          vsig_.data(),
          kind_.data(),
          id_.data(),
          distributed_ ? halo_.data() : nullptr};
}

template <class T>
void ParticleStore::reorder(par::Buffer<T>& field, par::Buffer<T>& tmp, const std::uint32_t* perm) {
  par::gather(field, tmp, perm, n_);
}

int ParticleStore::sort(neighbour::UniformGrid& grid) {
  cls_.resize(static_cast<std::size_t>(n_));
  std::uint8_t* dead = cls_.data();
  const std::uint8_t* kind = kind_.data();
  const auto removed = static_cast<std::uint8_t>(Kind::Removed), fluid = static_cast<std::uint8_t>(Kind::Fluid);
  // Sort class: fluid first in each cell, then boundary particles; removed ones last.
  par::parallel_for(
      n_, SURGE_LAMBDA(int i) { dead[i] = kind[i] == removed ? 2 : (kind[i] == fluid ? 0 : 1); });
  grid.sort(pos_.data(), dead, n_, distributed_ ? id_.data() : nullptr);
  const std::uint32_t* perm = grid.permutation();
  // acc, drho, press and vsig are recomputed after every sort, and pos_prev is scratch
  // within one symplectic step: none of them is carried through the sort, so acc and
  // drho serve as the gather scratch (no extra 16 B per particle), and cls, spent once
  // the keys are built, as the scratch of kind.
  reorder(pos_, acc_, perm);
  reorder(vel_, acc_, perm);
  reorder(vel_prev_, acc_, perm);
  reorder(rho_, drho_, perm);
  reorder(rho_prev_, drho_, perm);
  reorder(kind_, cls_, perm);
  reorder(id_, tmpu_, perm);
  if (distributed_) reorder(halo_, cls_, perm);
  grid.build_cell_start(n_);
  // The host knows how many were flagged, so the GPU need not report the live count.
  // The CPU builds, where the check costs nothing, verify it on every sort.
  const int live = n_ - removed_pending_;
#if !defined(SURGE_BACKEND_CUDA)
  if (grid.live_count() != live)
    throw std::logic_error("particle sort: " + std::to_string(n_ - grid.live_count()) + " particles were Removed, " +
                           std::to_string(removed_pending_) + " reported through add_removed");
#endif
  removed_pending_ = 0;
  const int dropped = n_ - live;
  n_ = live;
  for (auto* b : {&pos_, &vel_, &vel_prev_, &acc_}) b->truncate(static_cast<std::size_t>(live));
  for (auto* b : {&rho_, &rho_prev_, &drho_, &press_, &vsig_}) b->truncate(static_cast<std::size_t>(live));
  kind_.truncate(static_cast<std::size_t>(live));
  id_.truncate(static_cast<std::size_t>(live));
  if (distributed_) halo_.truncate(static_cast<std::size_t>(live));
  return dropped;
}

namespace detail {
// Free functions in a named namespace: nvcc's extended lambdas need an enclosing function
// with external linkage.
// out[k] <- field[idx[k]] on the host, through `scratch` (kept by the store: no allocation
// per exchange once it has grown; Buffer memory is 64-byte aligned, so any T fits).
template <class T>
void gather_to_host(const par::Buffer<T>& field, const std::uint32_t* idx, int n, par::Buffer<unsigned char>& scratch,
                    std::vector<T>& out) {
  scratch.resize(static_cast<std::size_t>(n) * sizeof(T));
  T* o = reinterpret_cast<T*>(scratch.data());
  const T* in = field.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int k) { o[k] = in[idx[k]]; });
  par::download_ptr(out, static_cast<const T*>(o), static_cast<std::size_t>(n));
}
// Grows the field by the host values, keeping what it holds.
template <class T>
void append_field(par::Buffer<T>& field, const std::vector<T>& add, std::size_t n_old) {
  field.resize_keep(n_old + add.size());
  par::upload_range(field, add, n_old);
}
} // namespace detail

void ParticleStore::coordinates(int axis, std::vector<Real>& x, std::vector<std::uint8_t>& state) {
  const auto n = static_cast<std::size_t>(n_);
  drho_.resize(n);
  cls_.resize(n);
  Real* out = drho_.data();
  std::uint8_t* st = cls_.data();
  const Vec3* pos = pos_.data();
  const std::uint8_t* kind = kind_.data();
  const std::uint8_t* halo = distributed_ ? halo_.data() : nullptr;
  const auto removed = static_cast<std::uint8_t>(Kind::Removed), fluid = static_cast<std::uint8_t>(Kind::Fluid);
  par::parallel_for(
      n_, SURGE_LAMBDA(int i) {
        out[i] = pos[i][axis];
        st[i] = kind[i] == removed ? 2 : (halo && halo[i] ? 1 : (kind[i] == fluid ? 0 : 3));
      });
  par::download(x, drho_, n);
  par::download(state, cls_, n);
}

ParticleStore::Scratch ParticleStore::exchange_scratch() {
  cls_.resize(static_cast<std::size_t>(n_));
  tmpu_.resize(static_cast<std::size_t>(n_));
  return {cls_.data(), tmpu_.data()};
}

void ParticleStore::extract(const std::vector<std::uint32_t>& idx, HostParticles& out) {
  const int n = static_cast<int>(idx.size());
  par::upload(idx_, idx);
  const std::uint32_t* k = idx_.data();
  detail::gather_to_host(pos_, k, n, extract_, out.pos);
  detail::gather_to_host(vel_, k, n, extract_, out.vel);
  detail::gather_to_host(vel_prev_, k, n, extract_, out.vel_prev);
  detail::gather_to_host(rho_, k, n, extract_, out.rho);
  detail::gather_to_host(rho_prev_, k, n, extract_, out.rho_prev);
  detail::gather_to_host(press_, k, n, extract_, out.press);
  detail::gather_to_host(kind_, k, n, extract_, out.kind);
  detail::gather_to_host(id_, k, n, extract_, out.id);
  out.halo.assign(idx.size(), 0);
}

void ParticleStore::remove(const std::vector<std::uint32_t>& idx) {
  par::upload(idx_, idx);
  const std::uint32_t* k = idx_.data();
  std::uint8_t* kind = kind_.data();
  const auto removed = static_cast<std::uint8_t>(Kind::Removed);
  const int n = static_cast<int>(idx.size());
  // upload filled k[0, n) (clang-tidy's analyzer loses the copy and calls k[j] undefined)
  par::parallel_for(
      n, SURGE_LAMBDA(int j) {
        kind[k[j]] = removed; // NOLINT(clang-analyzer-core.uninitialized.ArraySubscript)
      });
  add_removed(static_cast<int>(idx.size()));
}

void ParticleStore::append(const HostParticles& h) {
  if (h.size() == 0) return;
  const auto n_old = static_cast<std::size_t>(n_);
  detail::append_field(pos_, h.pos, n_old);
  detail::append_field(vel_, h.vel, n_old);
  detail::append_field(vel_prev_, h.vel_prev, n_old);
  detail::append_field(rho_, h.rho, n_old);
  detail::append_field(rho_prev_, h.rho_prev, n_old);
  detail::append_field(press_, h.press, n_old);
  detail::append_field(kind_, h.kind, n_old);
  detail::append_field(id_, h.id, n_old);
  if (distributed_)
    detail::append_field(halo_, h.halo.size() == h.size() ? h.halo : std::vector<std::uint8_t>(h.size(), 0), n_old);
  n_ = static_cast<int>(n_old + h.size());
  // Rates are recomputed before they are read; these only need the new size.
  for (auto* b : {&acc_}) b->resize_keep(n_old + h.size());
  for (auto* b : {&drho_, &vsig_}) b->resize_keep(n_old + h.size());
  cls_.resize(n_old + h.size());
}

std::size_t ParticleStore::bytes() const {
  std::size_t b = 0;
  for (const auto* x : {&pos_, &vel_, &vel_prev_, &pos_prev_, &acc_}) b += x->bytes();
  for (const auto* x : {&rho_, &rho_prev_, &drho_, &press_, &vsig_}) b += x->bytes();
  return b + kind_.bytes() + cls_.bytes() + halo_.bytes() + id_.bytes() + tmpu_.bytes() + idx_.bytes() +
         extract_.bytes();
}

} // namespace surge::particles
