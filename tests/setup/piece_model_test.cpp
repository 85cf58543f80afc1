// A process's piece of a model (setup/piece_model.hpp; issue 17, item 1),
// every part of 2 and 3 played in one process: the piece holds exactly the
// cells its part reads (those whose C it computes and whose non-local points
// it stores), numbered in the global order, and each local cell carries its
// global cell's data bit for bit: C at every local point, α bounds and
// points, the graph row (renumbered), CG/DG flag, damage law. The dof nodes
// are owned once over the parts, as many as the whole model's. (The matrix
// assembled on the pieces: tests/mpi/piece_model_mpitest.cpp.)

#include "perimorph/setup/piece_model.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/model_cases.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

namespace perimorph {
namespace {

template <class T>
bool same_bits(const T* a, const T* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(T)) == 0;
}

/// Cell k of `piece` against global cell piece.piece->global_cell[k] of `part`.
void expect_cells_of(const setup::Discretization& piece, const setup::Discretization& part) {
  const auto& d = piece;
  const auto& pp = d.nonlocal->points;
  const auto& wp = part.nonlocal->points;
  const int nv2 = d.stiffness.voigt() * d.stiffness.voigt();
  for (Index k = 0; k < d.mesh.num_cells(); ++k) {
    const Index g = piece.piece->global_cell[static_cast<std::size_t>(k)];
    const auto gk = static_cast<std::size_t>(g), kk = static_cast<std::size_t>(k);
    for (int q = 0; q < d.stiffness.points_per_cell(); ++q)
      EXPECT_TRUE(same_bits(d.stiffness.at(k, q), part.stiffness.at(g, q), static_cast<std::size_t>(nv2)))
          << "cell " << g << " point " << q;
    EXPECT_EQ(d.computed_cells[kk], part.computed_cells[gk]) << "cell " << g;
    EXPECT_EQ(d.nonlocal->morph.purely_nonlocal[kk], part.nonlocal->morph.purely_nonlocal[gk]);
    EXPECT_EQ(d.dofmap.continuity(k), part.dofmap.continuity(g));
    EXPECT_EQ(d.dofmap.cell_nodes(k).size(), part.dofmap.cell_nodes(g).size());
    EXPECT_EQ(pp.cell_alpha_min[kk], wp.cell_alpha_min[gk]);
    EXPECT_EQ(pp.cell_alpha_max[kk], wp.cell_alpha_max[gk]);
    ASSERT_EQ(pp.holds(k), wp.holds(g)) << "cell " << g;
    if (pp.holds(k)) {
      const std::size_t a = pp.index(k, 0), b = wp.index(g, 0);
      const auto n = static_cast<std::size_t>(pp.per_cell);
      EXPECT_TRUE(same_bits(pp.x[a].data(), wp.x[b].data(), 3 * n) &&
                  same_bits(&pp.weight[a], &wp.weight[b], n) && same_bits(&pp.alpha[a], &wp.alpha[b], n))
          << "cell " << g;
      if (wp.partial_volume()) {
        EXPECT_TRUE(same_bits(pp.half[a].data(), wp.half[b].data(), 3 * n)) << "cell " << g;
      }
    }
    std::vector<Index> row;
    for (Index f : d.nonlocal->graph.row(k))
      row.push_back(piece.piece->global_cell[static_cast<std::size_t>(f)]);
    const auto whole_row = part.nonlocal->graph.row(g);
    EXPECT_EQ(row, std::vector<Index>(whole_row.begin(), whole_row.end())) << "cell " << g;
    if (part.damage) {
      EXPECT_EQ(d.damage->law_of(k), part.damage->law_of(g));
    }
  }
}

TEST(PieceModel, HoldsTheCellsItsPartReadsWithTheirDataBitForBit) {
  for (const auto& [name, config] : testing::model_part_cases()) {
    SCOPED_TRACE(name);
    const auto whole = setup::build_discretization(config);
    const Index ncells = whole.mesh.num_cells();
    for (int parts : {2, 3}) {
      SCOPED_TRACE(parts);
      const auto p = partition::coordinate_bisection(whole.mesh, parts);
      testing::SharedFlags flags{&whole.nonlocal->morph.purely_nonlocal, {}};
      Index owned = 0, held = 0;
      for (int q = 0; q < parts; ++q) {
        const auto part = setup::build_discretization(config, {}, {parts, q, flags.share()});
        const auto piece = setup::cut_to_piece(part, p.owner, q, {});
        std::vector<Index> read;
        for (Index c = 0; c < ncells; ++c)
          if (part.computed_cells[static_cast<std::size_t>(c)] || part.nonlocal->points.holds(c))
            read.push_back(c);
        EXPECT_EQ(piece.piece->global_cell, read) << "part " << q;
        held += piece.mesh.num_cells();
        ASSERT_EQ(piece.mesh.num_cells(), static_cast<Index>(read.size()));
        for (std::size_t k = 0; k < read.size(); ++k)
          EXPECT_EQ(piece.piece->owner[k], p.owner[static_cast<std::size_t>(read[k])]);
        expect_cells_of(piece, part);
        owned += piece.piece->dofs.num_owned();
      }
      EXPECT_EQ(owned, whole.dofmap.num_nodes()) << "every dof node owned by one part";
      // (The 3D ball's bonds reach across it: each piece is the whole ball.)
      std::printf("%s, %d parts: the pieces hold %.2f× the cells of one process in all\n", name.c_str(),
                  parts, static_cast<double>(held) / static_cast<double>(ncells));
    }
  }
}

/// The whole model is its own piece: every cell, the whole dof map, all owned.
TEST(PieceModel, OfTheWholeModelIsTheWholeModel) {
  const auto config = testing::mixed_cg_dg_plate();
  const auto whole = setup::build_discretization(config);
  const std::vector<int> owner(static_cast<std::size_t>(whole.mesh.num_cells()), 0);
  const auto piece = setup::cut_to_piece(whole, owner, 0, {});
  EXPECT_EQ(piece.mesh.num_cells(), whole.mesh.num_cells());
  EXPECT_EQ(piece.dofmap.num_nodes(), whole.dofmap.num_nodes());
  EXPECT_EQ(piece.piece->dofs.num_owned(), whole.dofmap.num_nodes());
  EXPECT_TRUE(piece.nonlocal->points.holds_every_cell());
  EXPECT_EQ(piece.nonlocal->graph.neighbors, whole.nonlocal->graph.neighbors);
}

}  // namespace
}  // namespace perimorph
