// The one bond filter (peridynamics/bond_filter.hpp, THEORY §4): the reach,
// c_bond with the plain cut-off, a cut removing only pairs that would be
// bonds (so `gc` counts the cut bonds the assembly leaves out), and the
// partial-volume reach.

#include "perimorph/peridynamics/bond_filter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace perimorph {
namespace {

using peridynamics::Micromodulus;

Micromodulus constant_kernel(double delta) {
  Micromodulus c;
  c.horizon = delta;
  c.scale = 3.0;
  return c;
}

TEST(BondFilter, ReachIsTheOpenHorizonOrThePartialVolumeOuterRadius) {
  EXPECT_EQ(peridynamics::bond_reach_squared(2.0, false, 0.5), peridynamics::horizon_cutoff_squared(2.0));
  EXPECT_LT(peridynamics::horizon_cutoff_squared(2.0), 4.0);
  EXPECT_EQ(peridynamics::bond_reach_squared(2.0, true, 0.5), 6.25);
  EXPECT_FALSE(peridynamics::within_reach(0.0, 1.0));
  EXPECT_TRUE(peridynamics::within_reach(0.5, 1.0));
  EXPECT_FALSE(peridynamics::within_reach(1.0, 1.0));
}

TEST(BondFilter, CutOffBondHasTheKernelsMicromodulus) {
  const Micromodulus c = constant_kernel(1.0);
  const Vec3 a(0.0, 0.0, 0.0), b(0.6, 0.0, 0.0);
  const Vec3 xi = b - a;
  const auto bond = peridynamics::pair_bond<2>(c, a, b, xi, xi.squaredNorm(), nullptr, nullptr, {});
  EXPECT_EQ(bond.c_bond, c.bond(xi, xi.norm()));
  EXPECT_FALSE(bond.cut);
  // Exactly δ apart (within the relative tie): no bond, and not counted as cut.
  const Vec3 far(1.0, 0.0, 0.0);
  const auto none = peridynamics::pair_bond<2>(c, a, far, far - a, 1.0, nullptr, nullptr, {});
  EXPECT_EQ(none.c_bond, 0.0);
  EXPECT_FALSE(none.cut);
}

TEST(BondFilter, CutRemovesOnlyPairsThatWouldBeBonds) {
  const Micromodulus c = constant_kernel(1.0);
  // The segment x = 0.3, 0 ≤ y ≤ 1 (2D).
  const std::vector<Cut> cuts{Cut{2, Vec3(0.3, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), Vec3::Zero()}};
  const Vec3 a(0.0, 0.5, 0.0), b(0.6, 0.5, 0.0);
  auto bond = peridynamics::pair_bond<2>(c, a, b, b - a, (b - a).squaredNorm(), nullptr, nullptr, cuts);
  EXPECT_EQ(bond.c_bond, 0.0);
  EXPECT_TRUE(bond.cut);
  // Beyond the horizon and across the cut: no bond, not a cut bond.
  const Vec3 far(1.2, 0.5, 0.0);
  bond = peridynamics::pair_bond<2>(c, a, far, far - a, (far - a).squaredNorm(), nullptr, nullptr, cuts);
  EXPECT_EQ(bond.c_bond, 0.0);
  EXPECT_FALSE(bond.cut);
  // Past the cut's end: a bond.
  const Vec3 c0(0.0, 1.5, 0.0), c1(0.6, 1.5, 0.0);
  bond = peridynamics::pair_bond<2>(c, c0, c1, c1 - c0, (c1 - c0).squaredNorm(), nullptr, nullptr, cuts);
  EXPECT_GT(bond.c_bond, 0.0);
  EXPECT_FALSE(bond.cut);
}

}  // namespace
}  // namespace perimorph
