#include "perimorph/run/whole_state.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace perimorph::run {

namespace {

/// Whole-model integers (≥ 0) from the one process that holds each (the
/// others pass −1): exact as doubles below 2⁵³.
std::vector<Index> from_owners(const std::vector<Index>& mine) {
  std::vector<double> v(mine.size());
  for (std::size_t k = 0; k < mine.size(); ++k) v[k] = mine[k] < 0 ? -0.0 : static_cast<double>(mine[k]);
  const std::vector<double> all = la::from_owners(std::move(v));
  std::vector<Index> out(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    PERIMORPH_ASSERT(!std::signbit(all[k]), "a held dof whose node no process owns");
    out[k] = static_cast<Index>(all[k]);
  }
  return out;
}

}  // namespace

WholeState::WholeState(const setup::Discretization& piece)
    : piece_(&piece), numbering_(piece.piece->dofs, piece.dim()) {
  cells_ = static_cast<Index>(la::sum_over_processes({static_cast<double>(piece.piece->part_cells())})[0]);
}

bool WholeState::owns_dof(Index dof) const {
  return piece_->piece->dofs.owned[static_cast<std::size_t>(dof / piece_->dim())] != 0;
}

evolution::RunState WholeState::whole(const evolution::RunState& state,
                                      std::span<const double> owned_u) const {
  evolution::RunState out(*piece_);
  out.increment = state.increment;
  out.load_factor = state.load_factor;
  out.alpha = state.alpha;
  out.u = numbering_.whole(owned_u);
  out.num_cells = cells_;
  out.failed = {};
  out.detached_dofs = state.detached_dofs;
  out.floating_parts = state.floating_parts;
  out.cell_mechanisms = state.cell_mechanisms;
  out.energy = state.energy;

  // The failed bonds: every process's with their places, in the whole order.
  constexpr std::size_t kPacked = 5;
  std::vector<double> mine;
  mine.reserve(state.failed_in_order.size() * kPacked);
  for (std::size_t k = 0; k < state.failed_in_order.size(); ++k) {
    const auto& id = state.failed_in_order[k];
    if (!piece_->piece->of_part(id.e)) continue;  // sent once, by the process that decided it
    mine.insert(mine.end(), {static_cast<double>(state.failed_place[k]),
                             static_cast<double>(setup::global_cell(*piece_, id.e)),
                             static_cast<double>(setup::global_cell(*piece_, id.f)),
                             static_cast<double>(id.g), static_cast<double>(id.h)});
  }
  const std::vector<double> all = la::all_gather(mine);
  out.failed_in_order.assign(state.failed_over_model, {-1, -1, -1, -1});
  for (std::size_t k = 0; k + kPacked <= all.size(); k += kPacked) {
    const auto place = static_cast<std::size_t>(all[k]);
    PERIMORPH_ASSERT(place < out.failed_in_order.size(), "a failed bond's place beyond the model's count");
    out.failed_in_order[place] = {static_cast<Index>(all[k + 1]), static_cast<Index>(all[k + 2]),
                                  static_cast<int>(all[k + 3]), static_cast<int>(all[k + 4])};
  }
  for (const auto& id : out.failed_in_order)
    PERIMORPH_ASSERT(id.e >= 0, "a failed bond that no process holds");
  out.failed_over_model = state.failed_over_model;

  // D per cell: each cell's from the process that decides it.
  std::vector<double> dissipated;
  for (const auto& [c, d] : state.cell_dissipated)
    if (piece_->piece->of_part(c))
      dissipated.insert(dissipated.end(), {static_cast<double>(setup::global_cell(*piece_, c)), d});
  const std::vector<double> every = la::all_gather(dissipated);
  for (std::size_t k = 0; k + 1 < every.size(); k += 2)
    out.cell_dissipated[static_cast<Index>(every[k])] = every[k + 1];

  // The held dofs, names to whole dofs, each from the process owning its node.
  std::vector<Index> held(state.held_dofs.size(), -1);
  for (std::size_t k = 0; k < held.size(); ++k)
    if (const Index d = setup::dof_of_name(*piece_, state.held_dofs[k]); d >= 0 && owns_dof(d))
      held[k] = numbering_.whole_dofs_of({&d, 1})[0];
  out.held_dofs = from_owners(held);

  // The damage history: each cell's points from the process that decides the cell.
  if (!state.history.empty()) {
    const std::size_t n = points_per_cell();
    std::vector<double> damaged;
    for (Index c = 0; c < piece_->mesh.num_cells(); ++c) {
      if (!piece_->piece->of_part(c)) continue;
      const auto first = state.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * n);
      if (std::all_of(first, first + static_cast<std::ptrdiff_t>(n), [](double d) { return d == 0.0; }))
        continue;
      damaged.push_back(static_cast<double>(setup::global_cell(*piece_, c)));
      damaged.insert(damaged.end(), first, first + static_cast<std::ptrdiff_t>(n));
    }
    const std::vector<double> gathered = la::all_gather(damaged);
    out.history.assign(static_cast<std::size_t>(cells_) * n, 0.0);
    for (std::size_t k = 0; k + n < gathered.size(); k += n + 1)
      std::copy_n(
          gathered.begin() + static_cast<std::ptrdiff_t>(k + 1), n,
          out.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(gathered[k]) * n));
  }
  return out;
}

