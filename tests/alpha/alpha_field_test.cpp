// The morphing field α (THEORY §3.1): the three profiles, the distance to each
// shape (interval, slab with a tilted normal, ball in 2D and 3D, cylinder, box
// with infinite bounds), α = 1 inside, profile(1 − d/L) in the transition, 0
// beyond it, the union of regions as a pointwise max, and constant fields.

#include "perimorph/alpha/alpha_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace perimorph {
namespace {

using alpha::AlphaField;
using alpha::Profile;
using alpha::Region;

constexpr double inf = std::numeric_limits<double>::infinity();

TEST(AlphaField, HeavisideJumpsAtOneHalf) {
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, 0.0), 0.0);
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, 0.49999999), 0.0);
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, std::nextafter(0.5, 0.0)), 0.0);
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, 0.5), 1.0);
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, 0.75), 1.0);
  EXPECT_EQ(alpha::profile_value(Profile::heaviside, 1.0), 1.0);
}

TEST(AlphaField, LinearAndCubicProfiles) {
  for (double t : {0.0, 0.1, 0.25, 0.5, 0.6, 0.9, 1.0}) {
    EXPECT_DOUBLE_EQ(alpha::profile_value(Profile::linear, t), t) << t;
    EXPECT_NEAR(alpha::profile_value(Profile::cubic, t), 3 * t * t - 2 * t * t * t, 1e-15) << t;
  }
  // The cubic has zero slope at both ends and is symmetric: α(1 − t) = 1 − α(t).
  const double e = 1e-6;
  EXPECT_LT(alpha::profile_value(Profile::cubic, e), 4 * e * e);
  EXPECT_GT(alpha::profile_value(Profile::cubic, 1 - e), 1 - 4 * e * e);
  for (double t : {0.1, 0.3, 0.45})
    EXPECT_NEAR(alpha::profile_value(Profile::cubic, 1 - t), 1 - alpha::profile_value(Profile::cubic, t),
                1e-15);
}

TEST(AlphaField, ProfilesClampOutsideTheUnitInterval) {
  for (Profile p : {Profile::heaviside, Profile::linear, Profile::cubic}) {
    EXPECT_EQ(alpha::profile_value(p, -0.3), 0.0);
    EXPECT_EQ(alpha::profile_value(p, -1e9), 0.0);
    EXPECT_EQ(alpha::profile_value(p, 1.4), 1.0);
    EXPECT_EQ(alpha::profile_value(p, 1e9), 1.0);
  }
}

TEST(AlphaField, IntervalDistance) {
  const alpha::Shape s = alpha::Interval{1.0, 3.0};
  EXPECT_DOUBLE_EQ(alpha::distance(s, Vec3(0.0, 0, 0), 1), 1.0);
  EXPECT_DOUBLE_EQ(alpha::distance(s, Vec3(4.5, 0, 0), 1), 1.5);
  EXPECT_EQ(alpha::distance(s, Vec3(1.0, 0, 0), 1), 0.0);
  EXPECT_EQ(alpha::distance(s, Vec3(2.0, 0, 0), 1), 0.0);
  EXPECT_EQ(alpha::distance(s, Vec3(3.0, 0, 0), 1), 0.0);
  // Only x counts in 1D.
  EXPECT_DOUBLE_EQ(alpha::distance(s, Vec3(4.5, 7.0, -2.0), 1), 1.5);
}

TEST(AlphaField, SlabWithTiltedNormal) {
  const Vec3 n = Vec3(3.0, 4.0, 0.0).normalized();
  const Vec3 tangent(-4.0, 3.0, 0.0);
  const Vec3 p(1.0, -2.0, 0.0);
  const alpha::Shape s = alpha::Slab{p, n, 0.5};
  for (double side : {1.0, -1.0}) {
    EXPECT_NEAR(alpha::distance(s, p + side * 0.8 * n + 2.0 * tangent, 2), 0.3, 1e-14) << side;
    EXPECT_EQ(alpha::distance(s, p + side * 0.4 * n - 3.0 * tangent, 2), 0.0) << side;
  }
  // In 3D the slab is a thick plane: z along it does not matter.
  EXPECT_NEAR(alpha::distance(s, p + 1.5 * n + Vec3(0, 0, 9.0), 3), 1.0, 1e-14);
  // A field normalizes the normal it is given: α at distance 0.3 with L = 1, linear, is 0.7.
  const AlphaField f =
      AlphaField::regions({Region{alpha::Slab{p, Vec3(3.0, 4.0, 0.0), 0.5}, 1.0, Profile::linear}}, 2);
  EXPECT_NEAR(f(p + 0.8 * n + tangent), 0.7, 1e-14);
  EXPECT_NEAR(f(p - 0.8 * n - tangent), 0.7, 1e-14);
}

