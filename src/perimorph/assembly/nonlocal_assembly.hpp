#pragma once
// The loop that applies the pair kernel (peridynamics/pair_kernel.hpp) over
// every interacting pair of cells (THEORY §4). Pair blocks are computed in
// parallel (OpenMP) for a chunk of cells and inserted in a fixed order, so the
// matrix is bit-identical for any thread count.

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/bonds/cut_neighborhood.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}
namespace perimorph::dofs {
class DofMap;
}
namespace perimorph::alpha {
class AlphaField;
}
namespace perimorph::bonds {
struct NonlocalPoints;
struct CellGraph;
class BrokenBonds;
}  // namespace perimorph::bonds

namespace perimorph::assembly {

/// A view: every reference and pointer is non-owning; the caller keeps what
/// they refer to alive while the space is used.
struct NonlocalSpace {
  const mesh::Mesh& mesh;                    ///< non-owning
  const dofs::DofMap& dofmap;                ///< non-owning
  const bonds::NonlocalPoints& points;       ///< non-owning
  const bonds::CellGraph& graph;             ///< non-owning
  const peridynamics::Micromodulus& kernel;  ///< non-owning
  /// The α field the points were made with (non-owning). Read when
  /// NonlocalOptions::precomputed_points is false, or for a cell pair whose
  /// points are not stored (then required).
  const alpha::AlphaField* alpha = nullptr;
  /// The factor make_nonlocal_points applied to every weight (thickness in 2D,
  /// cross-section in 1D, 1 in 3D). Read only when precomputed_points is false.
  double scale = 1.0;
  /// Failed bonds, left out (non-owning; null: none). Pairs with one are never cached.
  const bonds::BrokenBonds* broken = nullptr;
  /// The cuts near each cell for bonds of this space's reach (non-owning;
  /// null: made from the mesh when needed). setup::Discretization keeps one.
  const bonds::CutNeighborhood* cuts = nullptr;
  /// The cuts a bond between points of cells e and f can cross (`buffer`
  /// holds them when `cuts` is set; else all of the mesh's).
  std::span<const Cut> cuts_near(Index e, Index f, std::vector<Cut>& buffer) const {
    return cuts != nullptr ? cuts->near_pair(e, f, buffer) : std::span<const Cut>(mesh.cuts);
  }
};

struct NonlocalStats {
  std::size_t cell_pairs = 0;       ///< pairs with at least one bond
  std::size_t bonds = 0;            ///< unordered quadrature-point pairs with ᾱ c > 0
  std::size_t reused_pairs = 0;     ///< pairs whose block came from the translation cache
  std::size_t distinct_blocks = 0;  ///< blocks computed for the cache
};

/// Switches for the structural optimizations (all on by default; the P1
/// benchmark measures each against the plain version).
struct NonlocalOptions {
  /// Read the quadrature points' positions, weights and α from
  /// NonlocalSpace::points. When false (the "plain" version), every cell pair
  /// recomputes both cells' points from the mesh nodes, the reference
  /// Gauss–Legendre rule and NonlocalSpace::alpha into thread-local buffers,
  /// with the same formulas in the same order as make_nonlocal_points, so the
  /// matrix is bit-identical. Still read from `points` in both cases: the
  /// point count, the reference shape table and the per-cell α bounds (which
  /// pairs are skipped, which are unit pairs).
  bool precomputed_points = true;
  /// Pairs with α ≡ 1 on both cells use ᾱ = 1 without reading α.
  bool unit_alpha_shortcut = true;
  /// On a structured grid, pairs with α ≡ 1 on both cells, away from cuts,
  /// depend only on the cells' relative offset: each distinct block is
  /// computed once and reused. It is computed from a representative pair of
  /// box cells alone (mesh::box_cell_mesh), so a piece of the box
  /// (mesh::part_mesh) computes any representative, held or not.
  bool translation_cache = true;
  /// Only the cell pairs (e, f), e ≤ f, for which this holds (all if empty):
  /// the contribution of some cells, for an update in place
  /// (system::ConstrainedSystem::reassemble).
  std::function<bool(Index e, Index f)> include_pair;
  /// Only the pairs with a flagged cell (one flag per cell; empty: every
  /// pair), and of the graph only the flagged cells' rows are read: each pair
  /// found from either end, the pairs taken in the same order as from every
  /// row (e, then f). A process of a distributed run assembles the pairs of
  /// the cells touching its nodes (system/stiffness.hpp). With include_pair
  /// too, the pairs both admit.
  std::span<const char> rows{};
  /// With include_pair or rows and the translation cache, when the
  /// processes' included pairs together are every pair (the distributed
  /// assembly, system/stiffness.hpp): each cached block is computed from the first
  /// cacheable pair of the whole graph with its key (offset and node counts),
  /// not this process's first included one, so that every process adds the
  /// serial matrix's blocks, bit for bit. `min_over_processes`, the
  /// elementwise minimum over the processes (collective; la::), is called
  /// twice: for the largest offset, then for each key's first pair (e·N + f
  /// in box cells, StructuredLayout::box_cell, in a slot per key). Only this
  /// process's included pairs are read: no pass over the whole graph, and the
  /// representative's cells need not be in this process's mesh.
  std::function<std::vector<long long>(std::vector<long long>)> min_over_processes{};
};

/// K += K_nl. Pairs whose cells have α ≡ 0 are skipped. Bonds crossing a
/// pre-crack cut of the mesh, and failed bonds, are left out.
NonlocalStats assemble_nonlocal(const NonlocalSpace& space, MatrixInserter& K,
                                const NonlocalOptions& options = {});

}  // namespace perimorph::assembly
