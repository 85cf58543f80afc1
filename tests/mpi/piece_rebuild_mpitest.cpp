// A run's state carried from its piece to the piece rebuilt for a grown α
// (issue 17; run/next_piece_state.hpp, system::transfer_dof_vector on
// pieces) under mpiexec -n 1, 2 and 3: by neighbour exchanges alone, it is
// the state gathered whole and cut to the next piece (run::WholeState, the
// way it went before), bit for bit.

#include "perimorph/la/distribution.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/next_piece_state.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/run/whole_state.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/remodel.hpp"
#include "support/fracture_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

namespace perimorph {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

la::OwnedDofs owned_dofs(const setup::Discretization& piece) {
  return la::OwnedDofs(system::piece_distribution(piece.piece->dofs).get(), piece.dim(),
                       piece.dofmap.num_dofs());
}

/// A state of `piece` as a run holds it, alike on every process: failed
/// bonds from each part cell e to every third cell f of its graph row (the
/// place of each in the order of (e, f) over the model), held where the
/// piece holds both cells; D, half of each held bond to each end (the whole
/// model's on the part's cells, a share on the halo's); a damage history
/// on every cell, zero on some; u at each dof its name (setup::dof_name).
evolution::RunState made_state(const setup::Discretization& piece) {
  evolution::RunState state(piece);
  const auto& numbers = *piece.piece;
  const int per_cell = piece.nonlocal->points.per_cell;
  std::vector<double> mine;
  for (Index e = 0; e < piece.mesh.num_cells(); ++e) {
    if (!numbers.of_part(e)) continue;
    for (Index f : piece.nonlocal->graph.row(e)) {
      const Index ge = setup::global_cell(piece, e), gf = setup::global_cell(piece, f);
      if ((ge + gf) % 3 == 0 && ge != gf)
        mine.insert(mine.end(), {static_cast<double>(ge), static_cast<double>(gf),
                                 static_cast<double>(ge % per_cell), static_cast<double>(gf % per_cell)});
    }
  }
  std::vector<std::array<double, 4>> every;
  const std::vector<double> all = la::all_gather(mine);
  for (std::size_t k = 0; k + 4 <= all.size(); k += 4)
    every.push_back({all[k], all[k + 1], all[k + 2], all[k + 3]});
  std::sort(every.begin(), every.end());
  for (std::size_t place = 0; place < every.size(); ++place) {
    const auto& [ge, gf, g, h] = every[place];
    const Index e = setup::local_cell(piece, static_cast<Index>(ge)),
                f = setup::local_cell(piece, static_cast<Index>(gf));
    if (e < 0 || f < 0) continue;
    const bonds::BondId id{e, f, static_cast<int>(g), static_cast<int>(h)};
    state.failed.add(id);
    state.failed_in_order.push_back(id);
    state.failed_place.push_back(place);
    for (Index c : {e, f}) state.cell_dissipated[c] += 0.5 * (0.25 * ge + 1.0);  // half to each end
  }
  state.failed_over_model = every.size();
  const std::size_t n = state.history.size() / static_cast<std::size_t>(piece.mesh.num_cells());
  for (Index c = 0; c < piece.mesh.num_cells(); ++c)
    for (std::size_t i = 0; i < n; ++i)
      state.history[static_cast<std::size_t>(c) * n + i] =
          0.1 * static_cast<double>((setup::global_cell(piece, c) * 7 + static_cast<Index>(i)) % 5);
  for (Index dof = 0; dof < piece.dofmap.num_dofs(); ++dof)
    state.u[static_cast<std::size_t>(dof)] = static_cast<double>(setup::dof_name(piece, dof));
  state.increment = 4;
  state.load_factor = 0.5;
  state.floating_parts = 2;
  return state;
}

// The damage handover plate (DG where purely non-local) with α grown in a
// disk across the parts' boundaries, then grown again: the second rebuild
// carries failed bonds, D, damage history and u to a piece whose halo grew.
TEST(NextPieceState, IsTheWholeStateCutToTheNextPiece) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process runs on the whole model";
  const auto config = testing::handover_plate(3);
  const setup::Discretization start = run::process_model(config);
  auto grown = [&](const setup::Discretization& piece, double radius) {
    return setup::rebuild_piece_for_alpha(
        piece, piece.nonlocal->alpha.grown({{alpha::Ball{Vec3(2.0, 1.6, 0.0), radius}, 0.375}}, 2));
  };
  const setup::Discretization before = grown(start, 0.3), after = grown(before, 0.7);
  ASSERT_TRUE(la::any_over_processes(after.mesh.num_cells() > before.mesh.num_cells())) << "a larger halo";
  const evolution::RunState state = made_state(before);
  ASSERT_GT(state.failed_over_model, 0U);
  ASSERT_FALSE(state.history.empty());

  const evolution::RunState got = run::next_piece_state(before, after, state);
  const run::WholeState was(before), now(after);
  const la::OwnedDofs owned_before = owned_dofs(before), owned_after = owned_dofs(after);
  evolution::RunState whole = was.whole(state, owned_before.of(state.u));
  const std::vector<double> whole_u = whole.u;
  whole.u = system::transfer_dof_vector(before.source->part, after.source->part, whole_u);
  const evolution::RunState expected = now.piece_of(whole);
  EXPECT_TRUE(la::any_over_processes(got.failed_in_order.size() > state.failed_in_order.size()))
      << "bonds of cells new to a piece";
  ASSERT_EQ(got.failed_in_order.size(), expected.failed_in_order.size());
  for (std::size_t k = 0; k < got.failed_in_order.size(); ++k) {
    const auto &a = got.failed_in_order[k], &b = expected.failed_in_order[k];
    ASSERT_TRUE(a.e == b.e && a.f == b.f && a.g == b.g && a.h == b.h) << "failed bond " << k;
    EXPECT_TRUE(got.failed.contains(a));
  }
  EXPECT_EQ(got.failed_place, expected.failed_place);
  EXPECT_EQ(got.failed_over_model, expected.failed_over_model);
  EXPECT_EQ(got.cell_dissipated, expected.cell_dissipated);
  EXPECT_TRUE(same_bits(got.history, expected.history));
  EXPECT_TRUE(la::any_over_processes(
      std::any_of(got.history.begin(), got.history.end(), [](double d) { return d > 0.0; })));
  EXPECT_EQ(got.increment, 4);
  EXPECT_EQ(got.floating_parts, 2U);
  EXPECT_TRUE(got.held_dofs.empty());

  // u and a reference diagonal (max) across, at the next piece's owned dofs:
  // those of the transfer on the source parts' whole dof maps, cut.
  for (const bool combine_max : {false, true}) {
    SCOPED_TRACE(combine_max ? "max" : "last cell's");
    const std::vector<double> moved = system::transfer_dof_vector(before, after, state.u, combine_max);
    const std::vector<double> whole_moved =
        system::transfer_dof_vector(before.source->part, after.source->part, whole_u, combine_max);
    const std::vector<double> mine = owned_after.of(moved),
                              theirs = owned_after.of(now.numbering().piece_of(whole_moved));
    ASSERT_FALSE(theirs.empty());
    EXPECT_TRUE(same_bits(mine, theirs));
  }
}

}  // namespace
}  // namespace perimorph
