#pragma once
// The quadrature points of the non-local double integral (THEORY §4): their
// positions, weights w|J| (× thickness in 2D, × area in 1D) and α, computed
// once and stored flat (cell c, point q at index c·n + q). The non-local
// quadrature order is its own input, separate from the local one.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/core/types.hpp"

#include <cassert>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}

namespace perimorph::bonds {

struct NonlocalPoints {
  int dim = 3;
  int per_cell = 0;
  std::vector<Vec3> x;
  std::vector<double> weight;
  std::vector<double> alpha;
  /// Reference Q1 shape values at the points: per_cell × nodes_per_cell,
  /// row q = point q (identical for every cell).
  std::vector<double> shape;
  std::vector<double> cell_alpha_max, cell_alpha_min;
  /// Partial-volume option (peridynamics/horizon_edge.hpp): each point's box
  /// half-widths; empty for the plain cut-off (a bond counts iff |ξ| < δ).
  std::vector<Vec3> half;
  /// max over points of |half|: a bond's reach Σ_i |e_i| (b_gi + b_hi) is at
  /// most |b_g| + |b_h|, so bonds reach at most δ + 2·half_bound.
  double half_bound = 0.0;

  bool partial_volume() const { return !half.empty(); }
  /// Largest point separation that can carry a bond.
  double bond_reach(double horizon) const { return horizon + 2.0 * half_bound; }

  Index num_cells() const { return static_cast<Index>(cell_alpha_max.size()); }
  std::size_t index(Index c, int q) const {
    assert(c >= 0 && c < num_cells() && q >= 0 && q < per_cell);
    return static_cast<std::size_t>(c) * static_cast<std::size_t>(per_cell) + static_cast<std::size_t>(q);
  }
};

/// Points of an n-per-direction Gauss–Legendre rule in every cell, with α
/// evaluated at each; `scale` multiplies every weight (thickness or area).
/// `partial_volume` also stores each point's box (NonlocalPoints::half).
NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume = false);

}  // namespace perimorph::bonds
