#include "perimorph/evolution/part_support.hpp"

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/cell_mechanisms.hpp"
#include "perimorph/evolution/floating_part_links.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace perimorph::evolution {

namespace {

// The lists below are of dof names (setup::dof_name: the dofs themselves but
// on a piece of the model), so that every process holds the same ones.

/// The dofs of `names` this process holds (on a piece, those of its piece).
std::vector<Index> dofs_of(const setup::Discretization& disc, std::span<const Index> names) {
  if (!disc.piece) return {names.begin(), names.end()};
  std::vector<Index> out;
  for (Index n : names)
    if (const Index d = setup::dof_of_name(disc, n); d >= 0) out.push_back(d);
  return out;
}

/// A system's vector read at given dof names, each from the process that owns it.
la::DofValuesAt values_at_names(const setup::Discretization& disc, la::DofValuesAt at_dofs) {
  if (!disc.piece) return at_dofs;
  return [&disc, at = std::move(at_dofs)](std::span<const Index> names) {
    std::vector<Index> dofs(names.size());
    for (std::size_t k = 0; k < names.size(); ++k) dofs[k] = setup::dof_of_name(disc, names[k]);
    return at(dofs);  // -1: not this process's (OwnedDofs::at)
  };
}

/// The system's applied force and reference diagonal, read at given dof
/// names from the processes that own them.
la::DofValuesAt applied_force_of(const setup::Discretization& disc, const system::ConstrainedSystem& system) {
  return values_at_names(disc,
                         [&system](std::span<const Index> dofs) { return system.applied_force_at(dofs); });
}
la::DofValuesAt reference_diagonal_of(const setup::Discretization& disc,
                                      const system::ConstrainedSystem& system) {
  return values_at_names(
      disc, [&system](std::span<const Index> dofs) { return system.reference_diagonal_at(dofs); });
}

/// The prescribed dofs' names, sorted, on every process (on a piece each
/// process's gathered; collective there).
std::vector<Index> prescribed_names(const setup::Discretization& disc,
                                    const system::ConstrainedSystem& system) {
  const auto& prescribed = system.bc().dofs;
  if (!disc.piece) return {prescribed.begin(), prescribed.end()};
  std::vector<double> mine;
  mine.reserve(prescribed.size());
  for (Index d : prescribed) mine.push_back(static_cast<double>(setup::dof_name(disc, d)));
  std::vector<Index> out;
  for (double v : la::all_gather(mine)) out.push_back(static_cast<Index>(v));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Where the node of dof name `name` is, on every process (collective on a
/// piece: from a process that holds it).
Vec3 position_of(const setup::Discretization& disc, Index name) {
  const int dim = disc.dim();
  const Index dof = setup::dof_of_name(disc, name);
  Vec3 x = Vec3::Constant(std::nan(""));
  if (dof >= 0) x = disc.dofmap.node_coordinate(disc.mesh, dof / dim);
  if (!disc.piece) return x;
  const std::vector<double> all = la::all_gather({x.x(), x.y(), x.z()});
  for (std::size_t k = 0; k + 2 < all.size(); k += 3)
    if (!std::isnan(all[k])) return {all[k], all[k + 1], all[k + 2]};
  return x;
}

/// The cells of `failed` (each once, ascending) with their dofs, on every
/// process: on a piece, each process lists those it decides and they are
/// gathered (collective).
CellsToCheck cells_of_failed_bonds(const setup::Discretization& disc, std::span<const bonds::BondId> failed) {
  std::vector<Index> cells;
  for (const auto& id : failed) cells.insert(cells.end(), {id.e, id.f});
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  if (!disc.piece) return cells_to_check(disc, cells);
  const std::vector<char> mine = setup::cells_of_process(disc, la::world_size(), la::world_rank());
  std::erase_if(cells, [&](Index c) { return !mine[static_cast<std::size_t>(c)]; });
  return cells_to_check_over_pieces(disc, cells);
}

/// A's principal blocks over sets of dof names (collective where A is spread).
BlocksAt blocks_of(const setup::Discretization& disc, const la::Matrix& A) {
  return [&disc, &A](std::span<const std::vector<Index>> sets) {
    if (!disc.piece) return A.blocks(sets);
    std::vector<std::vector<Index>> dofs(sets.begin(), sets.end());
    for (auto& s : dofs)
      for (Index& n : s) n = setup::dof_of_name(disc, n);  // -1 where the piece lacks it (Matrix::blocks)
    return A.blocks(dofs);
  };
}

}  // namespace

Proposal PartSupport::inspect(const RunState& state, const system::ConstrainedSystem& system) {
  detached_.clear();
  pins_.clear();
  cell_pins_.clear();
  parts_ = 0;
  mechanisms_ = 0;
  // Counted over the whole model, every process's alike; on a piece a
  // process holds the failed bonds of its piece only, from `first` on.
  const std::size_t first = state.failed_after(seen_), last = state.failed_in_order.size();
  const bool failed_now = seen_ != state.failed_over_model;
  seen_ = state.failed_over_model;
  const bool downdated = system.downdate_count() != downdates_seen_;
  downdates_seen_ = system.downdate_count();
  if (!failed_now && !downdated) return {};
  const int dim = disc_->dim();
  const la::DofValuesAt force = applied_force_of(*disc_, system),
                        reference = reference_diagonal_of(*disc_, system);
  // A free dof whose every bond has failed (or whose cells have all lost
  // their stiffness to damage, d = 1) has a zero row: the matrix turns
  // singular. Such a dof is coupled to nothing, so holding it at zero by a
  // spring of its initial stiffness changes no other dof.
  detached_ = system.without_stiffness(system.last_downdated());
  const std::vector<double> detached_force = force(detached_);
  for (std::size_t k = 0; k < detached_.size(); ++k) {
    const Index d = detached_[k];
    if (const double f = detached_force[k]; f != 0.0) {
      const Vec3 x = position_of(*disc_, d);
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
  if (!failed_now) return {detached_.size()};
  const assembly::NonlocalSpace space = disc_->nonlocal_space(&state.failed);
  // A process looks at the pairs whose cells' points it stores (on a part,
  // those its graph rows reach: the pair's decider among them), and the
  // answer is shared: every process gets the serial one.
  const auto& points = disc_->nonlocal->points;
  bool separated = false;
  for (std::size_t k = first; k < last && !separated; ++k) {
    const auto& id = state.failed_in_order[k];
    if (k > first && state.failed_in_order[k - 1].e == id.e && state.failed_in_order[k - 1].f == id.f)
      continue;
    if (points.holds(id.e) && points.holds(id.f)) separated = !assembly::has_intact_bond(space, id.e, id.f);
  }
  if (la::world_size() > 1) separated = la::max_over_processes(separated ? 1 : 0) != 0;
  const std::vector<Index> prescribed = prescribed_names(*disc_, system);
  if (separated) {
    std::vector<Index> held = state.held_dofs;
    held.insert(held.end(), detached_.begin(), detached_.end());
    held.insert(held.end(), prescribed.begin(), prescribed.end());
    std::sort(held.begin(), held.end());
    std::vector<Vec3> positions;  // a piece's links come with them
    const std::vector<Index> links = links_of_loosely_held_parts(*disc_, space, held, &positions);
    FloatingParts parts = find_floating_parts(*disc_, links, held, force, positions);
    pins_ = std::move(parts.pins);
    parts_ = parts.parts;
  }
  // The cells of the failed bonds may keep a motion no intact bond resists
  // (cell_mechanisms.hpp): looked at with what is about to be held left out.
  const CellsToCheck cells =
      cells_of_failed_bonds(*disc_, std::span(state.failed_in_order).subspan(first, last - first));
  std::vector<Index> held(prescribed.begin(), prescribed.end());
  held.insert(held.end(), detached_.begin(), detached_.end());
  held.insert(held.end(), pins_.begin(), pins_.end());
  std::sort(held.begin(), held.end());
  CellMechanisms mechanisms =
      find_cell_mechanisms(cells, blocks_of(*disc_, system.A()), reference, held, force);
  cell_pins_ = std::move(mechanisms.pins);
  mechanisms_ = mechanisms.cells;
  return {detached_.size() + pins_.size() + cell_pins_.size()};
}

Effect PartSupport::apply(RunState& state, system::ConstrainedSystem& system) {
  system.hold(dofs_of(*disc_, detached_), true);
  state.detached_dofs += detached_.size();
  state.held_dofs.insert(state.held_dofs.end(), detached_.begin(), detached_.end());
  system.hold(dofs_of(*disc_, pins_), false);
  state.held_dofs.insert(state.held_dofs.end(), pins_.begin(), pins_.end());
  state.floating_parts += static_cast<std::size_t>(parts_);
  system.hold(dofs_of(*disc_, cell_pins_), false);
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
  if (state.failed_over_model == 0 && state.history.empty()) return;
  const la::DofValuesAt force = applied_force_of(disc, system),
                        reference = reference_diagonal_of(disc, system);
  const std::vector<Index> detached = system.free_dofs_without_stiffness();
  system.hold(dofs_of(disc, detached), true);
  if (state.failed_over_model == 0) {
    state.held_dofs = detached;
    return;
  }
  std::vector<Index> held = detached;
  const std::vector<Index> prescribed = prescribed_names(disc, system);
  held.insert(held.end(), prescribed.begin(), prescribed.end());
  std::sort(held.begin(), held.end());
  std::vector<Vec3> positions;
  const std::vector<Index> links =
      links_of_loosely_held_parts(disc, disc.nonlocal_space(&state.failed), held, &positions);
  const FloatingParts parts = find_floating_parts(disc, links, held, force, positions);
  system.hold(dofs_of(disc, parts.pins), false);
  const CellsToCheck cells = cells_of_failed_bonds(disc, state.failed_in_order);
  held.insert(held.end(), parts.pins.begin(), parts.pins.end());
  std::sort(held.begin(), held.end());
  const CellMechanisms mechanisms =
      find_cell_mechanisms(cells, blocks_of(disc, system.A()), reference, held, force);
  system.hold(dofs_of(disc, mechanisms.pins), false);
  state.held_dofs = detached;
  state.held_dofs.insert(state.held_dofs.end(), parts.pins.begin(), parts.pins.end());
  state.held_dofs.insert(state.held_dofs.end(), mechanisms.pins.begin(), mechanisms.pins.end());
}

}  // namespace perimorph::evolution
