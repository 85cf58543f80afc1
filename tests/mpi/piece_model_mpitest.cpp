// A process's piece of a model (setup::cut_to_piece; issue 17, item 1) under
// mpiexec -n 1, 2 and 3: each process builds its part of the model
// (build_discretization with a ModelPart, as a run does), cuts it to the
// cells it reads, numbers the piece's dof nodes from the piece alone
// (system::piece_distribution) and assembles the hybrid stiffness on the
// piece. Its rows must be the whole model's distributed matrix's, bit for
// bit: local and non-local blocks, the translation cache's blocks from pairs
// of box cells the piece may not hold, cuts and holes. The case solved on
// the pieces (supports and loads from the piece's sets, u held at the
// piece's nodes) gives the whole model's u.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/model_cases.hpp"
#include "support/owned_rows.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

namespace perimorph {
namespace {

using testing::owned_rows;
using testing::Rows;

TEST(PieceModel, AssemblesTheWholeModelsRowsBitForBit) {
  for (const auto& [name, config] : testing::model_part_cases()) {
    SCOPED_TRACE(name);
    const setup::Discretization part = run::process_part(config);
    const auto p = partition::coordinate_bisection(part.mesh, la::world_size());
    const setup::Discretization piece =
        setup::cut_to_piece(part, p.owner, la::world_rank(), la::any_over_processes);
    EXPECT_EQ(piece.mesh.num_cells(), static_cast<Index>(piece.piece->global_cell.size()));

    const auto whole = system::assemble_stiffness(
        part, la::world_size() > 1 ? system::distribution_over_processes(part)
                                   : system::distribution_of(partition::dof_numbering(part.dofmap, p), 0));
    const auto mine = system::assemble_stiffness(piece, system::piece_distribution(piece.piece->dofs));
    const Rows expected = owned_rows(whole.K), got = owned_rows(mine.K);
    ASSERT_FALSE(expected.empty());
    EXPECT_TRUE(got == expected) << "process " << la::world_rank() << " of " << la::world_size();
    // The same pairs, bonds and cached blocks.
    EXPECT_EQ(mine.nonlocal.cell_pairs, whole.nonlocal.cell_pairs);
    EXPECT_EQ(mine.nonlocal.bonds, whole.nonlocal.bonds);
    EXPECT_EQ(mine.nonlocal.reused_pairs, whole.nonlocal.reused_pairs);
    EXPECT_EQ(mine.nonlocal.distinct_blocks, whole.nonlocal.distinct_blocks);
  }
}

/// u solved at load factor 1 by the case's solver on `model` spread by
/// `distribution`, at every dof node of the distribution (collective).
std::vector<double> solved(const setup::Discretization& model,
                           const std::shared_ptr<const la::Distribution>& distribution) {
  system::ConstrainedSystem system(model, system::assemble_stiffness(model, distribution).K,
                                   setup::build_dirichlet(model), setup::build_external_force(model));
  system.attach_solver();
  la::Vector u = system.make_vector();
  (void)system.solve(1.0, u);  // throws SolverError if it fails
  return la::NodeGather(distribution, model.dim(), {}).gathered(u, std::nan(""));
}

TEST(PieceModel, SolvesTheCaseAsTheWholeModelHoldingUAtItsNodesOnly) {
  for (const auto& [name, config] : testing::loaded_model_cases()) {
    SCOPED_TRACE(name);
    const setup::Discretization part = run::process_part(config);
    const auto p = partition::coordinate_bisection(part.mesh, la::world_size());
    const setup::Discretization piece =
        setup::cut_to_piece(part, p.owner, la::world_rank(), la::any_over_processes);
    const auto expected = solved(
        part, la::world_size() > 1 ? system::distribution_over_processes(part)
                                   : system::distribution_of(partition::dof_numbering(part.dofmap, p), 0));
    const auto got = solved(piece, system::piece_distribution(piece.piece->dofs));
    const int bs = part.dim();
    ASSERT_EQ(got.size(), static_cast<std::size_t>(piece.dofmap.num_dofs())) << "u as long as the piece";
    // The same matrix, right-hand side and numbering: the same bits on 1 and
    // 2 processes; from 3, an iterative solver's preconditioner may sum other
    // processes' messages in arrival order (distributed-runs.md), so within
    // round-off.
    double largest = 0.0, diff = 0.0;
    for (Index c = 0; c < piece.mesh.num_cells(); ++c) {
      const auto nodes = piece.dofmap.cell_nodes(c);
      const auto whole_nodes = part.dofmap.cell_nodes(piece.piece->global_cell[static_cast<std::size_t>(c)]);
      for (std::size_t a = 0; a < nodes.size(); ++a)
        for (int k = 0; k < bs; ++k) {
          const double mine = got[static_cast<std::size_t>(nodes[a] * bs + k)];
          const double theirs = expected[static_cast<std::size_t>(whole_nodes[a] * bs + k)];
          if (la::world_size() <= 2) {
            EXPECT_EQ(std::memcmp(&mine, &theirs, sizeof(double)), 0) << mine << " against " << theirs;
          }
          diff = std::max(diff, std::abs(mine - theirs));
          largest = std::max(largest, std::abs(theirs));
        }
    }
    EXPECT_GT(largest, 0.0);
    EXPECT_LE(diff, 1e-12 * largest) << "process " << la::world_rank() << " of " << la::world_size();
  }
}

/// A boundary condition's set may miss a piece and reach another's; one that
/// reaches no dof on any process is the case error of the whole model, on
/// every process (collective: none waits for another).
TEST(PieceModel, ASetMayMissAPieceButNotEveryPiece) {
  const auto config = testing::loaded_model_cases().back().config;  // the mixed plate pulled along x
  const setup::Discretization part = run::process_part(config);
  const auto p = partition::coordinate_bisection(part.mesh, la::world_size());
  setup::Discretization piece = setup::cut_to_piece(part, p.owner, la::world_rank(), la::any_over_processes);
  const bool mine = !piece.mesh.node_sets.at("xmax").empty();
  EXPECT_TRUE(la::any_over_processes(mine));
  const bool everywhere = la::min_over_processes({mine ? 1LL : 0LL}).front() == 1;  // (collective)
  if (la::world_size() > 1) {
    EXPECT_FALSE(everywhere) << "every piece reaches xmax";
  }
  EXPECT_EQ(setup::set_dof_nodes(piece, "xmax", {}).empty(), !mine);
  piece.mesh.node_sets["nowhere"] = {};
  EXPECT_THROW((void)setup::set_dof_nodes(piece, "nowhere", {}), InputError);
}

/// A run with [adaptivity] keeps its part less the arrays a rebuild makes
/// anew (setup::keep_source); the piece rebuilt from it for a grown α is the
/// piece cut from the whole part rebuilt for that α: the same cells and the
/// same matrix rows, bit for bit.
TEST(PieceModel, ARebuildFromTheKeptSourceIsTheCutOfTheRebuiltPart) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process runs on the whole model";
  const auto config =
      casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) + "/examples/hole_plate_2d/case.toml");
  ASSERT_TRUE(config.adaptivity.enabled);
  const setup::Discretization piece = run::process_model(config);
  ASSERT_TRUE(piece.source != nullptr);
  const setup::Discretization& kept = piece.source->part;
  EXPECT_EQ(kept.stiffness.num_cells(), 0);
  EXPECT_EQ(kept.nonlocal->points.num_cells(), 0);
  EXPECT_EQ(kept.nonlocal->graph.num_cells(), -1);
  EXPECT_TRUE(kept.nonlocal->morph.purely_nonlocal.empty());
  const setup::Discretization part = run::process_part(config);
  EXPECT_EQ(kept.dofmap.num_dofs(), part.dofmap.num_dofs()) << "the state's numbering";
  // α = 1 in a disk across the hole's equator on the right (a ball the
  // predictor would place), reaching cells of both halves.
  const auto alpha = piece.nonlocal->alpha.grown({{alpha::Ball{Vec3(5.0, 4.0, 0.0), 1.0}, 0.5}}, 2);
  const setup::Discretization got = setup::rebuild_piece_for_alpha(piece, alpha);
  const setup::Discretization whole = setup::rebuild_for_alpha(part, alpha);
  const setup::Discretization expected =
      setup::cut_to_piece(whole, partition::coordinate_bisection(whole.mesh, la::world_size()).owner,
                          la::world_rank(), la::any_over_processes);
  EXPECT_GE(got.mesh.num_cells(), piece.mesh.num_cells());
  EXPECT_TRUE(la::any_over_processes(got.mesh.num_cells() > piece.mesh.num_cells())) << "a larger halo";
  EXPECT_EQ(got.piece->global_cell, expected.piece->global_cell);
  EXPECT_EQ(got.dofmap.num_dofs(), expected.dofmap.num_dofs());
  const Rows rows =
      owned_rows(system::assemble_stiffness(got, system::piece_distribution(got.piece->dofs)).K);
  ASSERT_FALSE(rows.empty());
  EXPECT_TRUE(
      rows ==
      owned_rows(system::assemble_stiffness(expected, system::piece_distribution(expected.piece->dofs)).K));
  // Rebuilt again from the new source.
  EXPECT_TRUE(got.source != nullptr && got.source->part.nonlocal->points.num_cells() == 0);
}

}  // namespace
}  // namespace perimorph