TEST(AlphaField, BallIn2DAnd3D) {
  const alpha::Shape s = alpha::Ball{Vec3(1.0, 2.0, 7.0), 0.5};
  // 2D: the z of the centre and of the point are ignored.
  EXPECT_NEAR(alpha::distance(s, Vec3(1.0 + 3.0, 2.0 + 4.0, -3.0), 2), 4.5, 1e-14);
  EXPECT_EQ(alpha::distance(s, Vec3(1.2, 2.1, -3.0), 2), 0.0);
  // 3D: the full distance.
  EXPECT_NEAR(alpha::distance(s, Vec3(1.0 + 2.0, 2.0 + 3.0, 7.0 + 6.0), 3), 6.5, 1e-14);
  EXPECT_EQ(alpha::distance(s, Vec3(1.2, 2.1, 7.3), 3), 0.0);
  EXPECT_NEAR(alpha::distance(s, Vec3(1.2, 2.1, -3.0), 3), std::sqrt(0.04 + 0.01 + 100.0) - 0.5, 1e-13);
}

TEST(AlphaField, CylinderDistance) {
  // Axis along (1, 1, 1) through (1, 0, 0), radius 0.25.
  const Vec3 a = Vec3(1.0, 1.0, 1.0).normalized();
  const Vec3 radial = Vec3(1.0, -1.0, 0.0).normalized();  // ⊥ axis
  const alpha::Shape s = alpha::Cylinder{Vec3(1.0, 0.0, 0.0), a, 0.25};
  EXPECT_NEAR(alpha::distance(s, Vec3(1.0, 0.0, 0.0) + 5.0 * a + 1.25 * radial, 3), 1.0, 1e-14);
  EXPECT_NEAR(alpha::distance(s, Vec3(1.0, 0.0, 0.0) - 3.0 * a + 0.75 * radial, 3), 0.5, 1e-14);
  EXPECT_EQ(alpha::distance(s, Vec3(1.0, 0.0, 0.0) + 40.0 * a + 0.2 * radial, 3), 0.0);
  // A field normalizes the axis: the same cylinder given with axis (2, 2, 2).
  const AlphaField f = AlphaField::regions(
      {Region{alpha::Cylinder{Vec3(1.0, 0.0, 0.0), 2.0 * Vec3::Ones(), 0.25}, 2.0, Profile::linear}}, 3);
  EXPECT_NEAR(f(Vec3(1.0, 0.0, 0.0) + 5.0 * a + 1.25 * radial), 0.5, 1e-14);
}

TEST(AlphaField, BoxWithFiniteAndInfiniteBounds) {
  const alpha::Shape square = alpha::Box{Vec3(0.0, 0.0, -inf), Vec3(1.0, 1.0, inf)};
  EXPECT_NEAR(alpha::distance(square, Vec3(2.0, 3.0, 0.0), 2), std::sqrt(5.0), 1e-14);  // corner
  EXPECT_NEAR(alpha::distance(square, Vec3(0.5, -0.25, 0.0), 2), 0.25, 1e-15);          // face
  EXPECT_EQ(alpha::distance(square, Vec3(0.5, 0.5, 0.0), 2), 0.0);
  // A box finite in z is still a square in 2D (z ignored).
  const alpha::Shape cube = alpha::Box{Vec3(0.0, 0.0, 0.0), Vec3(1.0, 1.0, 1.0)};
  EXPECT_EQ(alpha::distance(cube, Vec3(0.5, 0.5, 50.0), 2), 0.0);
  EXPECT_NEAR(alpha::distance(cube, Vec3(2.0, 3.0, 3.0), 3), 3.0, 1e-14);
  // Half-space y ≤ 1 and slab 0 ≤ y ≤ 1 given by infinite bounds.
  alpha::Box half;
  half.upper = Vec3(inf, 1.0, inf);
  EXPECT_NEAR(alpha::distance(half, Vec3(-1e6, 3.0, 1e6), 3), 2.0, 1e-9);
  EXPECT_EQ(alpha::distance(half, Vec3(1e6, -1e6, 0.0), 3), 0.0);
  const alpha::Shape slab = alpha::Box{Vec3(-inf, 0.0, -inf), Vec3(inf, 1.0, inf)};
  EXPECT_NEAR(alpha::distance(slab, Vec3(100.0, -0.5, -50.0), 3), 0.5, 1e-14);
  EXPECT_NEAR(alpha::distance(slab, Vec3(100.0, 3.0, -50.0), 2), 2.0, 1e-14);
}

