#include "surge/particles/particle_store.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace surge::particles {

void ParticleStore::upload(const HostParticles& h) {
  begin_upload(h);
  for_each_state_field(h, f_, [&](const char*, const auto& host, auto& buf, unsigned use, const auto* from) {
    if (use & kOptional)
      upload_optional(buf, host, use);
    else
      par::upload(buf, (use & kHistory) && host.size() != h.size() ? *from : host);
  });
  finish_upload(h);
}

void ParticleStore::upload(HostParticles&& h) {
  begin_upload(h);
  const std::size_t n = h.size();
  // Each host field is released once it is in the execution space (a history field's
  // source with the history field), so that the two copies never coexist whole: the peak
  // of a solver's construction stays below its running memory.
  std::vector<const void*> sources;
  for_each_state_field(h, f_, [&](const char*, auto&, auto&, unsigned, const auto* from) {
    if (from) sources.push_back(from);
  });
  auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  for_each_state_field(h, f_, [&](const char*, auto& host, auto& buf, unsigned use, auto* from) {
    if (use & kOptional)
      upload_optional(buf, host, use);
    else
      par::upload(buf, (use & kHistory) && host.size() != n ? *from : host);
    if (from) release(*from);
    if (std::find(sources.begin(), sources.end(), &host) == sources.end()) release(host);
  });
  finish_upload(h);
  h = HostParticles{};
}

template <class T>
void ParticleStore::upload_optional(par::Buffer<T>& buf, const std::vector<T>& host, unsigned use) {
  if (!held(use))
    buf.resize(0);
  else if (host.size() == static_cast<std::size_t>(n_))
    par::upload(buf, host);
  else {
    buf.resize(static_cast<std::size_t>(n_));
    par::fill(buf, T{});
  }
}

void ParticleStore::begin_upload(const HostParticles& h) {
  n_ = static_cast<int>(h.size());
  removed_pending_ =
      static_cast<int>(std::count(h.kind.begin(), h.kind.end(), static_cast<std::uint8_t>(Kind::Removed)));
}

