#include "perimorph/evolution/run_state.hpp"

#include "perimorph/setup/discretization.hpp"

#include <algorithm>

namespace perimorph::evolution {

RunState::RunState(const setup::Discretization& disc)
    : u(static_cast<std::size_t>(disc.dofmap.num_dofs()), 0.0),
      alpha(disc.nonlocal ? disc.nonlocal->alpha : alpha::AlphaField::constant(0.0)),
      num_cells(disc.mesh.num_cells()) {
  if (disc.damage) history.assign(static_cast<std::size_t>(disc.mesh.num_cells()) * disc.rule.size(), 0.0);
  if (disc.nonlocal) failed = bonds::BrokenBonds(disc.mesh.num_cells(), disc.nonlocal->points.per_cell);
}

void RunState::take_progress(const RunState& from) {
  increment = from.increment;
  load_factor = from.load_factor;
  alpha = from.alpha;
  detached_dofs = from.detached_dofs;
  floating_parts = from.floating_parts;
  cell_mechanisms = from.cell_mechanisms;
  energy = from.energy;
}

std::size_t RunState::failed_after(std::size_t count) const {
  if (failed_place.empty()) return std::min(count, failed_in_order.size());
  return static_cast<std::size_t>(std::lower_bound(failed_place.begin(), failed_place.end(), count) -
                                  failed_place.begin());
}

}  // namespace perimorph::evolution
