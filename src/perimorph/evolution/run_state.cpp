#include "perimorph/evolution/run_state.hpp"

#include "perimorph/setup/discretization.hpp"

namespace perimorph::evolution {

RunState::RunState(const setup::Discretization& disc)
    : u(static_cast<std::size_t>(disc.dofmap.num_dofs()), 0.0),
      alpha(disc.nonlocal ? disc.nonlocal->alpha : alpha::AlphaField::constant(0.0)),
      num_cells(disc.mesh.num_cells()) {
  if (disc.damage) history.assign(static_cast<std::size_t>(disc.mesh.num_cells()) * disc.rule.size(), 0.0);
  if (disc.nonlocal) failed = bonds::BrokenBonds(disc.mesh.num_cells(), disc.nonlocal->points.per_cell);
}

}  // namespace perimorph::evolution
