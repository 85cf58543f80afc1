#pragma once
// Pure kernels of the local model (THEORY §1, §4): small values in, a block
// out; no I/O, no PETSc, no allocation. Element dofs are node-major:
// index a·D + d for component d of node a.

#include "perimorph/fem/quadrature.hpp"
#include "perimorph/fem/shape.hpp"

#include <span>

namespace perimorph::fem {

template <int D>
inline constexpr int voigt_dim = D == 1   ? 1
                                 : D == 2 ? 3
                                          : 6;
template <int D>
inline constexpr int element_dofs = D* q1_nodes<D>;

template <int D>
using ElementMatrix = Eigen::Matrix<double, element_dofs<D>, element_dofs<D>>;
template <int D>
using ElementVector = Eigen::Matrix<double, element_dofs<D>, 1>;
template <int D>
using VoigtMatrix = Eigen::Matrix<double, voigt_dim<D>, voigt_dim<D>>;
template <int D>
using VoigtVector = Eigen::Matrix<double, voigt_dim<D>, 1>;
template <int D>
using StrainMatrix = Eigen::Matrix<double, voigt_dim<D>, element_dofs<D>>;

/// The strain–displacement matrix B (ε_voigt = B u_e) from physical shape
/// gradients; engineering shear strains, Voigt order xx, yy, (zz,) (yz, xz,) xy.
template <int D>
StrainMatrix<D> strain_displacement(const ShapeGradients<D>& g) {
  StrainMatrix<D> B = StrainMatrix<D>::Zero();
  for (int a = 0; a < q1_nodes<D>; ++a) {
    const int c = a * D;
    if constexpr (D == 1) {
      B(0, c) = g(0, a);
    } else if constexpr (D == 2) {
      B(0, c) = g(0, a);
      B(1, c + 1) = g(1, a);
      B(2, c) = g(1, a);
      B(2, c + 1) = g(0, a);
    } else {
      B(0, c) = g(0, a);
      B(1, c + 1) = g(1, a);
      B(2, c + 2) = g(2, a);
      B(3, c + 1) = g(2, a);
      B(3, c + 2) = g(1, a);
      B(4, c) = g(2, a);
      B(4, c + 2) = g(0, a);
      B(5, c) = g(1, a);
      B(5, c + 1) = g(0, a);
    }
  }
  return B;
}

/// K_e = Σ_q Bᵀ C(q) B w_q |J_q| · scale (scale: thickness in 2D, area in 1D).
/// `tensor(q)` returns a pointer to the column-major Voigt matrix at point q.
template <int D, class TensorAt>
void elasticity_stiffness(const NodeCoords<D>& X, std::span<const QuadraturePoint> rule, TensorAt&& tensor,
                          double scale, ElementMatrix<D>& K) {
  K.setZero();
  ShapeGradients<D> g;
  for (std::size_t q = 0; q < rule.size(); ++q) {
    const double detJ = q1_physical_gradients<D>(X, rule[q].xi, g);
    const StrainMatrix<D> B = strain_displacement<D>(g);
    const Eigen::Map<const VoigtMatrix<D>> C(tensor(static_cast<int>(q)));
    K.noalias() += (B.transpose() * (C * B)) * (rule[q].weight * detJ * scale);
  }
}

/// f_e = Σ_q N_a b(x_q) w_q |J_q| · scale for a body force density b(x).
template <int D, class BodyForce>
void body_force_load(const NodeCoords<D>& X, std::span<const QuadraturePoint> rule, BodyForce&& b,
                     double scale, ElementVector<D>& f) {
  f.setZero();
  ShapeGradients<D> g;
  for (const QuadraturePoint& q : rule) {
    const double detJ = q1_physical_gradients<D>(X, q.xi, g);
    const ShapeValues<D> N = q1_values<D>(q.xi);
    const Eigen::Matrix<double, D, 1> x = X * N;
    Vec3 x3 = Vec3::Zero();
    x3.template head<D>() = x;
    const Vec3 bx = b(x3);
    for (int a = 0; a < q1_nodes<D>; ++a)
      for (int d = 0; d < D; ++d) f[a * D + d] += N[a] * bx[d] * q.weight * detJ * scale;
  }
}

/// Measure element of a face at reference point s of the face cell (dimension
/// D − 1, nodes in the face's own lexicographic order): 1 for a point, the
/// half-length for an edge, |∂x/∂s × ∂x/∂t| for a quad face.
template <int D>
double face_measure(const Eigen::Matrix<double, 3, q1_nodes<D - 1>>& Y, const Vec3& s) {
  if constexpr (D == 1) {
    (void)Y;
    (void)s;
    return 1.0;
  } else {
    const ShapeGradients<D - 1> G = q1_reference_gradients<D - 1>(s);
    const Eigen::Matrix<double, 3, D - 1> T = Y * G.transpose();
    if constexpr (D == 2)
      return T.col(0).norm();
    else
      return T.col(0).cross(T.col(1)).norm();
  }
}

/// Consistent nodal loads on a face for a constant traction t (force per
/// area): f_a = ∫ N_a t dS · scale, a over the face's nodes.
template <int D>
Eigen::Matrix<double, D * q1_nodes<D - 1>, 1> face_traction_load(
    const Eigen::Matrix<double, 3, q1_nodes<D - 1>>& Y, std::span<const QuadraturePoint> face_rule,
    const Vec3& t, double scale) {
  Eigen::Matrix<double, D * q1_nodes<D - 1>, 1> f = decltype(f)::Zero();
  for (const QuadraturePoint& q : face_rule) {
    const double dS = face_measure<D>(Y, q.xi);
    Eigen::Matrix<double, q1_nodes<D - 1>, 1> N;
    if constexpr (D == 1)
      N[0] = 1.0;
    else
      N = q1_values<D - 1>(q.xi);
    for (int a = 0; a < q1_nodes<D - 1>; ++a)
      for (int d = 0; d < D; ++d) f[a * D + d] += N[a] * t[d] * q.weight * dS * scale;
  }
  return f;
}

}  // namespace perimorph::fem
