#pragma once
// A process's part built on a window of a box mesh (issue 17, item 1): the
// grid's cells in an index range around its part, wide enough for every cell
// the part reads, instead of the whole mesh. What the window's set-up asks of
// the other processes, and what its cells and nodes are in the whole mesh.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/partition/grid_bisection.hpp"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace perimorph::setup {

/// What a check made on a window of the mesh needs of the whole mesh: whether
/// a condition holds on any process (collective; la::), and the whole mesh's
/// bounds, for its message. Default: the mesh checked is the whole mesh.
struct WholeMeshChecks {
  std::function<bool(bool)> any_over_processes{};
  std::optional<std::pair<Vec3, Vec3>> bounds{};

  bool any(bool holds) const { return any_over_processes ? any_over_processes(holds) : holds; }
  std::pair<Vec3, Vec3> bounds_of(const mesh::Mesh& m) const { return bounds ? *bounds : m.bounding_box(); }
};

/// The window a part is built on (ModelPart::window): the box grid's cells
/// lo ≤ (i, j, k) < hi, the part of each (partition::GridBisection, in the
/// window's order), and the collective operations its set-up needs.
struct MeshWindow {
  std::array<Index, 3> lo{}, hi{};
  std::vector<int> owner;
  std::function<bool(bool)> any_over_processes{};
  /// The maximum of a value over the processes (NonlocalPoints::half_bound,
  /// a bound over every cell of the whole mesh).
  std::function<double(double)> max_over_processes{};
};

/// What a part built on a window is in the whole mesh (Discretization::window).
struct WindowNumbers {
  std::array<Index, 3> lo{}, hi{};
  /// The global number of each cell and node of the window, ascending.
  std::vector<Index> global_cell, global_node;
  Index whole_cells = 0, whole_nodes = 0;
  /// NonlocalPoints::half_bound over the whole mesh (kept for a rebuild for α).
  double half_bound = 0.0;
};

/// The box of the case's [mesh] (its grid: mesh::make_box's spec).
mesh::BoxSpec box_of(const casefile::CaseConfig& config);

/// The bisection of the case's box into `parts` (partition::GridBisection):
/// what coordinate_bisection gives its whole mesh.
partition::GridBisection grid_bisection(const casefile::CaseConfig& config, int parts);

/// Whether a part of the case can be built on a window: a box mesh without
/// holes or pre-crack cuts (their cells and nodes are numbered over the whole
/// mesh).
bool has_windows(const casefile::CaseConfig& config);

/// The window of part `part` of `grid` (the bisection of the case's box):
/// the box of the part's cells widened along each axis d by the cells a cell
/// the part computes can read — 1 for its node neighbours, then
/// ⌈(δ + |h|) / h_d⌉ for the bonds (a bond reaches δ + 2·half_bound, and a
/// point box's half-width is at most half the cell's diagonal |h|) or, with
/// the matrix-free operator, ⌈δ / h_min⌉ + 1 (the patch of its blocks) — and
/// one cell more, so that no cell read lies on a side where the window cuts
/// the grid (cut_to_piece checks it); with the owner of each of its cells.
/// The collective operations are left to the caller.
MeshWindow part_window(const casefile::CaseConfig& config, const partition::GridBisection& grid, int part);

/// The mesh of a part built on `w` (ModelPart::window): the window of the
/// case's box (mesh::make_box_window) with the case's regions and node sets
/// (shape_mesh, checked over the processes), and `numbers`, what its cells
/// and nodes are in the whole mesh (half_bound left 0). Collective.
mesh::Mesh window_mesh(const casefile::CaseConfig& config, const MeshWindow& w,
                       std::shared_ptr<WindowNumbers>& numbers);

}  // namespace perimorph::setup
