#include "surge/domain/images.hpp"

#include "surge/algo/algo.hpp"

#include <cmath>
#include <stdexcept>

namespace surge::domain {

namespace {
// An image's shift per axis (axis_shifts: each from -3 to 3), packed in one word.
SURGE_HD inline std::uint32_t pack_shift(int sx, int sy, int sz) {
  return static_cast<std::uint32_t>((sx + 3) + 7 * (sy + 3) + 49 * (sz + 3));
}
SURGE_HD inline int unpack_shift(std::uint32_t code, int k) {
  const std::uint32_t d = k == 0 ? 1 : (k == 1 ? 7 : 49);
  return static_cast<int>((code / d) % 7) - 3;
}
// The axes on which the shift mirrors (the bits of the image's halo flag above image_flag).
SURGE_HD inline std::uint8_t mirror_bits(const ImageFrame& f, std::uint32_t code) {
  std::uint8_t b = 0;
  for (int k = 0; k < 3; ++k)
    if (!f.periodic[k] && unpack_shift(code, k) != 0) b = static_cast<std::uint8_t>(b | (1U << k));
  return b;
}
} // namespace

namespace detail {
// Free functions: nvcc's extended lambdas may not live in member functions of a class
// with private members they capture.

// Marks the old images Removed (returns how many), brings back the fluid that crossed a
// face (bring_back), and writes each live particle's image count.
long drop_wrap_count(const particles::ParticleView& p, std::uint8_t* halo, ImageFrame f, std::uint32_t* count) {
  const auto removed = static_cast<std::uint8_t>(Kind::Removed), fluid = static_cast<std::uint8_t>(Kind::Fluid);
  return par::parallel_reduce(
      p.n, 0L,
      SURGE_LAMBDA(int i)->long {
        count[i] = 0;
        if (halo[i] >= image_flag) { // an old image (a distributed run's exchange may have dropped it already)
          if (p.kind[i] == removed) return 0;
          p.kind[i] = removed;
          return 1;
        }
        if (p.kind[i] == removed) return 0;
        Vec3 x = p.pos[i];
        if (p.kind[i] == fluid) {
          Vec3 v = p.vel[i], v_prev = p.vel_prev[i];
          bring_back(f, x, v, v_prev);
          p.pos[i] = x;
          p.vel[i] = v;
          p.vel_prev[i] = v_prev;
        }
        std::uint32_t n = 1;
        for (int k = 0; k < 3; ++k) n *= static_cast<std::uint32_t>(axis_shifts(f, k, x[k]).count);
        count[i] = n - 1;
        return 0;
      },
      par::Sum{});
}

// For each particle with images, from its place `at` in the list: the particle and each
// image's shift (every combination of the axes' shifts but none).
void list_images(const particles::ParticleView& p, const std::uint8_t* halo, ImageFrame f, const std::uint32_t* at,
                 std::uint32_t* src, std::uint32_t* shift) {
  const auto removed = static_cast<std::uint8_t>(Kind::Removed);
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (halo[i] >= image_flag || p.kind[i] == removed) return;
        const Vec3 x = p.pos[i];
        const AxisShifts a = axis_shifts(f, 0, x.x), b = axis_shifts(f, 1, x.y), c = axis_shifts(f, 2, x.z);
        std::uint32_t q = at[i];
        for (int sz = c.first; sz < c.first + c.count; ++sz)
          for (int sy = b.first; sy < b.first + b.count; ++sy)
            for (int sx = a.first; sx < a.first + a.count; ++sx) {
              if (sx == 0 && sy == 0 && sz == 0) continue;
              src[q] = static_cast<std::uint32_t>(i);
              shift[q] = pack_shift(sx, sy, sz);
              ++q;
            }
      });
}