TEST(AlphaField, OneInsideProfileInTransitionZeroBeyond) {
  for (Profile p : {Profile::heaviside, Profile::linear, Profile::cubic}) {
    const AlphaField f = AlphaField::regions({Region{alpha::Ball{Vec3::Zero(), 1.0}, 2.0, p}}, 2);
    EXPECT_FALSE(f.is_constant());
    EXPECT_EQ(f(Vec3(0.0, 0.0, 0.0)), 1.0);
    EXPECT_EQ(f(Vec3(0.0, 1.0, 0.0)), 1.0);  // on the border: d = 0
    EXPECT_EQ(f(Vec3(-1.0, 0.0, 0.0)), 1.0);
    for (double d : {0.2, 0.9, 1.1, 1.7}) {
      const double expected = alpha::profile_value(p, 1.0 - d / 2.0);
      EXPECT_NEAR(f(Vec3(0.0, 1.0 + d, 0.0)), expected, 1e-14)
          << "profile " << static_cast<int>(p) << " d " << d;
    }
    EXPECT_EQ(f(Vec3(3.0, 0.0, 0.0)), 0.0);  // d = L exactly
    EXPECT_EQ(f(Vec3(0.0, -3.5, 0.0)), 0.0);
    EXPECT_EQ(f(Vec3(40.0, 0.0, 0.0)), 0.0);
  }
  // Explicit values: linear at d = L/4 is 3/4; cubic at mid-transition is 1/2; heaviside switches at d = L/2.
  const AlphaField lin = AlphaField::regions({Region{alpha::Interval{0.0, 1.0}, 2.0, Profile::linear}}, 1);
  EXPECT_DOUBLE_EQ(lin(Vec3(1.5, 0, 0)), 0.75);
  EXPECT_DOUBLE_EQ(lin(Vec3(-0.5, 0, 0)), 0.75);
  const AlphaField cub = AlphaField::regions({Region{alpha::Interval{0.0, 1.0}, 2.0, Profile::cubic}}, 1);
  EXPECT_DOUBLE_EQ(cub(Vec3(2.0, 0, 0)), 0.5);
  EXPECT_NEAR(cub(Vec3(1.5, 0, 0)), 3 * 0.5625 - 2 * 0.421875, 1e-15);
  const AlphaField hv = AlphaField::regions({Region{alpha::Interval{0.0, 1.0}, 2.0, Profile::heaviside}}, 1);
  EXPECT_EQ(hv(Vec3(1.99, 0, 0)), 1.0);
  EXPECT_EQ(hv(Vec3(2.01, 0, 0)), 0.0);
  // A sharp edge (L = 0): 1 inside, 0 just outside.
  const AlphaField sharp = AlphaField::regions({Region{alpha::Interval{0.0, 1.0}, 0.0, Profile::cubic}}, 1);
  EXPECT_EQ(sharp(Vec3(1.0, 0, 0)), 1.0);
  EXPECT_EQ(sharp(Vec3(1.0 + 1e-12, 0, 0)), 0.0);
}

TEST(AlphaField, UnionIsPointwiseMax) {
  const Region a{alpha::Ball{Vec3(0.0, 0.0, 0.0), 1.0}, 2.0, Profile::linear};
  const Region b{alpha::Ball{Vec3(3.0, 0.0, 0.0), 0.5}, 1.0, Profile::cubic};
  const AlphaField fa = AlphaField::regions({a}, 2), fb = AlphaField::regions({b}, 2);
  const AlphaField both = AlphaField::regions({a, b}, 2), reversed = AlphaField::regions({b, a}, 2);
  int overlapping = 0;
  for (double x = -4.0; x <= 6.0; x += 0.137)
    for (double y : {0.0, 0.3, -1.1}) {
      const Vec3 p(x, y, 0.0);
      EXPECT_EQ(both(p), std::max(fa(p), fb(p))) << x << " " << y;
      EXPECT_EQ(reversed(p), both(p));
      overlapping += fa(p) > 0.0 && fb(p) > 0.0 ? 1 : 0;
    }
  EXPECT_GT(overlapping, 0) << "the two transitions should overlap somewhere";
  // Inside either shape the union is 1.
  EXPECT_EQ(both(Vec3(3.1, 0.0, 0.0)), 1.0);
  EXPECT_EQ(both(Vec3(-0.5, 0.0, 0.0)), 1.0);
}

TEST(AlphaField, ConstantFields) {
  for (double v : {0.0, 0.3, 1.0}) {
    const AlphaField f = AlphaField::constant(v);
    EXPECT_TRUE(f.is_constant());
    EXPECT_EQ(f.constant_value(), v);
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1e3, -4.0, 2.0), Vec3(-1, 1, -1)}) EXPECT_EQ(f(p), v);
  }
  // No regions: α ≡ 0 (and the field counts as constant).
  const AlphaField empty = AlphaField::regions({}, 3);
  EXPECT_TRUE(empty.is_constant());
  EXPECT_EQ(empty(Vec3(1, 2, 3)), 0.0);
}

}  // namespace
}  // namespace perimorph
