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
#include "perimorph/evolution/bond_decisions.hpp"
#include "perimorph/evolution/component.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <vector>

namespace perimorph::evolution {

/// The energy of bonds broken by one apply() over the model (THEORY §5):
/// `dissipated` counts each at the critical stretch, ½ W ᾱ c (s_crit |ξ|)²
/// (the per-bond energy of the G_c closed forms and of `perimorph gc`);
/// `overshoot` is what they held beyond it at the solve that found them over
/// s_crit (≥ 0; it vanishes as the load increments shrink). Each summed per
/// cell e, then over the cells in whole-mesh order: the same bits on any
/// number of processes. With how many bonds broke and their largest stretch.
struct FailureEnergy {
  double dissipated = 0.0, overshoot = 0.0;
  std::size_t count = 0;
  double max_stretch = 0.0;
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

/// Bond failure as an evolution component: inspect selects the bonds over
/// the criterion at the state's displacement, apply breaks them by downdating
/// the system (Effect::downdate). Dofs left with no stiffness and parts cut
/// free are the next component's (PartSupport, part_support.hpp).
class BondFailure final : public Component {
 public:
  explicit BondFailure(const setup::Discretization& disc);

  std::string_view name() const override { return "bond failure"; }
  /// Keeps select(state) as the proposal; its size is the number of bonds
  /// over the model (collective on several processes).
  Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) override;
  /// Breaks the proposed bonds (apply below); Effect::downdate.
  Effect apply(RunState& state, system::ConstrainedSystem& system) override;
  void rebind(const setup::Discretization& disc, RunState& /*state*/,
              system::ConstrainedSystem& /*system*/) override {
    bind(disc);
  }
  /// Nothing is kept between increments but the discretization.
  void restore(const setup::Discretization& disc, core::BinaryReader& /*in*/) override { bind(disc); }

  /// The bonds this process proposed at the last inspect (what the last
  /// apply broke of its cells), and where their points are.
  const std::vector<assembly::StretchedBond>& proposed() const { return proposed_; }
  const std::vector<BondPoints>& proposed_points() const { return proposed_points_; }
  /// Every process's proposed bonds and points on process 0, in the whole
  /// model's order, cells in whole-mesh numbers (empty on the others;
  /// collective): what it writes.
  void proposed_on_process_zero(std::vector<assembly::StretchedBond>& bonds,
                                std::vector<BondPoints>& points) const;
  /// Their energy and count over the model, from the last apply.
  const FailureEnergy& applied_energy() const { return applied_; }
  /// The space the stiffness is assembled with, the state's failed bonds left out.
  assembly::NonlocalSpace space(const RunState& state) const;
  double s_crit() const { return s_crit_; }

  /// The intact bonds of `state` to break at its displacement: those with
  /// s > s_crit, or with rule = fraction those with s ≥ fraction · the
  /// largest such s; bonds with an end in a [fracture] no_fail region, and
  /// with intra_cell_failure = false bonds between two points of one cell,
  /// and with [material.damage] bonds with an end whose damage is below d_c
  /// (THEORY §6), are never selected. Grouped by cell pair, cells e
  /// ascending. On several processes, the bonds {e, f} (e ≤ f) of the cells e
  /// this process decides (cells_of_process; the fraction rule's largest
  /// stretch is the model's: collective). `points`, if given, gets where
  /// each bond's points are.
  std::vector<assembly::StretchedBond> select(const RunState& state,
                                              std::vector<BondPoints>* points = nullptr) const;

  /// Breaks `bonds` (from select at the state's displacement) and, on several
  /// processes, the other processes' (collective): each process sends its
  /// bonds to the processes that hold their cells e (bond_decisions.hpp).
  /// Records in the state the bonds whose two cells it holds (failed bonds,
  /// in the whole model's order, and on a piece their places in it; D per
  /// cell), the count over the model and D and overshoot in the ledger, and
  /// downdates `system` by their blocks (ConstrainedSystem::downdate): K −=
  /// the blocks; A −= them on free rows and columns; the right-hand side takes
  /// their prescribed columns. Finalizes K and A. Returns their energy, at
  /// s_crit and beyond it, and count over the model.
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
  /// Per axis, the count of faces times a face's area: the same bits on any
  /// number of processes. On several processes each looks at its cells'
  /// faces, and each column is counted by one process (collective).
  CrackArea crack_area(const RunState& state) const;

 private:
  /// Onto `disc` (a rebuilt piece numbers its cells anew): its no-fail and decided cells.
  void bind(const setup::Discretization& disc);
  const setup::Discretization* disc_;  ///< non-owning: the run's current discretization
  double s_crit_ = 0.0;
  std::vector<char> no_fail_;  ///< per cell, 1 in a no_fail region; empty when there is none
  /// On several processes, per cell, 1 where this process decides the cell's
  /// bonds {e, f} (e ≤ f): the cells of its part (partition::coordinate_bisection,
  /// as the assembly's). Empty on one process.
  std::vector<char> decides_;
  CellHolders holders_;  ///< the other processes holding each decided cell
  std::vector<assembly::StretchedBond> proposed_;
  std::vector<BondPoints> proposed_points_;
  FailureEnergy applied_;
};

}  // namespace perimorph::evolution
