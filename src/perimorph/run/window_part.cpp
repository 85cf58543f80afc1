#include "perimorph/run/window_part.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/mesh/box_window.hpp"

#include <algorithm>
#include <memory>

namespace perimorph::run {

std::vector<char> window_flags(const mesh::BoxSpec& box, const setup::MeshWindow& window,
                               std::vector<char> flags) {
  const int me = la::world_rank();
  const std::vector<Index> cells = mesh::box_window_cells(box, window.lo, window.hi);
  PERIMORPH_ASSERT(flags.size() == cells.size() && window.owner.size() == cells.size(),
                   "a flag and an owner for every cell of the window");
  // 1. To each other owner of a cell of the window: the window's box.
  std::vector<la::Parcel> asks;
  for (int q : window.owner)
    if (q != me && la::parcel_for(asks, q).empty())
      for (std::size_t d = 0; d < 3; ++d) {
        la::parcel_for(asks, q).push_back(static_cast<double>(window.lo[d]));
        la::parcel_for(asks, q).push_back(static_cast<double>(window.hi[d]));
      }
  // 2. To each asker: the flagged cells of this process's part in its box.
  const mesh::StructuredLayout grid = mesh::box_layout(box);
  std::vector<la::Parcel> answers;
  for (const la::Parcel& ask : la::exchange(asks)) {
    auto& out = la::parcel_for(answers, ask.process);
    for (std::size_t k = 0; k < cells.size(); ++k) {
      if (!flags[k] || window.owner[k] != me) continue;
      const auto ijk = grid.box_cell_ijk(cells[k]);
      bool inside = true;
      for (std::size_t d = 0; d < 3; ++d)
        inside = inside && ijk[d] >= static_cast<Index>(ask.values[2 * d]) &&
                 ijk[d] < static_cast<Index>(ask.values[2 * d + 1]);
      if (inside) out.push_back(static_cast<double>(cells[k]));
    }
  }
  for (const la::Parcel& answer : la::exchange(answers))
    for (double g : answer.values) {
      const auto it = std::lower_bound(cells.begin(), cells.end(), static_cast<Index>(g));
      PERIMORPH_ASSERT(it != cells.end() && *it == static_cast<Index>(g), "a flagged cell of the window");
      flags[static_cast<std::size_t>(it - cells.begin())] = 1;
    }
  return flags;
}

std::pair<setup::Discretization, std::vector<int>> window_part(const casefile::CaseConfig& config,
                                                               const setup::PhaseCallback& on_phase) {
  const int processes = la::world_size(), rank = la::world_rank();
  setup::MeshWindow window = setup::part_window(config, setup::grid_bisection(config, processes), rank);
  std::vector<int> owner = window.owner;
  window.any_over_processes = la::any_over_processes;
  window.max_over_processes = la::largest_over_processes;
  // Kept by the part for a rebuild for a grown α (Discretization::share_flags).
  auto kept = std::make_shared<const setup::MeshWindow>(setup::MeshWindow{window.lo, window.hi, owner});
  const mesh::BoxSpec box = setup::box_of(config);
  auto share_flags = [kept, box](std::vector<char> flags) {
    return window_flags(box, *kept, std::move(flags));
  };
  setup::Discretization part =
      setup::build_discretization(config, on_phase, {processes, rank, share_flags, std::move(window)});
  return {std::move(part), std::move(owner)};
}

}  // namespace perimorph::run
