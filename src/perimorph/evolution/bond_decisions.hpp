#pragma once
// Bond failure decided on several processes (issue 17, item 2): each bond is
// decided by the process of its cell e and sent only to the processes that
// hold e (a neighbour exchange, la::exchange), with a per-cell summary of the
// pass gathered by every process (a few numbers per cell where bonds break:
// the crack front, not the bonds). From the summary every process takes the
// pass's totals and each bond's place in the whole model's order, in the
// same bits whatever the number of processes: the ledger is summed per cell,
// then over the cells in whole-mesh order (THEORY §5).

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/evolution/run_state.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>
#include <vector>

namespace perimorph::evolution {

/// Where a bond's two points are (bonds::point_position of g in e, h in f).
struct BondPoints {
  Vec3 g = Vec3::Zero(), h = Vec3::Zero();
};

/// The other processes that hold each cell this process decides (collective
/// to build): on a piece those whose piece has the cell (each tells the
/// cell's process), on a part of the whole model every other process, on one
/// process none.
class CellHolders {
 public:
  CellHolders() = default;
  /// `decides`: setup::cells_of_process (empty on one process).
  CellHolders(const setup::Discretization& disc, std::span<const char> decides);
  /// The processes other than this one holding cell `c` (local number, a cell it decides).
  std::span<const int> of(Index c) const;

 private:
  bool every_process_ = false;  ///< a part of the whole model: every process holds every cell
  std::vector<int> others_;     ///< every other process (every_process_)
  std::vector<Index> offsets_;  ///< per local cell, into ranks_ (a piece)
  std::vector<int> ranks_;
};

/// A bond to break, in whole-mesh cell numbers, with what its downdate and
/// the ledger need.
struct DecidedBond {
  assembly::StretchedBond bond;  ///< id.e, id.f in whole-mesh numbers
  double critical = 0.0;         ///< its energy at s_crit (assembly::energy_at_stretch)
};

/// One breaking pass over the processes: its totals, and what each process
/// applies.
struct SharedPass {
  std::size_t count = 0;     ///< bonds broken over the model
  double dissipated = 0.0;   ///< Σ critical, per cell then over the cells in whole order
  double overshoot = 0.0;    ///< Σ (energy − critical), likewise
  double max_stretch = 0.0;  ///< the largest stretch of the pass
  /// The bonds this process holds a cell e of (its own and those sent to it),
  /// in the whole model's order (by cell e, then the deciding process's
  /// order), each with its place in the pass's order over the model.
  std::vector<DecidedBond> bonds;
  std::vector<std::size_t> place;
};

/// Shares the bonds this process decided in a pass (`mine`: in its cell
/// order, cells e ascending, in local numbers; `s_crit` for their energy at
/// the criterion) with the processes holding their cells e, and the pass's
/// per-cell summary with every process (collective where `distributed`).
SharedPass share_pass(const setup::Discretization& disc, std::span<const assembly::StretchedBond> mine,
                      double s_crit, const CellHolders& holders, bool distributed);

/// Every process's `bonds` with their `points` on process 0, in the whole
/// model's order, cells in whole-mesh numbers; nothing on the others
/// (collective where `distributed`): what process 0 alone writes.
void gather_pass_on_process_zero(const setup::Discretization& disc,
                                 std::vector<assembly::StretchedBond>& bonds, std::vector<BondPoints>& points,
                                 bool distributed);

/// The points of every bond failed over the model, in the order they failed,
/// on every process (collective): each process gives those of the cells it
/// decides, at their places (RunState::failed_place). For a piece (setup::cut_to_piece).
std::vector<std::pair<Vec3, Vec3>> failed_bond_points_over_processes(const setup::Discretization& piece,
                                                                     const RunState& state);

}  // namespace perimorph::evolution
