#pragma once
// Multilinear (Q1) shape functions on the reference cell [-1, 1]^D and the
// isoparametric map (THEORY §4). Pure, allocation-free, fixed-size.

#include "perimorph/core/types.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace perimorph::fem {

template <int D>
inline constexpr int q1_nodes = 1 << D;

template <int D>
using NodeCoords = Eigen::Matrix<double, D, q1_nodes<D>>;  ///< column a = node a

template <int D>
using ShapeValues = Eigen::Matrix<double, q1_nodes<D>, 1>;

template <int D>
using ShapeGradients = Eigen::Matrix<double, D, q1_nodes<D>>;  ///< column a = ∇N_a

/// N_a(ξ) = Π_d (1 + ξ_a,d ξ_d) / 2, with ξ_a,d = ±1 the node's reference coordinates.
template <int D>
ShapeValues<D> q1_values(const Vec3& xi) {
  ShapeValues<D> N;
  for (int a = 0; a < q1_nodes<D>; ++a) {
    double v = 1.0;
    for (int d = 0; d < D; ++d) v *= 0.5 * (1.0 + (((a >> d) & 1) ? 1.0 : -1.0) * xi[d]);
    N[a] = v;
  }
  return N;
}

/// Reference gradients ∂N_a/∂ξ_d.
template <int D>
ShapeGradients<D> q1_reference_gradients(const Vec3& xi) {
  ShapeGradients<D> G;
  for (int a = 0; a < q1_nodes<D>; ++a)
    for (int d = 0; d < D; ++d) {
      double v = 1.0;
      for (int e = 0; e < D; ++e) {
        const double s = ((a >> e) & 1) ? 1.0 : -1.0;
        v *= e == d ? 0.5 * s : 0.5 * (1.0 + s * xi[e]);
      }
      G(d, a) = v;
    }
  return G;
}

/// Physical gradients and Jacobian determinant at ξ for a cell with node
/// coordinates X. Returns det J (positive for a valid cell).
template <int D>
double q1_physical_gradients(const NodeCoords<D>& X, const Vec3& xi, ShapeGradients<D>& grad) {
  const ShapeGradients<D> G = q1_reference_gradients<D>(xi);
  const Eigen::Matrix<double, D, D> J = X * G.transpose();  // J_ij = ∂x_i/∂ξ_j
  grad = J.transpose().inverse() * G;
  return J.determinant();
}

/// Half-widths of the box a quadrature point stands for (the partial-volume
/// option of the bond quadrature, peridynamics/horizon_edge.hpp): the point's
/// share of the cell, b_i = ½ Σ_d |∂x_i/∂ξ_d| w_d with w_d its 1D Gauss weights
/// (on an axis-aligned box cell the boxes of a tensor rule tile the cell).
template <int D>
Vec3 q1_point_box_half_widths(const NodeCoords<D>& X, const Vec3& xi, const Vec3& line_weights) {
  const Eigen::Matrix<double, D, D> J = X * q1_reference_gradients<D>(xi).transpose();
  Vec3 b = Vec3::Zero();
  for (int i = 0; i < D; ++i)
    for (int d = 0; d < D; ++d) b[i] += 0.5 * std::abs(J(i, d)) * line_weights[d];
  return b;
}

}  // namespace perimorph::fem
