#pragma once
// Local damage updated on several processes (issue 17, item 2): the growth of
// d at a quadrature point is decided by the process of its cell and sent only
// to the processes that hold the cell (a neighbour exchange, la::exchange),
// with a per-cell summary gathered by every process (a few numbers per cell
// whose damage grows, not per point). From the summary every process takes
// the update's totals in the same bits whatever the number of processes: the
// ledger is summed per cell, then over the cells in whole-mesh order
// (THEORY §6).

#include "perimorph/evolution/bond_decisions.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>
#include <vector>

namespace perimorph::evolution {

/// A growth of d at one local quadrature point, with what it books in the
/// ledger.
struct DamageChange {
  std::size_t point;  ///< index into RunState::history (this process's numbers)
  std::size_t whole;  ///< the same in the whole model (whole-mesh cell × points + point)
  double d;           ///< the new value
  double old;         ///< the value it replaces
  double Y;           ///< the damage force that drove it
  double volume;      ///< w |J| scale of the point
  double dissipated;  ///< ∫ (k0 + k1 d) dd × volume, from old to d
};

/// One damage update over the processes: its totals, and the changes each
/// process applies.
struct SharedDamage {
  std::size_t count = 0;    ///< points whose d grows, over the model
  double largest = 0.0;     ///< the largest growth d − old
  double dissipated = 0.0;  ///< Σ dissipated, per cell then over the cells in whole order
  double overshoot = 0.0;   ///< Σ (Y (d − old) volume − dissipated), likewise
  /// The changes at the points this process holds (its own and those sent to
  /// it), in whole point order; Y, volume and dissipated only on the deciding
  /// process (the others apply d alone).
  std::vector<DamageChange> held;
};

/// Shares the changes this process decided (`mine`: its cells', in point
/// order, cells ascending) with the processes holding their cells, and the
/// per-cell summary with every process (collective where `distributed`; on
/// one process the same sums, so the same bits).
SharedDamage share_damage(const setup::Discretization& disc, std::span<const DamageChange> mine,
                          int points_per_cell, const CellHolders& holders, bool distributed);

}  // namespace perimorph::evolution
