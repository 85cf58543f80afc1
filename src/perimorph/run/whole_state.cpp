#include "perimorph/run/whole_state.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <cstddef>

namespace perimorph::run {

WholeState::WholeState(const setup::Discretization& piece, la::Onto onto)
    : piece_(&piece), onto_(onto), numbering_(piece.piece->dofs, piece.dim(), onto) {
  cells_ = static_cast<Index>(la::sum_over_processes({static_cast<double>(piece.piece->part_cells())})[0]);
}

evolution::RunState WholeState::whole(const evolution::RunState& state,
                                      std::span<const double> owned_u) const {
  evolution::RunState out(*piece_);
  out.take_progress(state);
  const bool receives = la::receives(onto_);
  out.u = numbering_.whole(owned_u);
  out.num_cells = receives ? cells_ : 0;
  out.failed = {};

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
  const std::vector<double> all = la::gather_onto(mine, onto_);
  if (receives) out.failed_in_order.assign(state.failed_over_model, {-1, -1, -1, -1});
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
  const std::vector<double> every = la::gather_onto(dissipated, onto_);
  for (std::size_t k = 0; k + 1 < every.size(); k += 2)
    out.cell_dissipated[static_cast<Index>(every[k])] = every[k + 1];

  // The held dofs: names (alike on every process) to whole dofs.
  out.held_dofs.clear();
  if (receives)
    for (Index name : state.held_dofs) out.held_dofs.push_back(numbering_.whole_of_name(name));

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
    const std::vector<double> gathered = la::gather_onto(damaged, onto_);
    out.history.assign(static_cast<std::size_t>(out.num_cells) * n, 0.0);
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
  PERIMORPH_ASSERT(onto_ == la::Onto::every_process,
                   "WholeState::piece_of on a state gathered onto process 0");
  evolution::RunState out(*piece_);
  out.take_progress(whole);
  out.u = numbering_.piece_of(whole.u);
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
  out.held_dofs.clear();
  for (Index w : whole.held_dofs) out.held_dofs.push_back(numbering_.name_of_whole(w));
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
