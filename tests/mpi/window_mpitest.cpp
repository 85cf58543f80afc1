// A part built on the process's window of its box (issue 17, item 1;
// run::window_part) under mpiexec -n 1, 2 and 3: the CG/DG flags of the
// window's cells the process does not compute come from their owners by
// neighbour exchange (run::window_flags), and equal the whole model's; the
// model a run gets (run::process_model) is the piece cut from the part on the
// whole mesh, its matrix rows bit for bit.

#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/run/window_part.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/owned_rows.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

/// A long DG plate whose α = 1 disk at its left end is cut by the first
/// part boundary: purely non-local cells on both sides of it.
casefile::CaseConfig long_plate() {
  auto config = testing::box_case(2, {36, 12, 1}, Vec3(36.0, 12.0, 0.0), 100.0, 0.25);
  testing::add_nonlocal(config, casefile::KernelKind::constant, 1.2, 0.0, 2,
                        casefile::Discretization::discontinuous);
  config.alpha.regions = {testing::alpha_ball(Vec3(12.0, 6.0, 0.0), 4.5, 1.0)};
  config.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmax", 0, 0.01)};
  return config;
}

TEST(WindowPart, GetsTheFlagsOfItsWindowFromTheirOwners) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process builds the whole model, on no window";
  const auto config = long_plate();
  ASSERT_TRUE(setup::has_windows(config));
  const setup::Discretization whole = setup::build_discretization(config);
  const auto& expected = whole.nonlocal->morph.purely_nonlocal;
  const auto [part, owner] = run::window_part(config);
  ASSERT_TRUE(part.window != nullptr);
  const auto& cells = part.window->global_cell;
  EXPECT_LT(cells.size(), static_cast<std::size_t>(whole.mesh.num_cells())) << "a window, not the mesh";
  const auto& got = part.nonlocal->morph.purely_nonlocal;
  ASSERT_EQ(got.size(), cells.size());
  Index from_others = 0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    EXPECT_EQ(got[k], expected[static_cast<std::size_t>(cells[k])]) << "cell " << cells[k];
    from_others += got[k] && !part.computed_cells[k];
  }
  EXPECT_TRUE(la::any_over_processes(from_others > 0)) << "flags sent by their owners";
}

TEST(WindowPart, IsThePieceOfThePartOnTheWholeMesh) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process builds the whole model, on no window";
  const auto config = long_plate();
  const setup::Discretization piece = run::process_model(config);
  const setup::Discretization part = run::process_part(config);
  const setup::Discretization expected =
      setup::cut_to_piece(part, partition::coordinate_bisection(part.mesh, la::world_size()).owner,
                          la::world_rank(), la::any_over_processes);
  EXPECT_EQ(piece.piece->global_cell, expected.piece->global_cell);
  EXPECT_EQ(piece.piece->dofs.key, expected.piece->dofs.key);
  EXPECT_EQ(piece.nonlocal->morph.purely_nonlocal, expected.nonlocal->morph.purely_nonlocal);
  const testing::Rows rows =
      testing::owned_rows(system::assemble_stiffness(piece, system::piece_distribution(piece.piece->dofs)).K);
  ASSERT_FALSE(rows.empty());
  EXPECT_TRUE(rows ==
              testing::owned_rows(
                  system::assemble_stiffness(expected, system::piece_distribution(expected.piece->dofs)).K));
}

}  // namespace
}  // namespace perimorph
