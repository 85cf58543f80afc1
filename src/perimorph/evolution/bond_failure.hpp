#pragma once
// Bond failure by critical stretch (THEORY §5), the first evolution component
// (component.hpp): which bonds break after a solve, and the incremental
// update of the assembled matrices when they do.
// A failed bond's block (pair_kernel.hpp, bond_block) is subtracted from K
// and from the constrained copy A, and the right-hand side is corrected for
// its columns on prescribed dofs; nothing is reassembled, so one update costs
// O(newly failed bonds).

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/evolution/component.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <vector>

namespace perimorph::evolution {

/// The energy of bonds broken by one apply() (THEORY §5): `dissipated` counts
/// each at the critical stretch, ½ W ᾱ c (s_crit |ξ|)² (the per-bond energy of
/// the G_c closed forms and of `perimorph gc`); `overshoot` is what they held
/// beyond it at the solve that found them over s_crit (≥ 0; it vanishes as the
/// load increments shrink).
struct FailureEnergy {
  double dissipated = 0.0, overshoot = 0.0;
};

/// Per-cell fracture fields for the VTU (empty for a run without [fracture]),
/// for the cells it writes, in their order.
struct FractureFields {
  std::vector<double> damage;      ///< fraction of bond weight lost, mean over the cell's points
  std::vector<double> dissipated;  ///< energy of the failed bonds at s_crit, half to each end's cell
};

/// `total`: the area of every broken face. `projected`: for each normal
/// axis, the broken faces with that normal projected along it (a face position
/// counted once however many rows of faces are broken there), the largest
/// over the axes: the area of a crack running across that axis, not inflated
/// by a band of failed cells. NaN on an unstructured mesh.
struct CrackArea {
  double total = 0.0, projected = 0.0;
};

/// Where a bond's two points are (bonds::point_position of g in e, h in f).
struct BondPoints {
  Vec3 g = Vec3::Zero(), h = Vec3::Zero();
};

/// Bond failure as an evolution component: inspect selects the bonds over
/// the criterion at the state's displacement, apply breaks them by downdating
/// the system (Effect::downdate). Dofs left with no stiffness and parts cut
/// free are the next component's (PartSupport, part_support.hpp).
class BondFailure final : public Component {
 public:
  explicit BondFailure(const setup::Discretization& disc);

  std::string_view name() const override { return "bond failure"; }
  /// Keeps select(state) as the proposal; its size is the number of bonds.
  Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) override;
  /// Breaks the proposed bonds (apply below); Effect::downdate.
  Effect apply(RunState& state, system::ConstrainedSystem& system) override;
  void rebind(const setup::Discretization& disc, RunState& /*state*/,
              system::ConstrainedSystem& /*system*/) override {
    bind(disc);
  }
  /// Nothing is kept between increments but the discretization.
  void restore(const setup::Discretization& disc, core::BinaryReader& /*in*/) override { bind(disc); }

  /// The bonds proposed by the last inspect (what the last apply broke), and
  /// where their points are (on a piece of the model, the points of bonds it
  /// does not hold too).
  const std::vector<assembly::StretchedBond>& proposed() const { return proposed_; }
  const std::vector<BondPoints>& proposed_points() const { return proposed_points_; }
  /// Their energy, from the last apply.
  const FailureEnergy& applied_energy() const { return applied_; }
  /// The space the stiffness is assembled with, the state's failed bonds left out.
  assembly::NonlocalSpace space(const RunState& state) const;
  double s_crit() const { return s_crit_; }

  /// The intact bonds of `state` to break at its displacement: those with
  /// s > s_crit, or with rule = fraction those with s ≥ fraction · the
  /// largest such s; bonds with an end in a [fracture] no_fail region, and
  /// with intra_cell_failure = false bonds between two points of one cell,
  /// and with [material.damage] bonds with an end whose damage is below d_c
  /// (THEORY §6), are never selected. Grouped by cell pair. On several
  /// processes each decides the bonds of its cells and the decisions are
  /// gathered (in whole-mesh cell numbers, with their points' positions):
  /// every process gets the same list, in the one-process order. On a piece
  /// of the model (setup::cut_to_piece) the cells are given back in local
  /// numbers, and a bond whose two cells the piece does not both hold has
  /// e = f = −1 (it touches no row the process owns: a piece holds every
  /// cell bonded to a cell with a node it owns). `points`, if given, gets
  /// where each bond's points are.
  std::vector<assembly::StretchedBond> select(const RunState& state,
                                              std::vector<BondPoints>* points = nullptr) const;

  /// Breaks `bonds` (from select at the state's displacement): records them in
  /// the state (failed bonds, their count over the model and, on a piece,
  /// their places in its order, D and overshoot in the ledger, D per cell; a
  /// bond a piece does not hold, e = −1, in the ledger and count only) and
  /// downdates `system` by their blocks (ConstrainedSystem::downdate): K −=
  /// the blocks; A −= them on free rows and columns; the right-hand side takes
  /// their prescribed columns. Finalizes K and A. Returns their energy, at
  /// s_crit and beyond it.
  FailureEnergy apply(const std::vector<assembly::StretchedBond>& bonds, RunState& state,
                      system::ConstrainedSystem& system) const;

  /// A bond's dofs and the shape values of its two points, in pair_kernel.hpp
  /// bond_block's layout: the dofs of E's nodes, then F's (E's alone when
  /// E = F); N_g over E's nodes, N_h over F's (a DG0 cell's one node: 1).
  /// The pointers are into the discretization's points (or a static 1).
  struct BondShape {
    std::vector<Index> dofs;
    const double* Ng = nullptr;
    const double* Nh = nullptr;
    int nE = 0, nF = 0;
    bool same_cell = false;
  };
  /// `b`'s BondShape (its dofs written into `out.dofs`, reusing its storage).
  void shape_of(const assembly::StretchedBond& b, BondShape& out) const;

  /// Damage index and dissipated energy (at s_crit) of each of `cells` (in
  /// that order; every cell if empty), for the VTU. On several processes the
  /// damage index of a cell of another process's part is NaN (the output asks
  /// for its piece's cells only, all of them this process's).
  FractureFields fields(const RunState& state, std::span<const Index> cells = {}) const;
  /// Crack area from the faces between adjacent cells all of whose bonds
  /// have failed (structured meshes; 2D: length × thickness; 1D: the
  /// cross-section). Pre-crack cuts are not counted (their bonds never existed).
  /// On several processes each looks at its cells' faces (collective).
  CrackArea crack_area(const RunState& state) const;

 private:
  /// Onto `disc` (a rebuilt piece numbers its cells anew): its no-fail and decided cells.
  void bind(const setup::Discretization& disc);
  /// The interfaces all of whose bonds have failed, in cell order, on every
  /// process (each process finds those of its cells e; collective); on
  /// several processes in whole-mesh cell numbers.
  std::vector<assembly::InterfaceBonds> broken_interfaces(const RunState& state) const;
  const setup::Discretization* disc_;  ///< non-owning: the run's current discretization
  double s_crit_ = 0.0;
  std::vector<char> no_fail_;  ///< per cell, 1 in a no_fail region; empty when there is none
  /// On several processes, per cell, 1 where this process decides the cell's
  /// bonds {e, f} (e ≤ f): the cells of its part (partition::coordinate_bisection,
  /// as the assembly's). Empty on one process.
  std::vector<char> decides_;
  std::vector<assembly::StretchedBond> proposed_;
  std::vector<BondPoints> proposed_points_;
  FailureEnergy applied_;
};

}  // namespace perimorph::evolution
