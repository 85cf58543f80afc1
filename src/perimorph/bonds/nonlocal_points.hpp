#pragma once
// The quadrature points of the non-local double integral (THEORY §4): their
// positions, weights w|J| (× thickness in 2D, × area in 1D) and α, computed
// once and stored flat, cell by cell. The non-local quadrature order is its
// own input, separate from the local one.
//
// A process of a distributed run (issue 17) stores the points of the cells
// its part reads only (store_points); the per-cell α bounds, the point boxes'
// bound and the rule are kept for every cell, and a point of a cell not
// stored is recomputed from the mesh, bit for bit (point_position).

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/fem/quadrature.hpp"

#include <cassert>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}

namespace perimorph::bonds {

struct NonlocalPoints {
  int dim = 3;
  int per_cell = 0;
  /// Per stored point (cell c, point q at index(c, q)).
  std::vector<Vec3> x;
  std::vector<double> weight;
  std::vector<double> alpha;
  /// Partial-volume option (peridynamics/horizon_edge.hpp): each stored
  /// point's box half-widths; empty for the plain cut-off (a bond counts iff
  /// |ξ| < δ).
  std::vector<Vec3> half;
  /// Reference Q1 shape values at the points: per_cell × nodes_per_cell,
  /// row q = point q (identical for every cell).
  std::vector<double> shape;
  /// Per cell of the mesh, stored or not: the extreme α at its points.
  std::vector<double> cell_alpha_max, cell_alpha_min;
  /// max over every point of the mesh of |half|: a bond's reach
  /// Σ_i |e_i| (b_gi + b_hi) is at most |b_g| + |b_h|, so bonds reach at most
  /// δ + 2·half_bound.
  double half_bound = 0.0;
  /// How the points were made: the reference rule, its 1D weights (partial
  /// volume only) and the factor on every weight.
  std::vector<fem::QuadraturePoint> rule;
  std::vector<Vec3> line_weights;
  double scale = 1.0;
  /// The cells whose points are stored, ascending, when not every cell's
  /// are; `slot[c]` is c's position among them, −1 when not stored. Both
  /// empty: every cell's points are stored, cell c's from c·per_cell.
  std::vector<Index> stored;
  std::vector<Index> slot;

  bool partial_volume() const { return !half.empty() || !line_weights.empty(); }
  /// Largest point separation that can carry a bond.
  double bond_reach(double horizon) const { return horizon + 2.0 * half_bound; }

  Index num_cells() const { return static_cast<Index>(cell_alpha_max.size()); }
  bool holds_every_cell() const { return slot.empty(); }
  bool holds(Index c) const { return slot.empty() || slot[static_cast<std::size_t>(c)] >= 0; }
  /// index(c, 0), checked in every build that c's points are stored: for
  /// the passes that enter a cell or a cell pair (once, not per bond).
  std::size_t first(Index c) const;
  std::size_t index(Index c, int q) const {
    assert(c >= 0 && c < num_cells() && q >= 0 && q < per_cell);
    const Index s = slot.empty() ? c : slot[static_cast<std::size_t>(c)];
    assert(s >= 0 && "the points of this cell are not stored on this process");
    return static_cast<std::size_t>(s) * static_cast<std::size_t>(per_cell) + static_cast<std::size_t>(q);
  }
};

/// Points of an n-per-direction Gauss–Legendre rule in every cell, with α
/// evaluated at each; `scale` multiplies every weight (thickness or area).
/// `partial_volume` also stores each point's box (NonlocalPoints::half).
NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume = false);

/// The same per-cell α bounds, half_bound, shape and rule, but the points of
/// the flagged cells only (one flag per cell; none flagged: none stored):
/// what a process of a distributed run holds. Their values are those of
/// make_nonlocal_points, bit for bit.
NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume,
                                    std::span<const char> stored_cells);

/// Stores the points of the flagged cells (one flag per cell) in p, made by
/// the function above, in place of those it held.
void store_points(NonlocalPoints& p, const mesh::Mesh& mesh, const alpha::AlphaField& alpha,
                  std::span<const char> cells);

/// The points of the listed cells (ascending, each once): cell k of the
/// result is cells[k], its α bounds, and its points if `p` stores them (the
/// same bits); half_bound, shape and rule are `p`'s (bounds over every cell
/// of the model). A process's piece of a model (setup::cut_to_piece).
NonlocalPoints points_of_cells(const NonlocalPoints& p, std::span<const Index> cells);

/// Position of point q of cell c, stored or not (recomputed from the mesh
/// with the same expressions: the stored value, bit for bit).
Vec3 point_position(const mesh::Mesh& mesh, const NonlocalPoints& points, Index c, int q);

/// The positions of every point of cell c (per_cell of them), the same way.
void point_positions(const mesh::Mesh& mesh, const NonlocalPoints& points, Index c, Vec3* out);

/// The points of cell c as make_nonlocal_points computes them, written to
/// x[q], weight[q] and alpha[q] (q < rule.size()), and half[q] when
/// line_weights is not empty; any output may be null.
void compute_cell_points(const mesh::Mesh& mesh, Index c, std::span<const fem::QuadraturePoint> rule,
                         std::span<const Vec3> line_weights, double scale, const alpha::AlphaField& alpha,
                         Vec3* x, double* weight, double* alpha_out, Vec3* half);

}  // namespace perimorph::bonds
