// The bisection of a box grid from its index ranges (partition/grid_bisection.hpp)
// gives every cell the part coordinate_bisection of the whole mesh gives it, on
// grids whose cuts fall inside slabs (parts that are not boxes), and each part's
// index bounds are its cells'.

#include "perimorph/partition/grid_bisection.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/partition/partition.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

struct Grid {
  int dim;
  std::array<Index, 3> cells;
  Vec3 lower, upper;
};

TEST(GridBisection, GivesEveryCellTheWholeMeshBisectionsPart) {
  const Grid grids[] = {
      {1, {17, 1, 1}, Vec3(0, 0, 0), Vec3(1, 0, 0)},
      {2, {7, 5, 1}, Vec3(0, 0, 0), Vec3(7, 5, 0)},
      {2, {9, 9, 1}, Vec3(-1, 0, 0), Vec3(1, 2, 0)},      // equal extents: the first axis
      {2, {13, 4, 1}, Vec3(0, 0, 0), Vec3(0.3, 1.7, 0)},  // the long axis is not the one with most cells
      {3, {7, 5, 3}, Vec3(0, 0, 0), Vec3(7, 5, 3)},
      {3, {6, 6, 6}, Vec3(0.1, -0.2, 0.3), Vec3(1.1, 0.8, 1.3)},
      {3, {5, 11, 4}, Vec3(0, 0, 0), Vec3(1, 1, 1)},
  };
  int compared = 0, partial_slabs = 0;
  for (const Grid& g : grids) {
    const mesh::Mesh m = mesh::make_box({g.dim, g.lower, g.upper, g.cells});
    for (int parts : {1, 2, 3, 4, 5, 7, 8, 11, 16}) {
      if (parts > m.num_cells()) continue;
      const partition::Partition whole = partition::coordinate_bisection(m, parts);
      const partition::GridBisection grid(*m.structure, g.dim, parts);
      for (Index c = 0; c < m.num_cells(); ++c)
        ASSERT_EQ(grid.owner(c), whole.owner[static_cast<std::size_t>(c)])
            << "dim " << g.dim << ", " << g.cells[0] << " x " << g.cells[1] << " x " << g.cells[2] << ", "
            << parts << " parts, cell " << c;
      for (int p = 0; p < parts; ++p) {
        std::array<Index, 3> lo{m.num_cells(), m.num_cells(), m.num_cells()}, hi{0, 0, 0};
        Index count = 0;
        for (Index c = 0; c < m.num_cells(); ++c) {
          if (whole.owner[static_cast<std::size_t>(c)] != p) continue;
          ++count;
          const auto ijk = m.structure->cell_ijk(c);
          for (std::size_t d = 0; d < 3; ++d) {
            lo[d] = std::min(lo[d], ijk[d]);
            hi[d] = std::max(hi[d], ijk[d] + 1);
          }
        }
        const auto [glo, ghi] = grid.bounds(p);
        EXPECT_EQ(glo, lo);
        EXPECT_EQ(ghi, hi);
        // A part that is not the box of its bounds: a cut inside a slab.
        if (count < (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])) ++partial_slabs;
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 50);
  EXPECT_GT(partial_slabs, 10);  // the cases cut inside slabs, not only between them
}

TEST(GridBisection, RefusesMorePartsThanCells) {
  const mesh::Mesh m = mesh::make_box({2, Vec3::Zero(), Vec3::Ones(), {2, 2, 1}});
  EXPECT_THROW(partition::GridBisection(*m.structure, 2, 5), InputError);
  EXPECT_THROW(partition::GridBisection(*m.structure, 2, 0), InputError);
}

}  // namespace
}  // namespace perimorph
