// Images across the domain's periodic and symmetry faces: copies of the particles near such
// a face, placed beyond it (one period away beyond the opposite face, or mirrored in the
// face itself), so that every neighbour loop (rates, wall models, gauges) sees the water
// across the face without knowing of it. The images are rebuilt before every sort (the old
// ones dropped, fluid that crossed a face wrapped in or reflected back, fresh copies made,
// all in the execution space) and, before every rates pass, refreshed in place from the
// particles they copy, so that a band of one interaction reach suffices whatever the
// integrator. Images are halo particles (ParticleView::owned is false): never counted,
// integrated for their own sake, removed, written or checkpointed.
#pragma once
#include "surge/domain/image_frame.hpp"
#include "surge/par/parallel.hpp"
#include "surge/particles/particle_store.hpp"

#include <cstdint>

namespace surge::domain {

// The halo flag of an image (ParticleView::halo; 1 is a distributed run's copy) is
// image_flag plus a bit per axis on which the image is mirrored (1 x, 2 y, 4 z).
inline constexpr std::uint8_t image_flag = 2;

// Whether particle i is an image (not a particle of its own, nor a distributed run's copy).
[[nodiscard]] SURGE_HD inline bool is_image(const particles::ParticleView& p, int i) {
  return p.halo != nullptr && p.halo[i] >= image_flag;
}

// A fluid particle that crossed a face during a step, put back: wrapped into [lo, hi) once
// across a periodic face (a particle crosses at most one period a step), or reflected in a
// symmetry face with its velocities' normal components reversed (its mirror image crossed
// the other way).
SURGE_HD inline void bring_back(const ImageFrame& f, Vec3& x, Vec3& v, Vec3& v_prev) {
  for (int k = 0; k < 3; ++k) {
    if (f.periodic[k]) {
      if (x[k] >= f.hi[k])
        x[k] -= f.len[k];
      else if (x[k] < f.lo[k])
        x[k] += f.len[k];
      continue;
    }
    const int s = f.mirror_lo[k] && x[k] < f.lo[k] ? -1 : (f.mirror_hi[k] && x[k] > f.hi[k] ? 1 : 0);
    if (s == 0) continue;
    x[k] = shifted(f, k, x[k], s);
    v[k] = -v[k];
    v_prev[k] = -v_prev[k];
  }
}

class Images {
public:
  Images() = default; // off
  // `max_id`: the largest particle id + 1 (the images find their particles by id).
  Images(const ImageFrame& f, std::uint32_t max_id);
  [[nodiscard]] bool on() const { return frame_.any(); }
  [[nodiscard]] const ImageFrame& frame() const { return frame_; }
  // Before a sort: drops the images, brings the fluid that crossed a face back in
  // (bring_back), and appends an image of each particle (owned, or a distributed run's
  // copy) for every combination of shifts that puts it within the band.
  void rebuild(particles::ParticleStore& store);
  // After a sort: where each particle's id now lies, for refresh.
  void link(particles::ParticleStore& store);
  // Before a rates pass (and again after the wall model's): every image takes its
  // particle's state (position moved by whole periods or mirrored, velocities' mirrored
  // components reversed; density, pressure, kind as they are).
  void refresh(const particles::ParticleView& p) const;
  [[nodiscard]] long count() const { return images_; }
  // By id: the index of the particle an image copies (valid after link; execution space),
  // for fields the refresh does not copy.
  [[nodiscard]] const std::uint32_t* sources() const { return where_.data(); }
  [[nodiscard]] std::size_t bytes() const { return where_.bytes() + count_.bytes() + src_.bytes() + shift_.bytes(); }

private:
  ImageFrame frame_;
  std::uint32_t max_id_ = 0;
  long images_ = 0;
  par::Buffer<std::uint32_t> where_;               // by id: the index of the particle an image copies
  par::Buffer<std::uint32_t> count_, src_, shift_; // the rebuild's scratch
};

} // namespace surge::domain
