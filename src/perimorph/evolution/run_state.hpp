#pragma once
// The state of a run (THEORY §5, §6): what the increments change and the next
// increment starts from. The run loop owns it; evolution components read it
// in inspect and change it in apply. Everything here is keyed by what outlives
// a rebuilt discretization (cells, non-local points, quadrature points), not
// by dofs, except the displacement itself.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/core/types.hpp"

#include <cstddef>
#include <unordered_map>
#include <vector>

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::evolution {

/// The energy balance of THEORY §5: the work W of the external forces, the
/// strain energy U of the last state, the fracture dissipation D (every failed
/// bond at s_crit), the damage dissipation D_d (THEORY §6) and the overshoot
/// of the finite load steps. W + ΔU_α − U − D − D_d − overshoot ≥ 0 is the
/// energy released by re-equilibration after failures and damage updates
/// (ΔU_α: model_change); it vanishes with the load step.
struct EnergyLedger {
  double external_work = 0.0;  ///< W, cumulative
  double strain_energy = 0.0;  ///< U, of the last recorded state
  double dissipated = 0.0;     ///< D, cumulative
  /// Cumulative: what failed bonds held beyond s_crit, and what the damage
  /// updates released at fixed u beyond the dissipation at the threshold.
  double overshoot = 0.0;
  /// Energy the local damage dissipated, ∫ (k0 + k1 d) dd = k0 d + ½ k1 d²
  /// summed over the local quadrature points (THEORY §6), cumulative.
  double damage_dissipated = 0.0;
  /// Strain energy α's growth added at fixed displacement (the stiffness
  /// changed, no work was done), cumulative; 0 without [adaptivity].
  double model_change = 0.0;
  double released() const {
    return external_work + model_change - strain_energy - dissipated - damage_dissipated - overshoot;
  }
};

struct RunState {
  /// An initial state of `disc`: u = 0, load factor 0, its α, no failed
  /// bond, nothing held, an empty ledger.
  explicit RunState(const setup::Discretization& disc);

  int increment = 0;         ///< the increment being computed (1-based), 0 before the first
  double load_factor = 0.0;  ///< λ of that increment
  std::vector<double> u;     ///< the displacement of the last solve (dof vector)
  alpha::AlphaField alpha;   ///< α of the discretization the run is on

  bonds::BrokenBonds failed;                   ///< failed bonds, keyed by cell and point
  std::vector<bonds::BondId> failed_in_order;  ///< the same, in the order they failed
  /// The bonds failed in the whole model: failed_in_order's size, but on a
  /// piece of the model (setup::cut_to_piece), which holds only the failed
  /// bonds whose two cells it holds; every process's alike.
  std::size_t failed_over_model = 0;
  /// On a piece, the place of each of failed_in_order in the whole model's
  /// order of failure (ascending); empty elsewhere.
  std::vector<std::size_t> failed_place;
  /// The position in failed_in_order of the first bond that failed after the
  /// whole model's first `count` ones (`count` itself but on a piece).
  std::size_t failed_after(std::size_t count) const;
  /// Takes `from`'s increment, load factor, α, cumulative counts (detached
  /// dofs, floating parts, cell mechanisms) and energy ledger: what every
  /// process holds alike, whatever the numbering of the model it is on (a
  /// state moved to another piece or to the whole model's numbers).
  void take_progress(const RunState& from);
  /// D per cell, half of each failed bond to each end: the cells with a
  /// failed bond only (0 elsewhere), so that it costs the crack, not the model.
  std::unordered_map<Index, double> cell_dissipated;
  Index num_cells = 0;  ///< the model's cells (a checkpoint writes D of each)
  /// Dofs held by springs: detached dofs, pins of parts (on a piece of the
  /// model their names, setup::dof_name, every process's alike).
  std::vector<Index> held_dofs;
  std::size_t detached_dofs = 0;    ///< free dofs left with no stiffness, cumulative
  std::size_t floating_parts = 0;   ///< parts cut free and held, cumulative
  std::size_t cell_mechanisms = 0;  ///< cells with a free motion held (cell_mechanisms.hpp), cumulative
  /// The damage d at every local quadrature point (cell-major, THEORY §6);
  /// empty without [material.damage].
  std::vector<double> history;
  EnergyLedger energy;
};

}  // namespace perimorph::evolution
