#pragma once
// Bond failure by critical stretch (THEORY §5): which bonds break after a
// solve, and the incremental update of the assembled matrices when they do.
// A failed bond's block (pair_kernel.hpp, bond_block) is subtracted from K
// and from the constrained copy A, and the right-hand side is corrected for
// its columns on prescribed dofs; nothing is reassembled, so one update costs
// O(newly failed bonds).

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <vector>

namespace perimorph::evolution {

/// `total`: the area of every broken face. `projected`: for each normal
/// axis, the broken faces with that normal projected along it (a face position
/// counted once however many rows of faces are broken there), the largest
/// over the axes: the area of a crack running across that axis, not inflated
/// by a band of failed cells. NaN on an unstructured mesh.
/// The energy of bonds broken by one apply() (THEORY §5): `dissipated` counts
/// each at the critical stretch, ½ W ᾱ c (s_crit |ξ|)² (the per-bond energy of
/// the G_c closed forms and of `perimorph gc`); `overshoot` is what they held
/// beyond it at the solve that found them over s_crit (≥ 0; it vanishes as the
/// load increments shrink).
struct FailureEnergy {
  double dissipated = 0.0, overshoot = 0.0;
};

/// Per-cell fracture fields for the VTU (empty for a run without [fracture]).
struct FractureFields {
  std::vector<double> damage;      ///< fraction of bond weight lost, mean over the cell's points
  std::vector<double> dissipated;  ///< energy of the failed bonds at s_crit, half to each end's cell
};

struct CrackArea {
  double total = 0.0, projected = 0.0;
};

class BondFailure {
 public:
  explicit BondFailure(const setup::Discretization& model);

  /// The space the stiffness is assembled with, failed bonds included.
  assembly::NonlocalSpace space() const;
  double s_crit() const { return s_crit_; }

  /// The intact bonds to break at displacement u: those with s > s_crit, or
  /// with rule = fraction those with s ≥ fraction · the largest such s;
  /// bonds with an end in a [fracture] no_fail region, and with
  /// intra_cell_failure = false bonds between two points of one cell, are
  /// never selected.
  std::vector<assembly::StretchedBond> select(std::span<const double> u) const;

  /// Breaks `bonds` (from select at the current u) in `system`: K −= their
  /// blocks; A −= their blocks on free rows and columns; rhs_unit[i] += B_ij g_j
  /// for free i and prescribed j (g = the prescribed values at load factor 1).
  /// Returns their energy, at s_crit and beyond it. Dofs left with no
  /// stiffness, and parts cut free of every support, are held by springs on A
  /// (no force on them). A and K are finalized here and the solver takes the
  /// new A (ConstrainedSystem::operator_changed).
  FailureEnergy apply(const std::vector<assembly::StretchedBond>& bonds, system::ConstrainedSystem& system);

  const bonds::BrokenBonds& broken() const { return broken_; }
  /// D of THEORY §5: Σ over the failed bonds of the energy each held at
  /// s = s_crit, ½ W ᾱ c (s_crit |ξ|)², cumulative (FailureEnergy::dissipated).
  double dissipated() const { return energy_.dissipated; }
  /// Σ over the failed bonds of the energy each held beyond s_crit at the
  /// solve that found it over the criterion, cumulative: the overshoot of the
  /// finite load steps (FailureEnergy::overshoot).
  double overshoot() const { return energy_.overshoot; }
  /// Free dofs left with no bond and no local stiffness, held at zero (their
  /// row of A is otherwise zero).
  std::size_t detached_dofs() const { return detached_; }
  /// Parts cut free by failures and held by a minimal support
  /// (floating_parts.hpp), cumulative; apply() throws Error for one whose
  /// applied forces do not balance.
  std::size_t floating_parts() const { return floating_parts_; }
  /// Damage index and dissipated energy (at s_crit) per cell, for the VTU.
  FractureFields fields() const;
  /// Crack area from the faces between adjacent cells all of whose bonds
  /// have failed (structured meshes; 2D: length × thickness; 1D: the
  /// cross-section). Pre-crack cuts are not counted (their bonds never existed).
  CrackArea crack_area() const;

 private:
  const setup::Discretization& model_;
  double s_crit_ = 0.0;
  bonds::BrokenBonds broken_;
  FailureEnergy energy_;
  std::vector<double> cell_dissipated_;
  std::size_t detached_ = 0;
  std::size_t floating_parts_ = 0;
  std::vector<Index> held_;    ///< detached dofs and pins of floating parts
  std::vector<char> no_fail_;  ///< per cell, 1 in a no_fail region; empty when there is none
};

}  // namespace perimorph::evolution
