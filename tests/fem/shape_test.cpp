// Q1 shape functions: partition of unity, Kronecker property, gradients, and
// the isoparametric map.
#include "perimorph/fem/shape.hpp"
#include "perimorph/mesh/cell_type.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace perimorph::fem {
namespace {

std::vector<Vec3> sample_points(int D, int count, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < count; ++i) {
    Vec3 xi = Vec3::Zero();
    for (int d = 0; d < D; ++d) xi[d] = u(gen);
    pts.push_back(xi);
  }
  pts.push_back(Vec3::Zero());
  return pts;
}

Vec3 reference_node(int D, int a) {
  Vec3 xi = Vec3::Zero();
  for (int d = 0; d < D; ++d) xi[d] = mesh::reference_node_coordinate(a, d);
  return xi;
}

template <int D>
void check_values() {
  for (const Vec3& xi : sample_points(D, 50, 11u * D)) {
    const ShapeValues<D> N = q1_values<D>(xi);
    EXPECT_NEAR(N.sum(), 1.0, 1e-15);
    // Linear completeness: Σ N_a ξ_a = ξ.
    Vec3 x = Vec3::Zero();
    for (int a = 0; a < q1_nodes<D>; ++a) {
      EXPECT_GE(N[a], 0.0);  // inside the reference cell
      x += N[a] * reference_node(D, a);
    }
    EXPECT_NEAR((x - xi).norm(), 0.0, 1e-15);
  }
  for (int a = 0; a < q1_nodes<D>; ++a) {
    const ShapeValues<D> N = q1_values<D>(reference_node(D, a));
    for (int b = 0; b < q1_nodes<D>; ++b) EXPECT_EQ(N[b], a == b ? 1.0 : 0.0) << "node " << a << ", N_" << b;
  }
}

template <int D>
void check_gradients() {
  const double h = 1e-6;
  for (const Vec3& xi : sample_points(D, 30, 7u + static_cast<unsigned>(D))) {
    const ShapeGradients<D> G = q1_reference_gradients<D>(xi);
    for (int d = 0; d < D; ++d) EXPECT_NEAR(G.row(d).sum(), 0.0, 1e-15);
    for (int d = 0; d < D; ++d) {
      Vec3 xp = xi, xm = xi;
      xp[d] += h;
      xm[d] -= h;
      const ShapeValues<D> fd = (q1_values<D>(xp) - q1_values<D>(xm)) / (2 * h);
      for (int a = 0; a < q1_nodes<D>; ++a) EXPECT_NEAR(G(d, a), fd[a], 1e-9) << "d " << d << " a " << a;
    }
  }
}

TEST(FemShape, PartitionOfUnityAndKronecker) {
  check_values<1>();
  check_values<2>();
  check_values<3>();
}

TEST(FemShape, GradientsSumToZeroAndMatchFiniteDifferences) {
  check_gradients<1>();
  check_gradients<2>();
  check_gradients<3>();
}

TEST(FemShape, KnownValuesAtCentre) {
  const auto N3 = q1_values<3>(Vec3::Zero());
  for (int a = 0; a < 8; ++a) EXPECT_EQ(N3[a], 0.125);
  const auto G2 = q1_reference_gradients<2>(Vec3::Zero());
  // ∂N_0/∂ξ = -1/4 (1 - η) at the centre.
  EXPECT_EQ(G2(0, 0), -0.25);
  EXPECT_EQ(G2(1, 0), -0.25);
  EXPECT_EQ(G2(0, 3), 0.25);
  EXPECT_EQ(G2(1, 1), -0.25);
}

/// Nodes x_a = A ξ_a + b (affine) or that plus a bilinear/trilinear
/// perturbation; either way an isoparametric element reproduces a linear field
/// u = g·x + c exactly.
template <int D>
void check_linear_reproduction(bool affine) {
  using MatD = Eigen::Matrix<double, D, D>;
  using VecD = Eigen::Matrix<double, D, 1>;
  MatD A;
  if constexpr (D == 1)
    A << 0.7;
  else if constexpr (D == 2)
    A << 1.3, 0.4, -0.2, 0.9;
  else
    A << 1.3, 0.4, 0.1, -0.2, 0.9, 0.3, 0.25, -0.15, 1.1;
  VecD b;
  for (int d = 0; d < D; ++d) b[d] = 0.5 - 0.3 * d;
  VecD g;
  for (int d = 0; d < D; ++d) g[d] = 1.5 + 2.0 * d;
  const double c = -0.75;
  NodeCoords<D> X;
  for (int a = 0; a < q1_nodes<D>; ++a) {
    X.col(a) = A * reference_node(D, a).head<D>() + b;
    if (!affine && D > 1) X(0, a) += 0.15 * (a == q1_nodes<D> - 1 ? 1.0 : 0.0);  // move the last corner
  }
  Eigen::Matrix<double, q1_nodes<D>, 1> u;
  for (int a = 0; a < q1_nodes<D>; ++a) u[a] = g.dot(X.col(a)) + c;
  for (const Vec3& xi : sample_points(D, 20, 3u)) {
    ShapeGradients<D> grad;
    const double detJ = q1_physical_gradients<D>(X, xi, grad);
    const VecD gu = grad * u;
    EXPECT_NEAR((gu - g).norm(), 0.0, 1e-12 * g.norm()) << "xi " << xi.transpose();
    // Gradients of the coordinates are the identity; of a constant, zero.
    EXPECT_NEAR((grad * X.transpose() - MatD::Identity()).norm(), 0.0, 1e-13);
    EXPECT_NEAR(grad.rowwise().sum().norm(), 0.0, 1e-13);
    if (affine) {
      EXPECT_NEAR(detJ, A.determinant(), 1e-13);
    }
    EXPECT_GT(detJ, 0.0);
  }
}

TEST(FemShape, PhysicalGradientsReproduceLinearFields) {
  check_linear_reproduction<1>(true);
  check_linear_reproduction<2>(true);
  check_linear_reproduction<3>(true);
  check_linear_reproduction<2>(false);
  check_linear_reproduction<3>(false);
}

TEST(FemShape, MirroredCellHasNegativeJacobian) {
  NodeCoords<2> X;
  for (int a = 0; a < 4; ++a) X.col(a) = reference_node(2, a).head<2>();
  X.row(0) *= -1.0;  // mirror x
  ShapeGradients<2> g;
  EXPECT_NEAR(q1_physical_gradients<2>(X, Vec3::Zero(), g), -1.0, 1e-15);
  // Unit-size cell [0, h]^3: det J = (h/2)^3.
  NodeCoords<3> Y;
  for (int a = 0; a < 8; ++a) Y.col(a) = 0.5 * (reference_node(3, a) + Vec3::Ones()) * 0.4;
  ShapeGradients<3> g3;
  EXPECT_NEAR(q1_physical_gradients<3>(Y, Vec3(0.3, -0.2, 0.9), g3), 0.2 * 0.2 * 0.2, 1e-15);
}

}  // namespace
}  // namespace perimorph::fem
