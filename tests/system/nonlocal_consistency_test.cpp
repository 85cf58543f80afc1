// Consistency of the hybrid operator (issue 3, item 7): α ≡ 0 is plain FEM
// exactly; α ≡ 1 with DG degree 0 is the meshfree peridynamic sum; a uniform
// strain in the interior of a fully non-local block is in equilibrium; the
// assembled matrix is bit-identical for 1 and 2 threads.

#include "perimorph/la/vector.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>
#include <omp.h>
#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <limits>

namespace perimorph {
namespace {

using casefile::KernelKind;

Eigen::MatrixXd dense_stiffness(const casefile::CaseConfig& c) {
  const auto model = setup::build_discretization(c);
  return system::assemble_stiffness(model).K.to_dense();
}

TEST(NonlocalConsistency, AlphaZeroIsPlainFemExactly) {
  for (int dim : {1, 2, 3}) {
    auto local = testing::box_case(dim, {6, 5, 4}, Vec3(3.0, 2.5, 2.0), 100.0, dim == 1 ? 0.3 : 0.25);
    auto hybrid = local;
    testing::add_nonlocal(hybrid, KernelKind::gaussian, 1.1, 0.4, 3);
    hybrid.alpha.value = 0.0;
    const Eigen::MatrixXd A = dense_stiffness(local), B = dense_stiffness(hybrid);
    ASSERT_EQ(A.rows(), B.rows());
    EXPECT_EQ((A - B).cwiseAbs().maxCoeff(), 0.0) << "dim " << dim;
  }
}

/// Independent meshfree sum: one node per cell at its centroid, weight = cell
/// volume, K += V_i V_j c(r) e eᵀ [[1, −1], [−1, 1]] for every pair closer than δ.
Eigen::MatrixXd meshfree_stiffness(int dim, std::array<Index, 3> n, Vec3 extent, double delta, double scale,
                                   double thickness) {
  std::vector<Vec3> x;
  Vec3 h = Vec3::Ones();
  for (int d = 0; d < dim; ++d) h[d] = extent[d] / static_cast<double>(n[static_cast<std::size_t>(d)]);
  double V = 1.0;
  for (int d = 0; d < dim; ++d) V *= h[d];
  V *= thickness;
  for (Index k = 0; k < (dim > 2 ? n[2] : 1); ++k)
    for (Index j = 0; j < (dim > 1 ? n[1] : 1); ++j)
      for (Index i = 0; i < n[0]; ++i) {
        Vec3 p = Vec3::Zero();
        p[0] = (i + 0.5) * h[0];
        if (dim > 1) p[1] = (j + 0.5) * h[1];
        if (dim > 2) p[2] = (k + 0.5) * h[2];
        x.push_back(p);
      }
  const auto N = static_cast<Index>(x.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N * dim, N * dim);
  for (Index a = 0; a < N; ++a)
    for (Index b = a + 1; b < N; ++b) {
      const Vec3 xi = x[static_cast<std::size_t>(b)] - x[static_cast<std::size_t>(a)];
      const double r = xi.norm();
      if (r >= delta) continue;
      const double l = delta / 3.0;
      const double c = scale * r * r * std::exp(-r * r / (l * l));  // gaussian kernel
      const Eigen::MatrixXd G = V * V * c / (r * r) * (xi.head(dim) * xi.head(dim).transpose());
      K.block(a * dim, a * dim, dim, dim) += G;
      K.block(b * dim, b * dim, dim, dim) += G;
      K.block(a * dim, b * dim, dim, dim) -= G;
      K.block(b * dim, a * dim, dim, dim) -= G;
    }
  return K;
}

TEST(NonlocalConsistency, AlphaOneDegreeZeroIsMeshfreeSum) {
  for (int dim : {1, 2, 3}) {
    const std::array<Index, 3> n{7, 6, 5};
    const Vec3 extent(3.5, 3.0, 2.5);
    const double delta = 1.6;  // δ/h = 3.2
    auto c = testing::box_case(dim, n, extent, 300.0, dim == 1 ? 0.0 : 0.25);
    c.model.thickness = 0.7;
    testing::add_nonlocal(c, KernelKind::gaussian, delta, delta / 3.0, 1,
                          casefile::Discretization::discontinuous_constant);
    c.alpha.value = 1.0;
    const auto model = setup::build_discretization(c);
    const Eigen::MatrixXd A = system::assemble_stiffness(model).K.to_dense();
    const Eigen::MatrixXd B =
        meshfree_stiffness(dim, n, extent, delta, model.nonlocal->kernel.scale, dim == 3 ? 1.0 : 0.7);
    ASSERT_EQ(A.rows(), B.rows()) << "dim " << dim;
    EXPECT_LT((A - B).cwiseAbs().maxCoeff(), 1e-12 * B.cwiseAbs().maxCoeff()) << "dim " << dim;
  }
}

/// Max |K u| over interior and boundary dofs for u = G x on every dof node of
/// a fully non-local unit box; interior: farther than δ + h from the boundary.
std::pair<double, double> uniform_strain_residual(
    int dim, casefile::Discretization dg, int quadrature,
    casefile::HorizonEdge edge = casefile::HorizonEdge::cutoff,
    const std::function<void(casefile::CaseConfig&)>& customize = {}) {
  const Index n = dim == 2 ? 12 : 10;
  auto c = testing::box_case(dim, {n, n, n}, Vec3::Constant(1.0), 1.0, 0.25);
  if (customize) customize(c);
  const double h = 1.0 / n, delta = 2.5 * h;
  testing::add_nonlocal(c, KernelKind::exponential, delta, delta / 5, quadrature, dg);
  c.nonlocal.horizon_edge = edge;
  c.alpha.value = 1.0;
  const auto model = setup::build_discretization(c);
  auto K = system::assemble_stiffness(model).K;
  std::vector<double> uv(static_cast<std::size_t>(model.dofmap.num_dofs()));
  Mat3 G;
  G << 1e-3, 2e-4, 0, 4e-4, -5e-4, 1e-4, 0, 3e-4, 2e-4;
  for (Index a = 0; a < model.dofmap.num_nodes(); ++a) {
    const Vec3 ua = G * model.dofmap.node_coordinate(model.mesh, a);
    for (int d = 0; d < dim; ++d) uv[static_cast<std::size_t>(a * dim + d)] = ua[d];
  }
  la::Vector u(model.dofmap.num_dofs(), dim), r(model.dofmap.num_dofs(), dim);
  u.assign(uv);
  K.mult(u, r);
  const auto rv = r.to_std();
  double interior = 0.0, boundary = 0.0;
  int interior_nodes = 0;
  for (Index a = 0; a < model.dofmap.num_nodes(); ++a) {
    const Vec3 x = model.dofmap.node_coordinate(model.mesh, a);
    double dist = 1.0;
    for (int d = 0; d < dim; ++d) dist = std::min({dist, x[d], 1.0 - x[d]});
    interior_nodes += dist > delta + h + 1e-12 ? 1 : 0;
    for (int d = 0; d < dim; ++d) {
      const double v = std::abs(rv[static_cast<std::size_t>(a * dim + d)]);
      (dist > delta + h + 1e-12 ? interior : boundary) =
          std::max(dist > delta + h + 1e-12 ? interior : boundary, v);
    }
  }
  EXPECT_GT(interior_nodes, 0) << "no interior node: the test would be vacuous";
  return {interior, boundary};
}

TEST(NonlocalConsistency, UniformStrainInFullyNonlocalInteriorIsInEquilibriumCG) {
  // CG: exact to round-off, by the point symmetry of the quadrature lattice
  // about every interior node (the partial-volume weights keep that symmetry).
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume})
    for (int dim : {2, 3}) {
      const auto [interior, boundary] =
          uniform_strain_residual(dim, casefile::Discretization::continuous, 3, edge);
      std::printf("CG %dD %s: max interior residual %.3e, max boundary residual %.3e\n", dim,
                  edge == casefile::HorizonEdge::cutoff ? "cut-off" : "partial volume", interior, boundary);
      EXPECT_LT(interior, 1e-10 * boundary) << "dim " << dim;
      EXPECT_GT(boundary, 0.0);
    }
}

