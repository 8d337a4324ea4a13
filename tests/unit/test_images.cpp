// Periodic and mirror images (domain/images.hpp) and absorbing zones (sph/damping.hpp):
// the shifts, the mirror and wrap formulas against their closed forms, and a still-water
// store whose images are exactly the shifted or mirrored particles.
#include "surge/domain/images.hpp"
#include "surge/sph/damping.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace surge;

namespace {
domain::ImageFrame frame() {
  domain::ImageFrame f;
  f.periodic[0] = 1;  // x periodic
  f.mirror_lo[1] = 1; // a mirror at y = 0
  f.mirror_hi[2] = 1; // and at z = 0.4
  f.hi = Vec3{1, 0.5f, 0.4f};
  f.len = f.hi - f.lo;
  f.band = Vec3{0.1f, 0.1f, 0.1f};
  return f;
}
} // namespace

TEST(Images, AxisShifts) {
  const auto f = frame();
  // Periodic x: near lo an image one period up, near hi one down, in the middle none.
  auto a = domain::axis_shifts(f, 0, Real(0.05));
  EXPECT_EQ(a.first, 0);
  EXPECT_EQ(a.count, 2);
  a = domain::axis_shifts(f, 0, Real(0.95));
  EXPECT_EQ(a.first, -1);
  EXPECT_EQ(a.count, 2);
  a = domain::axis_shifts(f, 0, Real(0.5));
  EXPECT_EQ(a.count, 1);
  // Mirror at y = 0 only: near it -1, near y = 0.5 (no mirror) nothing.
  a = domain::axis_shifts(f, 1, Real(0.02));
  EXPECT_EQ(a.first, -1);
  EXPECT_EQ(a.count, 2);
  EXPECT_EQ(domain::axis_shifts(f, 1, Real(0.45)).count, 1);
  // Mirror at z = 0.4: +1 near it.
  a = domain::axis_shifts(f, 2, Real(0.35));
  EXPECT_EQ(a.first, 0);
  EXPECT_EQ(a.count, 2);
}

TEST(Images, ShiftedAndBroughtBack) {
  const auto f = frame();
  EXPECT_FLOAT_EQ(domain::shifted(f, 0, Real(0.05), 1), 1.05f);   // one period
  EXPECT_FLOAT_EQ(domain::shifted(f, 1, Real(0.02), -1), -0.02f); // mirrored in y = 0
  EXPECT_FLOAT_EQ(domain::shifted(f, 2, Real(0.35), 1), 0.45f);   // mirrored in z = 0.4
  // A particle that left through x = 1 (periodic), y = 0 (mirror) and z = 0.4 (mirror).
  Vec3 x{1.02f, -0.01f, 0.43f}, v{1, -2, 3}, vp{4, -5, 6};
  domain::bring_back(f, x, v, vp);
  EXPECT_NEAR(x.x, 0.02, 1e-6);
  EXPECT_NEAR(x.y, 0.01, 1e-6);
  EXPECT_NEAR(x.z, 0.37, 1e-6);
  EXPECT_EQ(v.x, 1); // periodic: velocity kept
  EXPECT_EQ(v.y, 2); // mirrored: normal components reversed, the previous step's too
  EXPECT_EQ(v.z, -3);
  EXPECT_EQ(vp.y, 5);
  EXPECT_EQ(vp.z, -6);
}

// Particles near every image face of a store: after a rebuild the images are exactly
// the particles shifted or mirrored, one per combination, velocities mirrored.
TEST(Images, RebuildMakesEveryImage) {
  const auto f = frame();
  particles::HostParticles h;
  h.push(Vec3{0.05f, 0.02f, 0.2f}, Vec3{1, 2, 3}, 1000, Kind::Fluid, 0); // x lo, y lo: 3 images
  h.push(Vec3{0.5f, 0.25f, 0.2f}, Vec3{1, 2, 3}, 1000, Kind::Fluid, 1);  // middle: none
  h.push(Vec3{0.97f, 0.25f, 0.38f}, Vec3{1, 2, 3}, 1000, Kind::Wall, 2); // x hi, z hi: 3 images
  particles::ParticleStore store;
  store.set_images(true);
  store.upload(h);
  domain::Images im(f, 3);
  im.rebuild(store);
  EXPECT_EQ(im.count(), 6);
  particles::HostParticles out;
  store.download(out);
  ASSERT_EQ(out.size(), 9U);
  std::vector<std::vector<Real>> got;
  for (std::size_t i = 3; i < out.size(); ++i) {
    EXPECT_GE(out.halo[i], domain::image_flag);
    got.push_back({static_cast<Real>(out.id[i]), out.pos[i].x, out.pos[i].y, out.pos[i].z, out.vel[i].y, out.vel[i].z,
                   static_cast<Real>(out.halo[i])});
  }
  std::sort(got.begin(), got.end());
  const std::vector<std::vector<Real>> want = {
      {0, 0.05f, -0.02f, 0.2f, -2, 3, 2 + 2},  // mirrored in y
      {0, 1.05f, -0.02f, 0.2f, -2, 3, 2 + 2},  // periodic in x and mirrored in y
      {0, 1.05f, 0.02f, 0.2f, 2, 3, 2},        // periodic in x
      {2, -0.03f, 0.25f, 0.38f, 2, 3, 2},      // periodic in x
      {2, -0.03f, 0.25f, 0.42f, 2, -3, 2 + 4}, // periodic in x and mirrored in z
      {2, 0.97f, 0.25f, 0.42f, 2, -3, 2 + 4}}; // mirrored in z
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k)
    for (std::size_t c = 0; c < want[k].size(); ++c) EXPECT_NEAR(got[k][c], want[k][c], 1e-6) << k << " " << c;
}

TEST(Damping, FactorIsDualSphysicsLaw) {
  sph::DampingZone z; // a zone from x = 2 to the face x = 3, rate 10/s
  z.axis = 0;
  z.inner = 2;
  z.length = 1;
  z.rate = 10;
  const Real dt = 1e-3f;
  EXPECT_EQ(z.factor(Vec3{1.5f, 0, 0}, dt), 1); // before the zone
  EXPECT_EQ(z.factor(Vec3{2.0f, 0, 0}, dt), 1); // its inner edge
  EXPECT_FLOAT_EQ(z.factor(Vec3{2.5f, 0, 0}, dt), 1 - dt * 10 * 0.25f);
  EXPECT_FLOAT_EQ(z.factor(Vec3{3.0f, 0, 0}, dt), 1 - dt * 10);
  EXPECT_FLOAT_EQ(z.factor(Vec3{3.2f, 0, 0}, dt), 1 - dt * 10); // beyond the face: full rate
  EXPECT_EQ(z.factor(Vec3{3.0f, 0, 0}, Real(0.2)), 0);          // never reversed
  // A zone at a face lo (x = 0, 0.5 deep): the length is negative.
  sph::DampingZone lo{0, 0.5f, -0.5f, 10};
  EXPECT_FLOAT_EQ(lo.factor(Vec3{0.25f, 0, 0}, dt), 1 - dt * 10 * 0.25f);
  EXPECT_EQ(lo.factor(Vec3{0.6f, 0, 0}, dt), 1);
  sph::DampingZones both;
  both.zone[both.n++] = z;
  both.zone[both.n++] = lo;
  EXPECT_FLOAT_EQ(both.factor(Vec3{2.5f, 0, 0}, dt), 1 - dt * 10 * 0.25f);
}
