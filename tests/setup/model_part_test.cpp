// The part of a model a process builds (setup/discretization.hpp, ModelPart;
// issue 17, item 1): the morphed C only of the cells near its part
// (partition::cells_near_part), bit for bit the whole model's there, NaN
// elsewhere (0 on purely non-local cells); the graph rows of those cells and
// the non-local points of the cells those rows reach, bit for bit the whole
// model's; the CG/DG flags and the dofs are the whole model's, so every
// process numbers the dofs alike. The cells near a part hold every cell whose local
// stiffness it assembles (touching a dof node it owns: dof_layout), whatever α
// makes CG or DG, and its own cells (output, damage); a rebuild for a grown α
// keeps the part.

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/nonlocal_setup.hpp"
#include "support/model_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>

namespace perimorph {
namespace {

bool bitwise_equal(const double* a, const double* b, int n) {
  return std::memcmp(a, b, static_cast<std::size_t>(n) * sizeof(double)) == 0;
}

/// The part's non-local points: those of the computed cells and of every
/// cell in their graph rows, the whole model's bit for bit; the per-cell α
/// bounds of every cell; a point not stored recomputed to the stored bits.
void expect_points_of(const setup::Discretization& part, const setup::Discretization& whole) {
  const auto& pp = part.nonlocal->points;
  const auto& wp = whole.nonlocal->points;
  EXPECT_TRUE(wp.holds_every_cell());
  EXPECT_EQ(pp.cell_alpha_min, wp.cell_alpha_min);
  EXPECT_EQ(pp.cell_alpha_max, wp.cell_alpha_max);
  EXPECT_EQ(pp.half_bound, wp.half_bound);
  const std::vector<char> read = whole.nonlocal->graph.cells_in_rows(part.computed_cells);
  const auto bits = [](const Vec3& a, const Vec3& b) {
    return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0;
  };
  for (Index c = 0; c < whole.mesh.num_cells(); ++c) {
    ASSERT_EQ(pp.holds(c), read[static_cast<std::size_t>(c)] != 0) << "cell " << c;
    for (int q = 0; q < pp.per_cell; ++q) {
      const std::size_t w = wp.index(c, q);
      EXPECT_TRUE(bits(bonds::point_position(part.mesh, pp, c, q), wp.x[w]))
          << "cell " << c << " point " << q;
      if (!pp.holds(c)) continue;
      const std::size_t k = pp.index(c, q);
      EXPECT_TRUE(bitwise_equal(&pp.weight[k], &wp.weight[w], 1) &&
                  bitwise_equal(&pp.alpha[k], &wp.alpha[w], 1))
          << "cell " << c << " point " << q;
      if (wp.partial_volume()) {
        EXPECT_TRUE(bits(pp.half[k], wp.half[w])) << "cell " << c << " point " << q;
      }
    }
  }
}

/// `part` against `whole`: the same flags, α, dofs and graph; the same C on
/// every computed cell; NaN or 0 (purely non-local) elsewhere. Returns the
/// number of cells left NaN.
Index expect_part_of(const setup::Discretization& part, const setup::Discretization& whole) {
  const auto& pm = part.nonlocal->morph;
  const auto& wm = whole.nonlocal->morph;
  EXPECT_EQ(pm.purely_nonlocal, wm.purely_nonlocal);
  // The graph rows of the computed cells, the others empty.
  const bonds::CellGraph rows = whole.nonlocal->graph.rows_of(part.computed_cells);
  EXPECT_EQ(part.nonlocal->graph.offsets, rows.offsets);
  EXPECT_EQ(part.nonlocal->graph.neighbors, rows.neighbors);
  if (!whole.nonlocal->graph.neighbors.empty()) {  // (the flagship starts with α = 0: no pair)
    EXPECT_LT(part.nonlocal->graph.neighbors.size(), whole.nonlocal->graph.neighbors.size());
  }
  expect_points_of(part, whole);
  EXPECT_EQ(part.dofmap.num_nodes(), whole.dofmap.num_nodes());
  const int nv2 = part.stiffness.voigt() * part.stiffness.voigt();
  Index absent = 0;
  for (Index c = 0; c < whole.mesh.num_cells(); ++c) {
    const auto pn = part.dofmap.cell_nodes(c), wn = whole.dofmap.cell_nodes(c);
    EXPECT_TRUE(std::equal(pn.begin(), pn.end(), wn.begin(), wn.end())) << "cell " << c;
    const bool computed = part.computed_cells[static_cast<std::size_t>(c)] != 0;
    bool nan = false;
    for (int q = 0; q < part.stiffness.points_per_cell(); ++q) {
      const double* C = part.stiffness.at(c, q);
      if (computed || wm.purely_nonlocal[static_cast<std::size_t>(c)]) {
        EXPECT_TRUE(bitwise_equal(C, whole.stiffness.at(c, q), nv2)) << "cell " << c << " point " << q;
      } else {
        EXPECT_TRUE(std::isnan(C[0])) << "cell " << c << " point " << q;
        nan = true;
      }
    }
    absent += nan ? 1 : 0;
  }
  return absent;
}

TEST(ModelPart, APartComputesTheCellsItAssemblesBitForBitAndNoOthers) {
  for (const auto& [name, config] : testing::model_part_cases()) {
    SCOPED_TRACE(name);
    const auto whole = setup::build_discretization(config);
    ASSERT_TRUE(whole.computed_cells.empty());
    ASSERT_TRUE(whole.nonlocal.has_value());
    EXPECT_TRUE(setup::build_discretization(config, {}, {1, 0}).computed_cells.empty());
    const Index ncells = whole.mesh.num_cells();
    for (int parts : {2, 3, 4}) {
      SCOPED_TRACE(parts);
      const auto p = partition::coordinate_bisection(whole.mesh, parts);
      const auto layout = partition::dof_layout(whole.dofmap, p, whole.nonlocal->graph);
      Index computed_total = 0;
      testing::SharedFlags flags{&whole.nonlocal->morph.purely_nonlocal, {}};
      for (int q = 0; q < parts; ++q) {
        const auto part = setup::build_discretization(config, {}, {parts, q, flags.share()});
        ASSERT_EQ(part.computed_cells.size(), static_cast<std::size_t>(ncells));
        const Index absent = expect_part_of(part, whole);
        EXPECT_GT(absent, 0) << "part " << q << " computed every cell's C";
        const auto touching = partition::cells_touching(
            whole.dofmap, [&](Index n) { return layout.node_owner[static_cast<std::size_t>(n)] == q; });
        for (Index c = 0; c < ncells; ++c) {
          const auto k = static_cast<std::size_t>(c);
          computed_total += part.computed_cells[k] != 0;
          EXPECT_TRUE(part.computed_cells[k] || (!touching[k] && p.owner[k] != q))
              << "part " << q << " assembles or owns cell " << c << " without its C";
        }
      }
      // Every flag is decided by the part that computes its cell.
      EXPECT_EQ(flags.over_parts, whole.nonlocal->morph.purely_nonlocal);
      // Near a boundary cells are computed twice, but not every cell on every part.
      EXPECT_GE(computed_total, ncells);
      EXPECT_LT(computed_total, static_cast<Index>(parts) * ncells);
      std::printf("%s, %d parts: %.2f× the cells of one process computed in all\n", name.c_str(), parts,
                  static_cast<double>(computed_total) / static_cast<double>(ncells));
    }
  }
}

TEST(ModelPart, ARebuildForAGrownAlphaKeepsThePart) {
  const auto config = testing::mixed_cg_dg_plate();
  const auto whole = setup::build_discretization(config);
  auto wide = config;
  wide.alpha.regions.front().radius += 1.5;
  const auto grown = setup::make_alpha_field(wide);
  const auto rebuilt_whole = setup::rebuild_for_alpha(whole, grown);
  testing::SharedFlags flags{&whole.nonlocal->morph.purely_nonlocal, {}};
  const auto part = setup::build_discretization(config, {}, {3, 1, flags.share()});
  flags.whole = &rebuilt_whole.nonlocal->morph.purely_nonlocal;  // the rebuild shares the grown model's
  flags.over_parts.clear();
  const auto rebuilt_part = setup::rebuild_for_alpha(part, grown);
  EXPECT_FALSE(flags.over_parts.empty()) << "the rebuild did not share its flags";
  EXPECT_EQ(rebuilt_part.computed_cells, part.computed_cells);
  EXPECT_GT(expect_part_of(rebuilt_part, rebuilt_whole), 0);
  // The grown α changed some cell's flags: the rebuild is not the old model.
  EXPECT_NE(rebuilt_whole.nonlocal->morph.purely_nonlocal, whole.nonlocal->morph.purely_nonlocal);
}

// What a process of a distributed run brings of the displacement after each
// solve (setup::nodes_read): the nodes of the cells its stretch pass reaches
// (its own cells and their graph neighbours), of the cells it writes and
// strains, and every node it owns; not the whole model's.
TEST(ModelPart, APartReadsTheDisplacementOfItsHaloOnly) {
  for (const auto& [name, config] : testing::model_part_cases()) {
    SCOPED_TRACE(name);
    const auto whole = setup::build_discretization(config);
    const Index nodes = whole.dofmap.num_nodes();
    const std::vector<Index> all = setup::nodes_read(whole);
    ASSERT_EQ(static_cast<Index>(all.size()), nodes);
    for (Index n = 0; n < nodes; ++n) ASSERT_EQ(all[static_cast<std::size_t>(n)], n);
    for (int parts : {2, 4}) {
      SCOPED_TRACE(parts);
      const auto p = partition::coordinate_bisection(whole.mesh, parts);
      const auto layout = partition::dof_layout(whole.dofmap, p, whole.nonlocal->graph);
      std::size_t total = 0;
      for (int q = 0; q < parts; ++q) {
        testing::SharedFlags flags{&whole.nonlocal->morph.purely_nonlocal, {}};
        const auto part = setup::build_discretization(config, {}, {parts, q, flags.share()});
        const std::vector<Index> read = setup::nodes_read(part);
        ASSERT_TRUE(std::is_sorted(read.begin(), read.end()));
        std::vector<char> is_read(static_cast<std::size_t>(nodes), 0);
        for (Index n : read) is_read[static_cast<std::size_t>(n)] = 1;
        const auto expect_read = [&](Index c, const char* why) {
          for (Index n : whole.dofmap.cell_nodes(c))
            ASSERT_TRUE(is_read[static_cast<std::size_t>(n)])
                << "part " << q << ": node " << n << " of cell " << c << " (" << why << ")";
        };
        const auto& graph = whole.nonlocal->graph;
        for (Index c = 0; c < whole.mesh.num_cells(); ++c) {
          if (p.owner[static_cast<std::size_t>(c)] != q) continue;
          expect_read(c, "its own");
          for (Index f : graph.row(c)) expect_read(f, "a bond of its own cell");
        }
        for (Index n = 0; n < nodes; ++n) {
          if (layout.node_owner[static_cast<std::size_t>(n)] == q) {
            EXPECT_TRUE(is_read[static_cast<std::size_t>(n)]) << "owned node " << n;
          }
        }
        total += read.size();
      }
      // The 3D ball's horizon (1.0 on 6 cells of 1.0 with a ball of α) spans
      // the block: each part reads it all. The others are wider than a horizon.
      if (name.rfind("3D ball", 0) != 0) {
        EXPECT_LT(total, static_cast<std::size_t>(parts * nodes)) << "every part reads every node";
      }
      std::printf("%s, %d parts: each part reads %.2f of the nodes on average\n", name.c_str(), parts,
                  static_cast<double>(total) / (parts * static_cast<double>(nodes)));
    }
  }
}

}  // namespace
}  // namespace perimorph
