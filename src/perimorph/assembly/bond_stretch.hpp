#pragma once
// Bond stretches of a displacement field (THEORY §1, §5): s = η/|ξ| with
// η = e·(u(x_h) − u(x_g)), u interpolated at the non-local points by the
// cells' shape functions, for the same bonds as the non-local stiffness
// (ᾱ c_bond > 0, not crossing a cut, not failed). Deterministic: the result
// is in the order (e, f, g, h) for any thread count.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/bonds/broken_bonds.hpp"

#include <array>
#include <span>
#include <vector>

namespace perimorph::assembly {

struct StretchedBond {
  bonds::BondId id;    ///< canonical (e ≤ f)
  double stretch = 0;  ///< s
  double energy = 0;   ///< ½ W ᾱ c_bond η², the energy the bond stores (THEORY §1)
  double k = 0;        ///< W ᾱ c_bond / |ξ|²: the bond's block is k ξξᵀ ⊗ v vᵀ (pair_kernel.hpp)
  Vec3 xi = Vec3::Zero();
};

/// The energy the bond held when its stretch was `s` instead of b.stretch:
/// ½ W ᾱ c (s |ξ|)² = b.energy (s / b.stretch)² (THEORY §5: at s = s_crit, the
/// energy a failed bond dissipates).
inline double energy_at_stretch(const StretchedBond& b, double s) {
  const double ratio = s / b.stretch;
  return b.energy * ratio * ratio;
}

/// The displacement at every non-local point (point k of NonlocalPoints at k).
std::vector<Vec3> point_displacements(const NonlocalSpace& space, std::span<const double> u);

/// Every intact bond with s > threshold (tension only), with its energy.
/// With `cells` (one flag per cell), only the bonds {e, f} (e ≤ f) whose cell
/// e is flagged: each bond is looked at from one flagged set of a partition.
std::vector<StretchedBond> bonds_over(const NonlocalSpace& space, std::span<const double> u, double threshold,
                                      std::span<const char> cells = {});

/// Per non-local point: Σ over its bonds of W ᾱ c_bond |ξ|² (total) and the
/// part carried by failed bonds (lost). Damage index = lost / total (0 where
/// total = 0). Cut bonds count in neither. Computed in parallel, the same for
/// any thread count. With `cells` (one flag per cell), only the points of the
/// flagged cells are summed, each the same bits as in the whole pass (a cell
/// reads its own graph row only); the others' stay 0.
struct BondWeights {
  std::vector<double> total, lost;
};
BondWeights point_bond_weights(const NonlocalSpace& space, std::span<const char> cells = {});

/// The damage index of each of `cells` (in that order): the mean over the
/// cell's points of lost / total (point_bond_weights, 0 where total = 0), the
/// same bits as from point_bond_weights' arrays, with no array longer than
/// the list (the output's field for the cells it writes). Each cell reads its
/// own graph row.
std::vector<double> cell_damage(const NonlocalSpace& space, std::span<const Index> cells);

/// The bonds of the space: unordered pairs of non-local points with
/// ᾱ c_bond > 0 not crossing a cut, failed ones included (the bonds of the
/// non-local stiffness before any failure: NonlocalStats::bonds), and the cell
/// pairs (e ≤ f) that hold at least one (NonlocalStats::cell_pairs).
struct BondCount {
  std::size_t bonds = 0, cell_pairs = 0;
};
BondCount count_bonds(const NonlocalSpace& space);

/// Whether cells e and f share at least one intact bond (either order).
/// Stops at the first one found.
bool has_intact_bond(const NonlocalSpace& space, Index e, Index f);

/// Every cell pair {e, f} (e ≤ f, e = f included) joined by at least one
/// intact bond, sorted. Costs one bond per pair where none has failed. With
/// `cells` (one flag per cell), only the pairs whose cell e is flagged (each
/// pair from one part of a partition; only the flagged cells' graph rows read).
std::vector<std::array<Index, 2>> bonded_pairs(const NonlocalSpace& space, std::span<const char> cells = {});

/// The bonds between each pair of face-adjacent cells of a structured mesh
/// (cells e < f differing by one in one index), and how many have failed.
/// Bonds crossing a cut are in neither count. In cell order e; with `cells`
/// (a flag per cell), the pairs of the flagged cells e only (a process's
/// share: its bonds' work falls with the number of processes).
struct InterfaceBonds {
  Index e = 0, f = 0;
  int axis = 0;  ///< the axis normal to the shared face
  std::size_t total = 0, failed = 0;
};
std::vector<InterfaceBonds> interface_bonds(const NonlocalSpace& space, std::span<const char> cells = {});

}  // namespace perimorph::assembly
