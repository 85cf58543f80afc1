// Patch tests (issue 2, item 8): a uniform strain imposed on the boundary of a
// mesh with distorted interior nodes is reproduced exactly (to 1e-10) in the
// interior, in 1D, 2D and 3D, for isotropic and orthotropic materials.

#include "perimorph/fem/material.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/mesh/box.hpp"
#include "support/solve_local.hpp"

#include <gtest/gtest.h>

#include <random>

namespace perimorph {
namespace {

/// A box mesh whose interior nodes are moved randomly by up to 20% of h.
mesh::Mesh distorted_box(int dim, int n) {
  mesh::BoxSpec spec{dim, Vec3::Zero(), Vec3(1.0, 0.8, 1.2), {n, n + 1, n}};
  const mesh::Mesh box = mesh::make_box(spec);
  std::vector<Vec3> nodes = box.nodes();
  std::vector<char> on_boundary(nodes.size(), 0);
  for (Index b : box.node_sets.at("boundary")) on_boundary[static_cast<std::size_t>(b)] = 1;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> shift(-0.2 / n, 0.2 / n);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (!on_boundary[i])
      for (int d = 0; d < dim; ++d) nodes[i][d] += shift(rng);
  mesh::Mesh m(dim, nodes, box.connectivity());
  m.node_sets = box.node_sets;
  return m;
}

Mat3 strain_gradient(int dim) {
  Mat3 G = Mat3::Zero();
  G << 1e-3, 2e-4, -3e-4, -1e-4, -5e-4, 4e-4, 2.5e-4, 1e-4, 7e-4;
  for (int i = dim; i < 3; ++i) {
    G.row(i).setZero();
    G.col(i).setZero();
  }
  return G;
}

void run_patch_test(int dim, const Voigt6& C3, fem::PlaneMode mode) {
  const mesh::Mesh m = distorted_box(dim, dim == 1 ? 7 : dim == 2 ? 5 : 3);
  const dofs::DofMap dm(m, dim);
  const auto rule = fem::gauss_legendre(dim, 2);
  fem::ConstitutiveField C(dim, m.num_cells(), static_cast<int>(rule.size()));
  const int id = C.add_tensor(fem::reduce_stiffness(C3, dim, mode));
  for (Index c = 0; c < m.num_cells(); ++c) C.set_cell(c, id);
  const Mat3 G = strain_gradient(dim);
  auto exact = [&](const Vec3& x) -> Vec3 { return G * x; };
  const std::vector<double> F(static_cast<std::size_t>(dm.num_dofs()), 0.0);
  const auto u = testing::solve_local({m, dm, rule, 1.0}, C, m.node_sets.at("boundary"), exact, F);
  double max_err = 0.0, max_u = 0.0;
  for (Index n = 0; n < dm.num_nodes(); ++n) {
    const Vec3 ue = exact(dm.node_coordinate(m, n));
    for (int d = 0; d < dim; ++d) {
      max_err = std::max(max_err, std::abs(u[static_cast<std::size_t>(n * dim + d)] - ue[d]));
      max_u = std::max(max_u, std::abs(ue[d]));
    }
  }
  EXPECT_LT(max_err / max_u, 1e-10) << "dim " << dim;
  // The strain is uniform and exact at every quadrature point.
  const assembly::LocalSpace space{m, dm, rule, 1.0};
  for (Index c = 0; c < m.num_cells(); c += 3) {
    const auto eps = assembly::strain_at(space, c, rule[0].xi, u);
    EXPECT_NEAR(eps[0], G(0, 0), 1e-12);
    if (dim >= 2) {
      EXPECT_NEAR(eps[1], G(1, 1), 1e-12);
      EXPECT_NEAR(eps[dim == 2 ? 2 : 5], G(0, 1) + G(1, 0), 1e-12);
    }
  }
}

TEST(AssemblyPatch, UniformStrain1D) {
  run_patch_test(1, fem::stiffness_voigt(fem::IsotropicElasticity{200.0, 0.3}), fem::PlaneMode::strain);
}

TEST(AssemblyPatch, UniformStrain2DPlaneStrainAndStress) {
  const Voigt6 C = fem::stiffness_voigt(fem::IsotropicElasticity{200.0, 0.3});
  run_patch_test(2, C, fem::PlaneMode::strain);
  run_patch_test(2, C, fem::PlaneMode::stress);
}

TEST(AssemblyPatch, UniformStrain3DIsotropic) {
  run_patch_test(3, fem::stiffness_voigt(fem::IsotropicElasticity{200.0, 0.3}), fem::PlaneMode::strain);
}

TEST(AssemblyPatch, UniformStrain3DRotatedOrthotropic) {
  fem::OrthotropicElasticity o{60, 90, 150, 0.3, 0.1, 0.2, 25, 20, 30, Mat3::Identity()};
  o.axes = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  run_patch_test(3, fem::stiffness_voigt(o), fem::PlaneMode::strain);
  run_patch_test(2, fem::stiffness_voigt(o), fem::PlaneMode::stress);
}

}  // namespace
}  // namespace perimorph
