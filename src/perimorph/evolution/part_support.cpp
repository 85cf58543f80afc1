#include "perimorph/evolution/part_support.hpp"

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/cell_mechanisms.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace perimorph::evolution {

namespace {

/// The system's applied force and reference diagonal, read at given dofs
/// from the processes that own them.
la::DofValuesAt applied_force_of(const system::ConstrainedSystem& system) {
  return [&system](std::span<const Index> dofs) { return system.applied_force_at(dofs); };
}
la::DofValuesAt reference_diagonal_of(const system::ConstrainedSystem& system) {
  return [&system](std::span<const Index> dofs) { return system.reference_diagonal_at(dofs); };
}

}  // namespace

Proposal PartSupport::inspect(const RunState& state, const system::ConstrainedSystem& system) {
  detached_.clear();
  pins_.clear();
  cell_pins_.clear();
  parts_ = 0;
  mechanisms_ = 0;
  const std::size_t first = seen_;
  seen_ = state.failed_in_order.size();
  const bool downdated = system.downdate_count() != downdates_seen_;
  downdates_seen_ = system.downdate_count();
  if (first == seen_ && !downdated) return {};
  const int dim = disc_->dim();
  const la::DofValuesAt force = applied_force_of(system), reference = reference_diagonal_of(system);
  // A free dof whose every bond has failed (or whose cells have all lost
  // their stiffness to damage, d = 1) has a zero row: the matrix turns
  // singular. Such a dof is coupled to nothing, so holding it at zero by a
  // spring of its initial stiffness changes no other dof.
  detached_ = system.without_stiffness(system.last_downdated());
  const std::vector<double> detached_force = system.applied_force_at(detached_);
  for (std::size_t k = 0; k < detached_.size(); ++k) {
    const Index d = detached_[k];
    if (const double f = detached_force[k]; f != 0.0) {
      const Vec3 x = disc_->dofmap.node_coordinate(disc_->mesh, d / dim);
      throw Error(
          fmt::format("bond failures or damage have left the node at ({:g}, {:g}, {:g}) with no stiffness in "
                      "direction {} while an applied force {:g} acts on it: there is no quasi-static "
                      "equilibrium",
                      x.x(), x.y(), x.z(), "xyz"[d % dim], f));
    }
  }
  // A cell pair that lost its last intact bond may have cut a part free
  // (floating_parts.hpp). The bonds fail grouped by cell pair: each pair is
  // looked at once.
  if (first == seen_) return {detached_.size()};
  const assembly::NonlocalSpace space = disc_->nonlocal_space(&state.failed);
  // A process looks at the pairs whose cells' points it stores (on a part,
  // those its graph rows reach: the pair's decider among them), and the
  // answer is shared: every process gets the serial one.
  const auto& points = disc_->nonlocal->points;
  bool separated = false;
  for (std::size_t k = first; k < seen_ && !separated; ++k) {
    const auto& id = state.failed_in_order[k];
    if (k > first && state.failed_in_order[k - 1].e == id.e && state.failed_in_order[k - 1].f == id.f)
      continue;
    if (points.holds(id.e) && points.holds(id.f)) separated = !assembly::has_intact_bond(space, id.e, id.f);
  }
  if (la::world_size() > 1) separated = la::max_over_processes(separated ? 1 : 0) != 0;
  const auto& prescribed = system.bc().dofs;
  if (separated) {
    std::vector<Index> held = state.held_dofs;
    held.insert(held.end(), detached_.begin(), detached_.end());
    held.insert(held.end(), prescribed.begin(), prescribed.end());
    std::sort(held.begin(), held.end());
    FloatingParts parts =
        find_floating_parts(*disc_, stiffness_links_over_processes(*disc_, space), held, force);
    pins_ = std::move(parts.pins);
    parts_ = parts.parts;
  }
  // The cells of the failed bonds may keep a motion no intact bond resists
  // (cell_mechanisms.hpp): looked at with what is about to be held left out.
  std::vector<Index> cells;
  for (std::size_t k = first; k < seen_; ++k) {
    cells.push_back(state.failed_in_order[k].e);
    cells.push_back(state.failed_in_order[k].f);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  std::vector<Index> held(prescribed.begin(), prescribed.end());
  held.insert(held.end(), detached_.begin(), detached_.end());
  held.insert(held.end(), pins_.begin(), pins_.end());
  std::sort(held.begin(), held.end());
  CellMechanisms mechanisms = find_cell_mechanisms(*disc_, system.A(), reference, cells, held, force);
  cell_pins_ = std::move(mechanisms.pins);
  mechanisms_ = mechanisms.cells;
  return {detached_.size() + pins_.size() + cell_pins_.size()};
}

Effect PartSupport::apply(RunState& state, system::ConstrainedSystem& system) {
  system.hold(detached_, true);
  state.detached_dofs += detached_.size();
  state.held_dofs.insert(state.held_dofs.end(), detached_.begin(), detached_.end());
  system.hold(pins_, false);
  state.held_dofs.insert(state.held_dofs.end(), pins_.begin(), pins_.end());
  state.floating_parts += static_cast<std::size_t>(parts_);
  system.hold(cell_pins_, false);
  state.held_dofs.insert(state.held_dofs.end(), cell_pins_.begin(), cell_pins_.end());
  state.cell_mechanisms += mechanisms_;
  return Effect::hold;
}

}  // namespace perimorph::evolution

namespace perimorph::evolution {

void PartSupport::rebind(const setup::Discretization& disc, RunState& state,
                         system::ConstrainedSystem& system) {
  disc_ = &disc;
  state.held_dofs.clear();
  downdates_seen_ = system.downdate_count();
  if (state.failed_in_order.empty() && state.history.empty()) return;
  const la::DofValuesAt force = applied_force_of(system), reference = reference_diagonal_of(system);
  const std::vector<Index> detached = system.free_dofs_without_stiffness();
  system.hold(detached, true);
  if (state.failed_in_order.empty()) {
    state.held_dofs = detached;
    return;
  }
  std::vector<Index> held = detached;
  const auto& prescribed = system.bc().dofs;
  held.insert(held.end(), prescribed.begin(), prescribed.end());
  std::sort(held.begin(), held.end());
  const FloatingParts parts = find_floating_parts(
      disc, stiffness_links_over_processes(disc, disc.nonlocal_space(&state.failed)), held, force);
  system.hold(parts.pins, false);
  std::vector<Index> cells;
  for (const auto& id : state.failed_in_order) {
    cells.push_back(id.e);
    cells.push_back(id.f);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  held.insert(held.end(), parts.pins.begin(), parts.pins.end());
  std::sort(held.begin(), held.end());
  const CellMechanisms mechanisms = find_cell_mechanisms(disc, system.A(), reference, cells, held, force);
  system.hold(mechanisms.pins, false);
  state.held_dofs = detached;
  state.held_dofs.insert(state.held_dofs.end(), parts.pins.begin(), parts.pins.end());
  state.held_dofs.insert(state.held_dofs.end(), mechanisms.pins.begin(), mechanisms.pins.end());
}

}  // namespace perimorph::evolution