std::size_t WholeState::points_per_cell() const {
  return piece_->damage ? static_cast<std::size_t>(piece_->damage->points_per_cell) : 0;
}

evolution::RunState WholeState::empty_whole() const {
  evolution::RunState out(*piece_);
  out.u.assign(static_cast<std::size_t>(numbering_.whole_dofs()), 0.0);
  out.num_cells = cells_;
  if (piece_->nonlocal) out.failed = bonds::BrokenBonds(cells_, piece_->nonlocal->points.per_cell);
  out.history.assign(static_cast<std::size_t>(cells_) * points_per_cell(), 0.0);
  return out;
}

evolution::RunState WholeState::piece_of(const evolution::RunState& whole) const {
  evolution::RunState out(*piece_);
  out.increment = whole.increment;
  out.load_factor = whole.load_factor;
  out.alpha = whole.alpha;
  out.u = numbering_.piece_of(whole.u);
  out.detached_dofs = whole.detached_dofs;
  out.floating_parts = whole.floating_parts;
  out.cell_mechanisms = whole.cell_mechanisms;
  out.energy = whole.energy;
  for (std::size_t k = 0; k < whole.failed_in_order.size(); ++k) {
    const auto& id = whole.failed_in_order[k];
    const Index e = setup::local_cell(*piece_, id.e), f = setup::local_cell(*piece_, id.f);
    if (e < 0 || f < 0) continue;
    const bonds::BondId local{e, f, id.g, id.h};
    out.failed.add(local);
    out.failed_in_order.push_back(local);
    out.failed_place.push_back(k);
  }
  out.failed_over_model = whole.failed_in_order.size();
  for (const auto& [c, d] : whole.cell_dissipated)
    if (const Index lc = setup::local_cell(*piece_, c); lc >= 0 && piece_->piece->of_part(lc))
      out.cell_dissipated[lc] = d;
  std::vector<Index> names(whole.held_dofs.size(), -1);
  for (std::size_t k = 0; k < names.size(); ++k)
    if (const Index d = numbering_.piece_dofs_of({&whole.held_dofs[k], 1})[0]; d >= 0 && owns_dof(d))
      names[k] = setup::dof_name(*piece_, d);
  out.held_dofs = from_owners(names);
  // The damage history of every cell of the piece (a cell of its halo shares
  // nodes with, or bonds to, its part's).
  if (const std::size_t n = points_per_cell(); n > 0)
    for (Index c = 0; c < piece_->mesh.num_cells(); ++c)
      std::copy_n(whole.history.begin() + static_cast<std::ptrdiff_t>(
                                              static_cast<std::size_t>(setup::global_cell(*piece_, c)) * n),
                  n, out.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * n));
  return out;
}

}  // namespace perimorph::run