TEST(NonlocalConsistency, UniformStrainInFullyNonlocalAnisotropicInteriorIsInEquilibriumCG) {
  // Issue 4: the angular part Y is centrosymmetric, so the point symmetry of
  // the lattice still cancels the interior residual, for rotated axes too.
  auto orthotropic = [](casefile::CaseConfig& c) {
    auto& m = c.materials.front();
    m.kind = casefile::MaterialKind::orthotropic;
    m.E1 = 0.6;
    m.E2 = 0.9;
    m.E3 = 1.5;
    m.nu12 = 0.3;
    m.nu13 = 0.1;
    m.nu23 = 0.2;
    m.G12 = m.G13 = m.G23 = std::numeric_limits<double>::quiet_NaN();
    m.axes = c.dim() == 2 ? Mat3(Eigen::AngleAxisd(0.4, Vec3::UnitZ()))
                          : Mat3(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));
  };
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume})
    for (int dim : {2, 3}) {
      const auto [interior, boundary] =
          uniform_strain_residual(dim, casefile::Discretization::continuous, 3, edge, orthotropic);
      std::printf("CG %dD orthotropic, rotated, %s: max interior residual %.3e, max boundary residual %.3e\n",
                  dim, edge == casefile::HorizonEdge::cutoff ? "cut-off" : "partial volume", interior,
                  boundary);
      EXPECT_LT(interior, 1e-10 * boundary) << "dim " << dim;
      EXPECT_GT(boundary, 0.0);
    }
}

TEST(NonlocalConsistency, UniformStrainInFullyNonlocalInteriorDGResidualIsQuadratureError) {
  // DG: each node sees one cell only, so the interior residual is the quadrature
  // error of the horizon integral at off-centre points: small, and shrinking as
  // the non-local quadrature order grows.
  std::vector<double> ratios;
  for (int q : {2, 3, 4}) {
    const auto [interior, boundary] = uniform_strain_residual(2, casefile::Discretization::discontinuous, q);
    std::printf("DG 2D, %d points/direction: interior %.3e, boundary %.3e, ratio %.3e\n", q, interior,
                boundary, interior / boundary);
    ratios.push_back(interior / boundary);
  }
  EXPECT_LT(ratios.back(), ratios.front());
  EXPECT_LT(ratios.back(), 0.05);
}

TEST(NonlocalConsistency, BitIdenticalForOneAndTwoThreads) {
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume}) {
    auto c = testing::box_case(3, {6, 6, 6}, Vec3::Ones(), 90.0, 0.25);
    testing::add_nonlocal(c, KernelKind::exponential, 0.5, 0.1, 3);
    c.nonlocal.horizon_edge = edge;
    c.alpha.regions = {testing::alpha_ball(Vec3::Constant(0.5), 0.15, 0.2)};
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const Eigen::MatrixXd A = dense_stiffness(c);
    omp_set_num_threads(2);
    const Eigen::MatrixXd B = dense_stiffness(c);
    omp_set_num_threads(saved);
    ASSERT_EQ(A.size(), B.size());
    EXPECT_EQ(std::memcmp(A.data(), B.data(), sizeof(double) * static_cast<std::size_t>(A.size())), 0);
  }
}

}  // namespace
}  // namespace perimorph
