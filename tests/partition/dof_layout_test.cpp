// The dofs over parts (partition/dof_layout.hpp): each part's owned nodes are
// contiguous in serial order, shared CG nodes go to the lowest part, DG nodes
// to their cell's part, the ghosts are exactly the other parts' nodes its rows
// couple to, and each part's owned rows of what it computes (owner computes)
// are the serial matrix's rows bit for bit.

#include "perimorph/partition/dof_layout.hpp"

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <set>

namespace perimorph {
namespace {

setup::Discretization mixed_plate() {
  return setup::build_discretization(testing::mixed_cg_dg_plate());
}

TEST(DofLayout, OnePartIsTheSerialNumbering) {
  const auto m = mixed_plate();
  const auto p = partition::coordinate_bisection(m.mesh, 1);
  const auto layout = partition::dof_layout(m.dofmap, p, m.nonlocal->graph);
  for (Index n = 0; n < m.dofmap.num_nodes(); ++n)
    EXPECT_EQ(layout.to_distributed[static_cast<std::size_t>(n)], n);
  EXPECT_EQ(layout.owned_nodes(0), m.dofmap.num_nodes());
  EXPECT_TRUE(layout.ghosts[0].empty());
}

TEST(DofLayout, OwnersNumberingAndGhostsEqualABruteForceCount) {
  const auto m = mixed_plate();
  const auto& graph = m.nonlocal->graph;
  bool some_dg = false, some_cg = false;
  for (Index c = 0; c < m.dofmap.num_cells(); ++c)
    (m.dofmap.continuity(c) == dofs::Continuity::continuous ? some_cg : some_dg) = true;
  ASSERT_TRUE(some_cg && some_dg) << "the plate must mix CG and DG cells";
  for (int parts : {2, 3, 4}) {
    SCOPED_TRACE(parts);
    const auto p = partition::coordinate_bisection(m.mesh, parts);
    const auto layout = partition::dof_layout(m.dofmap, p, graph);
    const auto nodes = static_cast<std::size_t>(m.dofmap.num_nodes());
    // Owners: the lowest part among the cells of a node.
    std::vector<int> owner(nodes, parts);
    for (Index c = 0; c < m.dofmap.num_cells(); ++c)
      for (Index n : m.dofmap.cell_nodes(c))
        owner[static_cast<std::size_t>(n)] =
            std::min(owner[static_cast<std::size_t>(n)], p.owner[static_cast<std::size_t>(c)]);
    EXPECT_EQ(layout.node_owner, owner);
    // Numbering: a permutation; part q's nodes in [offset q, offset q+1), serial order kept.
    std::vector<Index> seen(nodes, -1);
    for (std::size_t n = 0; n < nodes; ++n) {
      const Index d = layout.to_distributed[n];
      ASSERT_GE(d, layout.part_offsets[static_cast<std::size_t>(owner[n])]);
      ASSERT_LT(d, layout.part_offsets[static_cast<std::size_t>(owner[n]) + 1]);
      ASSERT_EQ(seen[static_cast<std::size_t>(d)], -1);
      seen[static_cast<std::size_t>(d)] = static_cast<Index>(n);
    }
    for (std::size_t d = 1; d < nodes; ++d) {
      if (owner[static_cast<std::size_t>(seen[d])] == owner[static_cast<std::size_t>(seen[d - 1])]) {
        EXPECT_LT(seen[d - 1], seen[d]);
      }
    }
    // Ghosts: nodes owned elsewhere of the cells touching an owned node and of
    // their neighbours in the cell graph (brute force over the pairs).
    for (int q = 0; q < parts; ++q) {
      std::set<Index> ghosts;
      auto touches = [&](Index c) {
        for (Index n : m.dofmap.cell_nodes(c))
          if (owner[static_cast<std::size_t>(n)] == q) return true;
        return false;
      };
      auto visit = [&](Index c) {
        for (Index n : m.dofmap.cell_nodes(c))
          if (owner[static_cast<std::size_t>(n)] != q) ghosts.insert(n);
      };
      for (Index e = 0; e < m.dofmap.num_cells(); ++e)
        for (Index f : graph.row(e))
          if (touches(e) || touches(f)) {
            visit(e);
            visit(f);
          }
      EXPECT_EQ(layout.ghosts[static_cast<std::size_t>(q)], std::vector<Index>(ghosts.begin(), ghosts.end()))
          << q;
      EXPECT_FALSE(ghosts.empty()) << q;
    }
    EXPECT_GT(layout.ghost_ratio(), 0.0);
  }
}

TEST(DofLayout, OwnerComputesGivesTheSerialRowsBitForBit) {
  const auto m = mixed_plate();
  const auto n = m.dofmap.num_dofs();
  const int dim = m.dim();
  testing::DenseInserter serial(n);
  assembly::assemble_elasticity(m.local_space(), m.stiffness, serial);
  // The whole graph's answers to the two reductions of the translation cache
  // (NonlocalOptions::min_over_processes): its largest offset, each key's
  // first pair.
  std::vector<std::vector<long long>> whole;
  assembly::NonlocalOptions recording;
  recording.min_over_processes = [&](std::vector<long long> v) {
    whole.push_back(v);
    return v;
  };
  assembly::assemble_nonlocal(m.nonlocal_space(), serial, recording);
  ASSERT_EQ(whole.size(), 2u);
  std::vector<long long> first_over_parts(whole[1].size(), std::numeric_limits<long long>::max());
  bool later_first = false;  // a part whose first pair of a key is not the whole graph's
  const auto p = partition::coordinate_bisection(m.mesh, 3);
  const auto layout = partition::dof_layout(m.dofmap, p, m.nonlocal->graph);
  Eigen::MatrixXd rows = Eigen::MatrixXd::Constant(n, n, -1.0);
  std::size_t cells_computed = 0;
  for (int q = 0; q < 3; ++q) {
    const auto owns = [&](Index node) { return layout.node_owner[static_cast<std::size_t>(node)] == q; };
    const auto touching = partition::cells_touching(m.dofmap, owns);
    testing::DenseInserter part(n);
    assembly::assemble_elasticity(m.local_space(), m.stiffness, part,
                                  [&](Index c) { return touching[static_cast<std::size_t>(c)] != 0; });
    assembly::NonlocalOptions only_touching;
    // The reduction over the parts, simulated: the part's first pairs, no
    // earlier than the whole graph's, are kept for the minimum below, and the
    // whole graph's answer is given back.
    int call = 0;
    only_touching.min_over_processes = [&](std::vector<long long> v) {
      EXPECT_EQ(v.size(), whole[static_cast<std::size_t>(call)].size()) << q << " " << call;
      if (call == 1 && v.size() == first_over_parts.size())
        for (std::size_t k = 0; k < v.size(); ++k) {
          EXPECT_GE(v[k], whole[1][k]) << q << " " << k;
          later_first |= v[k] > whole[1][k] && v[k] != std::numeric_limits<long long>::max();
          first_over_parts[k] = std::min(first_over_parts[k], v[k]);
        }
      return whole[static_cast<std::size_t>(call++)];
    };
    // The pairs with a touching cell, from the touching cells' graph rows:
    // given those rows alone.
    only_touching.rows = touching;
    const bonds::CellGraph part_graph = m.nonlocal->graph.rows_of(touching);
    ASSERT_LT(part_graph.neighbors.size(), m.nonlocal->graph.neighbors.size());
    // The non-local points of the cells those rows reach alone, as a process
    // stores them; a cache representative of another part's is made again
    // from the mesh (NonlocalSpace::alpha).
    const bonds::NonlocalPoints part_points =
        bonds::make_nonlocal_points(m.mesh, m.config.nonlocal.quadrature, m.scale, m.nonlocal->alpha,
                                    m.nonlocal->points.partial_volume(), part_graph.cells_in_rows(touching));
    ASSERT_LT(part_points.stored.size(), static_cast<std::size_t>(m.mesh.num_cells()));
    assembly::NonlocalSpace part_space{m.mesh, m.dofmap, part_points, part_graph, m.nonlocal->kernel};
    part_space.alpha = &m.nonlocal->alpha;
    part_space.cuts = &m.nonlocal->cuts;
    assembly::assemble_nonlocal(part_space, part, only_touching);
    for (Index r = 0; r < n; ++r)
      if (owns(r / dim)) rows.row(r) = part.A.row(r);
    for (char t : touching) cells_computed += t != 0;
  }
  // Every key's first pair is some part's first; the cache is used, and the
  // reduction matters (a part alone would pick another pair).
  EXPECT_EQ(first_over_parts, whole[1]);
  EXPECT_GT(std::count_if(whole[1].begin(), whole[1].end(),
                          [](long long v) { return v != std::numeric_limits<long long>::max(); }),
            0);
  EXPECT_TRUE(later_first);
  // Every row from its owner, summed from the same blocks in the same order,
  // each process reading only the graph rows of the cells it assembles.
  EXPECT_TRUE((rows.array() == serial.A.array()).all())
      << "max difference " << (rows - serial.A).cwiseAbs().maxCoeff();
  // Cells touching two parts are computed on both.
  EXPECT_GT(cells_computed, static_cast<std::size_t>(m.dofmap.num_cells()));
}

}  // namespace
}  // namespace perimorph