// The copies at [first, first + m) become images: moved by their shifts (mirrored
// velocity components reversed, the SPS stress seen mirrored), flagged with their mirrored axes.
void place_images(const particles::ParticleView& p, std::uint8_t* halo, ImageFrame f, int first, int m,
                  const std::uint32_t* shift) {
  par::parallel_for(
      m, SURGE_LAMBDA(int k) {
        const int i = first + k;
        Vec3 x = p.pos[i], v = p.vel[i], v_prev = p.vel_prev[i];
        // list_images wrote every shift[k], k < m (the analyzer cannot follow the scan).
        const std::uint8_t mirrored = mirror_bits(f, shift[k]); // NOLINT(clang-analyzer-core.CallAndMessage)
        for (int a = 0; a < 3; ++a) {
          x[a] = shifted(f, a, x[a], unpack_shift(shift[k], a));
          if (mirrored & (1U << a)) {
            v[a] = -v[a];
            v_prev[a] = -v_prev[a];
          }
        }
        p.pos[i] = x;
        p.vel[i] = v;
        p.vel_prev[i] = v_prev;
        if (p.sps) p.sps[i] = p.sps[i].mirrored(mirrored);
        halo[i] = static_cast<std::uint8_t>(image_flag + mirrored);
      });
}

void link(const particles::ParticleView& p, std::uint32_t* where) {
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (p.halo[i] < image_flag) where[p.id[i]] = static_cast<std::uint32_t>(i);
      });
}

void refresh(const particles::ParticleView& p, ImageFrame f, const std::uint32_t* where) {
  par::parallel_for(
      p.n, SURGE_LAMBDA(int i) {
        if (!is_image(p, i)) return;
        const auto j = static_cast<int>(where[p.id[i]]);
        const Vec3 xi = p.pos[i], xj = p.pos[j];
        const unsigned mirrored = static_cast<unsigned>(p.halo[i] - image_flag);
        Vec3 x = xj, v = p.vel[j], v_prev = p.vel_prev[j];
        for (int k = 0; k < 3; ++k) {
          int s = 0;
          if (f.periodic[k]) {
            // The image lies a whole number of periods from its particle, give or take what
            // the two moved apart since the rebuild (far less than half a period).
            s = static_cast<int>(std::floor((xi[k] - xj[k]) / f.len[k] + Real(0.5)));
          } else if (mirrored & (1U << k)) {
            s = 2 * xi[k] < f.lo[k] + f.hi[k] ? -1 : 1; // the face the image lies beyond
            v[k] = -v[k];
            v_prev[k] = -v_prev[k];
          }
          x[k] = shifted(f, k, xj[k], s);
        }
        p.pos[i] = x;
        p.vel[i] = v;
        p.vel_prev[i] = v_prev;
        p.rho[i] = p.rho[j];
        p.rho_prev[i] = p.rho_prev[j];
        p.press[i] = p.press[j];
        p.kind[i] = p.kind[j];
        if (p.sps) p.sps[i] = p.sps[j].mirrored(mirrored);
      });
}
} // namespace detail

Images::Images(const ImageFrame& f, std::uint32_t max_id) : frame_(f), max_id_(max_id) {}

void Images::rebuild(particles::ParticleStore& store) {
  const int n = store.size();
  count_.resize(static_cast<std::size_t>(n) + 1);
  const auto flags = [&store] { // re-read after appending: the buffer may have moved
    std::uint8_t* h = store.halo_flags();
    if (h == nullptr) throw std::logic_error("images need a store that carries halo flags (set_images)");
    return h;
  };
  std::uint8_t* halo = flags();
  const long dropped = detail::drop_wrap_count(store.view(), halo, frame_, count_.data());
  store.add_removed(static_cast<int>(dropped));
  const std::uint32_t m = algo::exclusive_scan(count_.data(), count_.data(), n);
  src_.resize(m);
  shift_.resize(m);
  detail::list_images(store.view(), halo, frame_, count_.data(), src_.data(), shift_.data());
  const int first = store.append_copies(src_.data(), static_cast<int>(m));
  detail::place_images(store.view(), flags(), frame_, first, static_cast<int>(m), shift_.data());
  images_ = m;
}

void Images::link(particles::ParticleStore& store) {
  where_.resize(max_id_);
  detail::link(store.view(), where_.data());
}

void Images::refresh(const particles::ParticleView& p) const {
  if (images_ == 0) return;
  detail::refresh(p, frame_, where_.data());
}

} // namespace surge::domain
