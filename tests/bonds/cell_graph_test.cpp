// The cell graph (bonds/cell_graph.hpp): complete (every cell pair with a
// point pair closer than the reach is in it, checked by brute force), sorted,
// symmetric, with the diagonal; the point boxes keep fewer bond-free pairs
// than the node boxes.

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/mesh/box.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>

namespace perimorph {
namespace {

/// Unordered cell pairs (E ≤ F) with at least one point pair closer than reach.
std::set<std::pair<Index, Index>> brute_force_pairs(const bonds::NonlocalPoints& p, double reach) {
  std::set<std::pair<Index, Index>> out;
  for (Index e = 0; e < p.num_cells(); ++e)
    for (Index f = e; f < p.num_cells(); ++f) {
      bool any = false;
      for (int g = 0; g < p.per_cell && !any; ++g)
        for (int h = 0; h < p.per_cell && !any; ++h)
          any = (p.x[p.index(f, h)] - p.x[p.index(e, g)]).norm() < reach;
      if (any) out.insert({e, f});
    }
  return out;
}

void check_structure(const bonds::CellGraph& g, Index ncells) {
  ASSERT_EQ(g.num_cells(), ncells);
  for (Index e = 0; e < ncells; ++e) {
    const auto row = g.row(e);
    EXPECT_TRUE(std::is_sorted(row.begin(), row.end()));
    EXPECT_TRUE(std::binary_search(row.begin(), row.end(), e)) << "cell " << e << " lacks itself";
    for (Index f : row) {
      const auto back = g.row(f);
      EXPECT_TRUE(std::binary_search(back.begin(), back.end(), e)) << e << "-" << f << " not symmetric";
    }
  }
}

TEST(BondsCellGraph, CompleteSymmetricAndTighterWithPointBoxes) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(::testing::Message() << dim << "D");
    mesh::BoxSpec spec;
    spec.dim = dim;
    spec.upper = Vec3(1.0, 0.8, 0.6);
    spec.cells = {10, 8, dim == 3 ? 6 : 1};
    const mesh::Mesh m = mesh::make_box(spec);
    const double h = 0.1, delta = 3.0 * h;
    const auto pts = bonds::make_nonlocal_points(m, 3, 1.0, alpha::AlphaField::constant(1.0));
    std::vector<Vec3> reference;
    for (const auto& q : fem::gauss_legendre(dim, 3)) reference.push_back(q.xi);
    const auto by_points = bonds::find_cell_neighbors(m, bonds::point_boxes(m, reference), delta);
    const auto by_nodes = bonds::find_cell_neighbors(m, delta);
    check_structure(by_points, m.num_cells());
    check_structure(by_nodes, m.num_cells());
    const auto truth = brute_force_pairs(pts, delta);
    for (const auto& [e, f] : truth) {
      const auto row = by_points.row(e);
      EXPECT_TRUE(std::binary_search(row.begin(), row.end(), f)) << "missing pair " << e << "-" << f;
    }
    std::printf("%dD, δ = 3h, 3 points: pairs with bonds %zu; graph pairs: point boxes %zu, node boxes %zu\n",
                dim, truth.size(), by_points.num_pairs(), by_nodes.num_pairs());
    EXPECT_LE(truth.size(), by_points.num_pairs());
    EXPECT_LT(by_points.num_pairs(), by_nodes.num_pairs());
  }
}

TEST(BondsCellGraph, KeepPredicateFilters) {
  mesh::BoxSpec spec;
  spec.dim = 2;
  spec.cells = {6, 6, 1};
  const mesh::Mesh m = mesh::make_box(spec);
  const auto g =
      bonds::find_cell_neighbors(m, 0.4, [](Index e, Index f) { return e % 2 == 0 && f % 2 == 0; });
  for (Index e = 0; e < m.num_cells(); ++e)
    for (Index f : g.row(e)) {
      if (f != e) {
        EXPECT_TRUE(e % 2 == 0 && f % 2 == 0) << e << "-" << f;
      }
    }
  EXPECT_GT(g.num_pairs(), static_cast<std::size_t>(m.num_cells()));
}

}  // namespace
}  // namespace perimorph
