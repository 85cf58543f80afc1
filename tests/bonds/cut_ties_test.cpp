// Bonds through the end of a pre-crack cut: the cut is closed (Cut::crosses),
// and the decision must not depend on the round-off of the crossing point.
// B6 (BENCHMARKS) ends its pre-crack at x = 4, where mirror-image bonds between
// the Gauss points of the cells meet it exactly; before the tie margin, half
// of them were kept and half removed, by the last bit of the crossing point.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace perimorph {
namespace {

/// Every pair of points (a below y = 4, b above, |b − a| ≤ δ = 1) whose exact
/// crossing of y = 4 (in long double) lies at x = 4 within 1e-13 is cut; in
/// 3D the block is [0, 12] × [0, 8] × [0, 2], the cut a plane through the
/// thickness.
void check_ties(int dim, double h, int& ties) {
  mesh::BoxSpec spec;
  spec.dim = dim;
  spec.upper = Vec3(12.0, 8.0, dim == 3 ? 2.0 : 0.0);
  spec.cells = {static_cast<Index>(std::lround(12.0 / h)), static_cast<Index>(std::lround(8.0 / h)),
                static_cast<Index>(dim == 3 ? std::lround(2.0 / h) : 1)};
  const mesh::Mesh m = mesh::make_box(spec);
  const auto pts = bonds::make_nonlocal_points(m, 2, 1.0, alpha::AlphaField::constant(1.0));
  Cut cut;
  cut.dim = dim;
  cut.origin = Vec3(0.0, 4.0, 0.0);
  cut.edge1 = Vec3(4.0, 0.0, 0.0);
  cut.edge2 = Vec3(0.0, 0.0, 2.0);
  const std::vector<Cut> cuts{cut};
  // Only points near the edge matter: x in (3, 5), y in (3, 5).
  std::vector<Vec3> near;
  for (const Vec3& x : pts.x)
    if (std::abs(x.x() - 4.0) < 1.0 && std::abs(x.y() - 4.0) < 1.0) near.push_back(x);
  for (const Vec3& a : near)
    for (const Vec3& b : near) {
      if (!(a.y() < 4.0 && b.y() > 4.0) || (b - a).squaredNorm() > 1.0) continue;
      const long double t = (4.0L - a.y()) / (static_cast<long double>(b.y()) - a.y());
      const long double x = a.x() + t * (static_cast<long double>(b.x()) - a.x());
      if (std::fabs(x - 4.0L) > 1e-13L) continue;
      ++ties;
      EXPECT_TRUE(peridynamics::bond_cut(a, b, cuts))
          << dim << "D, h " << h << ": " << a.transpose() << " to " << b.transpose();
      EXPECT_TRUE(peridynamics::bond_cut(b, a, cuts));
    }
}

TEST(BondsCutTies, BondsThroughTheCutEndAreCutWhateverTheRoundOff) {
  for (int dim : {2, 3})
    for (const double h : {1.0, 2.0 / 3.0, 0.5, 0.4}) {
      int ties = 0;
      check_ties(dim, h, ties);
      std::printf("%dD h = %.4g: %d bonds through the cut's end\n", dim, h, ties);
      EXPECT_GT(ties, 0) << dim << "D, h " << h;
    }
}

}  // namespace
}  // namespace perimorph