void ParticleStore::finish_upload(const HostParticles& h) {
  const auto n = static_cast<std::size_t>(n_);
  if (halos()) {
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
  for_each_state_field(h, f_, [&](const char*, auto& host, const auto& buf, unsigned use, const auto*) {
    if (((use & kHistory) && !history) || !held(use))
      host.clear();
    else
      par::download(host, buf, n);
  });
  if (halos())
    par::download(h.halo, halo_, n);
  else
    h.halo.clear();
}

void ParticleStore::reserve_position_scratch() { pos_prev_.resize(static_cast<std::size_t>(n_)); }

ParticleView ParticleStore::view() {
  return {n_,
          f_.pos.data(),
          f_.vel.data(),
          f_.vel_prev.data(),
          pos_prev_.data(),
          acc_.data(),
          f_.rho.data(),
          f_.rho_prev.data(),
          drho_.data(),
          f_.press.data(),
          vsig_.data(),
          f_.kind.data(),
          f_.id.data(),
          f_.surface.data(),
          optional_ ? f_.sps.data() : nullptr,
          halos() ? halo_.data() : nullptr};
}

template <class T>
void ParticleStore::reorder(par::Buffer<T>& field, par::Buffer<T>& tmp, const std::uint32_t* perm) {
  par::gather(field, tmp, perm, n_);
}

int ParticleStore::sort(neighbour::UniformGrid& grid) {
  cls_.resize(static_cast<std::size_t>(n_));
  std::uint8_t* dead = cls_.data();
  const std::uint8_t* kind = f_.kind.data();
  const auto removed = static_cast<std::uint8_t>(Kind::Removed), fluid = static_cast<std::uint8_t>(Kind::Fluid);
  // Sort class: fluid first in each cell, then boundary particles; removed ones last.
  par::parallel_for(
      n_, SURGE_LAMBDA(int i) { dead[i] = kind[i] == removed ? 2 : (kind[i] == fluid ? 0 : 1); });
  // acc, recomputed after every sort, is the sort's scratch (12 B per particle: 64-bit keys
  // and values when sorting by id).
  grid.sort(f_.pos.data(), dead, n_, distributed_ ? f_.id.data() : nullptr, acc_.data(), acc_.bytes());
  grid.build_cell_start(n_);
  const std::uint32_t* perm = grid.permutation();
  // acc, drho, press and vsig are recomputed after every sort, and pos_prev is scratch
  // within one symplectic step: none of them is carried through the sort, so acc and
  // drho serve as the gather scratch (no extra 16 B per particle), cls, spent once the
  // keys are built, as the scratch of kind, and the keys, spent once cell_start is
  // built, as the scratch of id.
  par::Buffer<std::uint32_t>& spent_keys = grid.spent_keys();
  for_each_state_field(f_, f_, [&](const char*, auto& buf, auto&, unsigned use, const auto*) {
    if (!(use & kSorted) || !held(use)) return;
    if constexpr (std::is_same_v<std::decay_t<decltype(buf)>, par::Buffer<std::uint32_t>>)
      reorder(buf, spent_keys, perm);
    else
      reorder(buf, scratch(buf), perm);
  });
  if (halos()) reorder(halo_, cls_, perm);
  grid.mark_wet(f_.kind.data());
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
  const auto keep = static_cast<std::size_t>(live);
  for_each_state_field(f_, f_, [&](const char*, auto& buf, auto&, unsigned, const auto*) { buf.truncate(keep); });
  acc_.truncate(keep);
  for (auto* b : {&drho_, &vsig_}) b->truncate(keep);
  if (halos()) halo_.truncate(keep);
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
  const Vec3* pos = f_.pos.data();
  const std::uint8_t* kind = f_.kind.data();
  const std::uint8_t* halo = halos() ? halo_.data() : nullptr;
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
  for_each_state_field(out, f_, [&](const char*, auto& host, const auto& buf, unsigned use, const auto*) {
    if (held(use))
      detail::gather_to_host(buf, k, n, extract_, host);
    else
      host.clear();
  });
  out.halo.assign(idx.size(), 0);
}

void ParticleStore::remove(const std::vector<std::uint32_t>& idx) {
  par::upload(idx_, idx);
  const std::uint32_t* k = idx_.data();
  std::uint8_t* kind = f_.kind.data();
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
  for_each_state_field(h, f_, [&](const char*, const auto& host, auto& buf, unsigned use, const auto*) {
    if (!held(use)) return;
    // An optional field the host does not give starts as 0.
    using T = typename std::decay_t<decltype(host)>::value_type;
    detail::append_field(buf, host.size() == h.size() ? host : std::vector<T>(h.size(), T{}), n_old);
  });
  if (halos())
    detail::append_field(halo_, h.halo.size() == h.size() ? h.halo : std::vector<std::uint8_t>(h.size(), 0), n_old);
  n_ = static_cast<int>(n_old + h.size());
  // Rates are recomputed before they are read; these only need the new size.
  for (auto* b : {&acc_}) b->resize_keep(n_old + h.size());
  for (auto* b : {&drho_, &vsig_}) b->resize_keep(n_old + h.size());
  cls_.resize(n_old + h.size());
}

namespace detail {
// field[n_old + k] <- field[idx[k]] for k < m (the field already grown to n_old + m).
template <class T>
void copy_to_tail(par::Buffer<T>& field, const std::uint32_t* idx, int m, std::size_t n_old) {
  field.resize_keep(n_old + static_cast<std::size_t>(m));
  T* f = field.data();
  if (f == nullptr) return; // m == 0 (the caller returns before)
  par::parallel_for(
      m, SURGE_LAMBDA(int k) { f[n_old + static_cast<std::size_t>(k)] = f[idx[k]]; });
}
} // namespace detail

int ParticleStore::append_copies(const std::uint32_t* idx, int m) {
  const int n_old = n_;
  if (m == 0) return n_old;
  const auto old = static_cast<std::size_t>(n_old), n_new = old + static_cast<std::size_t>(m);
  for_each_state_field(f_, f_, [&](const char*, auto& buf, auto&, unsigned use, const auto*) {
    if (held(use)) detail::copy_to_tail(buf, idx, m, old);
  });
  if (halos()) detail::copy_to_tail(halo_, idx, m, old);
  n_ = n_old + m;
  acc_.resize_keep(n_new);
  for (auto* b : {&drho_, &vsig_}) b->resize_keep(n_new);
  cls_.resize(n_new);
  return n_old;
}

std::size_t ParticleStore::bytes() const {
  std::size_t b = 0;
  for_each_state_field(f_, f_,
                       [&](const char*, const auto& buf, const auto&, unsigned, const auto*) { b += buf.bytes(); });
  for (const auto* x : {&pos_prev_, &acc_}) b += x->bytes();
  for (const auto* x : {&drho_, &vsig_}) b += x->bytes();
  return b + cls_.bytes() + halo_.bytes() + tmpu_.bytes() + idx_.bytes() + extract_.bytes() + sps_scratch_.bytes();
}

} // namespace surge::particles
