// Local-model assembly through a dense test inserter: element stiffness
// properties (symmetry, rigid modes, a hand-computed entry), consistent loads,
// and bit-identical assembly for any thread count.
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"

#include "../support/dense_inserter.hpp"

#include <gtest/gtest.h>

#include <omp.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cstring>
#include <vector>

namespace perimorph::assembly {
namespace {

using testing::DenseInserter;

mesh::Mesh box(int dim, Vec3 upper, std::array<Index, 3> cells) {
  mesh::BoxSpec s;
  s.dim = dim;
  s.upper = upper;
  s.cells = cells;
  return mesh::make_box(s);
}

/// One distorted hex (no two edges parallel), lexicographic node order.
mesh::Mesh distorted_hex() {
  std::vector<Vec3> x{{0.0, 0.0, 0.0},   {1.1, 0.1, -0.05}, {-0.1, 0.9, 0.1}, {1.2, 1.1, 0.0},
                      {0.05, -0.1, 1.0}, {1.0, 0.0, 1.2},   {0.1, 1.0, 0.9},  {0.9, 1.2, 1.1}};
  return mesh::Mesh(3, std::move(x), {0, 1, 2, 3, 4, 5, 6, 7});
}

mesh::Mesh distorted_quad() {
  std::vector<Vec3> x{{0.0, 0.0, 0.0}, {1.2, 0.1, 0.0}, {-0.1, 0.8, 0.0}, {1.0, 1.1, 0.0}};
  return mesh::Mesh(2, std::move(x), {0, 1, 2, 3});
}

Eigen::MatrixXd material(int dim, double E, double nu, fem::PlaneMode mode = fem::PlaneMode::strain) {
  return fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{E, nu}), dim, mode);
}

/// Assembles the stiffness of `m` with one tensor on every cell.
Eigen::MatrixXd assemble(const mesh::Mesh& m, const Eigen::MatrixXd& C, double scale = 1.0, int n1d = 2) {
  const dofs::DofMap dm(m, m.dim());
  const auto rule = fem::gauss_legendre(m.dim(), n1d);
  fem::ConstitutiveField field(m.dim(), m.num_cells(), static_cast<int>(rule.size()));
  const int id = field.add_tensor(C);
  for (Index c = 0; c < m.num_cells(); ++c) field.set_cell(c, id);
  const LocalSpace space{m, dm, rule, scale};
  DenseInserter K(dm.num_dofs());
  assemble_elasticity(space, field, K);
  return K.A;
}

Eigen::VectorXd sorted_eigenvalues(const Eigen::MatrixXd& K) {
  const Eigen::MatrixXd S = 0.5 * (K + K.transpose());
  Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues();
  std::sort(ev.data(), ev.data() + ev.size());
  return ev;
}

/// Rigid displacement t + ω × x at the mesh nodes (dof = node·dim + d).
Eigen::VectorXd rigid(const mesh::Mesh& m, const Vec3& t, const Vec3& omega) {
  Eigen::VectorXd u(m.num_nodes() * m.dim());
  for (Index n = 0; n < m.num_nodes(); ++n) {
    const Vec3 v = t + omega.cross(m.node(n));
    for (int d = 0; d < m.dim(); ++d) u[n * m.dim() + d] = v[d];
  }
  return u;
}

TEST(AssemblyLocal, HexStiffnessHasSixRigidModes) {
  const mesh::Mesh m = distorted_hex();
  const Eigen::MatrixXd K = assemble(m, material(3, 200.0, 0.3));
  ASSERT_EQ(K.rows(), 24);
  EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm());
  const Eigen::VectorXd ev = sorted_eigenvalues(K);
  const double top = ev[23];
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev[i]), 1e-12 * top) << "eigenvalue " << i << ": " << ev[i];
  for (int i = 6; i < 24; ++i) EXPECT_GT(ev[i], 1e-4 * top) << "eigenvalue " << i << ": " << ev[i];
  // Rigid translations and rotations produce no force.
  for (const auto& [t, w] : {std::pair{Vec3(1, 0, 0), Vec3::Zero().eval()},
                             {Vec3(0, -2, 0.5), Vec3::Zero().eval()},
                             {Vec3::Zero().eval(), Vec3(0, 0, 1)},
                             {Vec3::Zero().eval(), Vec3(0.3, -1, 0.7)}}) {
    const Eigen::VectorXd u = rigid(m, t, w);
    EXPECT_LT((K * u).norm(), 1e-13 * K.norm() * u.norm());
  }
  // A non-rigid mode (uniform stretch) does produce force.
  Eigen::VectorXd stretch(24);
  for (Index n = 0; n < 8; ++n) stretch.segment<3>(3 * n) = m.node(n);
  EXPECT_GT((K * stretch).norm(), 1e-2 * K.norm() * stretch.norm());
}

TEST(AssemblyLocal, QuadStiffnessHasThreeRigidModes) {
  const mesh::Mesh m = distorted_quad();
  const Eigen::MatrixXd K = assemble(m, material(2, 70.0, 0.25, fem::PlaneMode::stress), 0.1);
  ASSERT_EQ(K.rows(), 8);
  EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm());
  const Eigen::VectorXd ev = sorted_eigenvalues(K);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(ev[i]), 1e-12 * ev[7]) << "eigenvalue " << i;
  for (int i = 3; i < 8; ++i) EXPECT_GT(ev[i], 1e-4 * ev[7]) << "eigenvalue " << i;
  for (const auto& [t, w] : {std::pair{Vec3(1, 0, 0), Vec3::Zero().eval()},
                             {Vec3(0, 1, 0), Vec3::Zero().eval()},
                             {Vec3::Zero().eval(), Vec3(0, 0, 1)}}) {
    const Eigen::VectorXd u = rigid(m, t, w);
    EXPECT_LT((K * u).norm(), 1e-13 * K.norm() * u.norm());
  }
}

TEST(AssemblyLocal, BarStiffnessIsEAOverL) {
  const mesh::Mesh m = box(1, Vec3(2.0, 0, 0), {1, 1, 1});
  const double E = 30.0, A = 0.2;
  const Eigen::MatrixXd K = assemble(m, material(1, E, 0.3), A);
  Eigen::Matrix2d expected;
  expected << 1, -1, -1, 1;
  expected *= E * A / 2.0;
  EXPECT_LT((K - expected).norm(), 1e-14 * expected.norm()) << K;
}

TEST(AssemblyLocal, UnitSquarePlaneStressHandEntries) {
  // K for a unit square, plane stress, thickness t, 2×2 Gauss (exact):
  //   K(0x,0x) = t E/(1−ν²) (1/2 − ν/6), K(0x,0y) = t E/(1−ν²) (1+ν)/8,
  //   K(0x,1x) = t E/(1−ν²) (−1/3 + (1−ν)/12).
  const double E = 1000.0, nu = 0.3, t = 0.5;
  const mesh::Mesh m = box(2, Vec3(1, 1, 0), {1, 1, 1});
  const Eigen::MatrixXd K = assemble(m, material(2, E, nu, fem::PlaneMode::stress), t);
  const double f = t * E / (1 - nu * nu);
  EXPECT_NEAR(K(0, 0), f * (0.5 - nu / 6), 1e-12 * f);
  EXPECT_NEAR(K(0, 1), f * (1 + nu) / 8, 1e-12 * f);
  EXPECT_NEAR(K(0, 2), f * (-1.0 / 3 + (1 - nu) / 12), 1e-12 * f);
  // By symmetry of the square every diagonal entry is equal.
  for (int i = 1; i < 8; ++i) EXPECT_NEAR(K(i, i), K(0, 0), 1e-12 * f);
  // A higher-order rule changes nothing (the integrand is quadratic).
  const Eigen::MatrixXd K3 = assemble(m, material(2, E, nu, fem::PlaneMode::stress), t, 3);
  EXPECT_LT((K3 - K).norm(), 1e-13 * K.norm());
}

TEST(AssemblyLocal, BodyForceTotalsAndMoments) {
  const mesh::Mesh m = box(3, Vec3(2.0, 1.0, 1.5), {3, 2, 2});
  const dofs::DofMap dm(m, 3);
  const auto rule = fem::gauss_legendre(3, 2);
  const LocalSpace space{m, dm, rule, 1.0};
  const double volume = 3.0;
  {
    std::vector<double> F(static_cast<std::size_t>(dm.num_dofs()), 0.0);
    const Vec3 b(1.0, -2.0, 3.0);
    assemble_body_force(
        space, [&](const Vec3&) { return b; }, F);
    Vec3 total = Vec3::Zero(), moment_x = Vec3::Zero();
    for (Index n = 0; n < dm.num_nodes(); ++n)
      for (int d = 0; d < 3; ++d) {
        total[d] += F[static_cast<std::size_t>(3 * n + d)];
        moment_x[d] += F[static_cast<std::size_t>(3 * n + d)] * dm.node_coordinate(m, n).x();
      }
    EXPECT_NEAR((total - b * volume).norm(), 0.0, 1e-13);
    // Σ_a f_a x_a = ∫ b x dV = b · volume · centroid_x.
    EXPECT_NEAR((moment_x - b * volume * 1.0).norm(), 0.0, 1e-13);
  }
  {
    // Bilinear density: ∫ y z dV = 2 · (1/2) · (1.5²/2) = 1.125; ∫ x dV = 3.
    std::vector<double> F(static_cast<std::size_t>(dm.num_dofs()), 0.0);
    assemble_body_force(
        space, [](const Vec3& x) { return Vec3(x.x(), x.y() * x.z(), 0.0); }, F);
    Vec3 total = Vec3::Zero();
    for (Index n = 0; n < dm.num_nodes(); ++n)
      for (int d = 0; d < 3; ++d) total[d] += F[static_cast<std::size_t>(3 * n + d)];
    EXPECT_NEAR(total.x(), 3.0, 1e-13);
    EXPECT_NEAR(total.y(), 1.125, 1e-13);
    EXPECT_EQ(total.z(), 0.0);
  }
  {
    // 2D with thickness: total = b · area · t; loads accumulate (+=).
    const mesh::Mesh q = box(2, Vec3(3.0, 2.0, 0.0), {3, 4, 1});
    const dofs::DofMap dq(q, 2);
    const auto rule2 = fem::gauss_legendre(2, 2);
    const LocalSpace s2{q, dq, rule2, 0.25};
    std::vector<double> F(static_cast<std::size_t>(dq.num_dofs()), 1.0);
    assemble_body_force(
        s2, [](const Vec3&) { return Vec3(2.0, -1.0, 5.0); }, F);
    double fx = 0.0, fy = 0.0;
    for (Index n = 0; n < dq.num_nodes(); ++n) {
      fx += F[static_cast<std::size_t>(2 * n)] - 1.0;
      fy += F[static_cast<std::size_t>(2 * n + 1)] - 1.0;
    }
    EXPECT_NEAR(fx, 2.0 * 6.0 * 0.25, 1e-13);
    EXPECT_NEAR(fy, -1.0 * 6.0 * 0.25, 1e-13);
  }
}

TEST(AssemblyLocal, TractionTotalsEqualTractionTimesArea) {
  {
    const mesh::Mesh m = box(3, Vec3(2.0, 1.0, 1.5), {3, 2, 2});
    const dofs::DofMap dm(m, 3);
    const auto rule = fem::gauss_legendre(3, 2);
    const LocalSpace space{m, dm, rule, 1.0};
    std::vector<double> F(static_cast<std::size_t>(dm.num_dofs()), 0.0);
    const Vec3 t(0.5, 1.0, -2.0);
    assemble_traction(space, m.face_sets.at("xmax"), t, F);
    Vec3 total = Vec3::Zero();
    for (Index n = 0; n < dm.num_nodes(); ++n)
      for (int d = 0; d < 3; ++d) {
        const double f = F[static_cast<std::size_t>(3 * n + d)];
        total[d] += f;
        if (dm.node_coordinate(m, n).x() != 2.0) {
          EXPECT_EQ(f, 0.0) << "load off the face at node " << n;
        }
      }
    EXPECT_NEAR((total - t * 1.5).norm(), 0.0, 1e-13);  // face 1 × 1.5
  }
  {
    // One face of a unit cube: each corner receives a quarter.
    const mesh::Mesh m = box(3, Vec3(1, 1, 1), {1, 1, 1});
    const dofs::DofMap dm(m, 3);
    const auto rule = fem::gauss_legendre(3, 2);
    const LocalSpace space{m, dm, rule, 1.0};
    std::vector<double> F(24, 0.0);
    assemble_traction(space, m.face_sets.at("zmax"), Vec3(0, 0, 4.0), F);
    for (Index n = 4; n < 8; ++n) EXPECT_NEAR(F[static_cast<std::size_t>(3 * n + 2)], 1.0, 1e-14);
    for (Index n = 0; n < 4; ++n) EXPECT_EQ(F[static_cast<std::size_t>(3 * n + 2)], 0.0);
  }
  {
    // 2D edge load with thickness: t · length · thickness.
    const mesh::Mesh q = box(2, Vec3(3.0, 2.0, 0.0), {3, 4, 1});
    const dofs::DofMap dq(q, 2);
    const auto rule = fem::gauss_legendre(2, 2);
    const LocalSpace s2{q, dq, rule, 0.25};
    std::vector<double> F(static_cast<std::size_t>(dq.num_dofs()), 0.0);
    assemble_traction(s2, q.face_sets.at("ymax"), Vec3(-1.0, 3.0, 0.0), F);
    double fx = 0.0, fy = 0.0;
    for (Index n = 0; n < dq.num_nodes(); ++n) {
      fx += F[static_cast<std::size_t>(2 * n)];
      fy += F[static_cast<std::size_t>(2 * n + 1)];
    }
    EXPECT_NEAR(fx, -1.0 * 3.0 * 0.25, 1e-13);
    EXPECT_NEAR(fy, 3.0 * 3.0 * 0.25, 1e-13);
  }
  {
    // 1D end load: t · cross-section area on the end node only.
    const mesh::Mesh b = box(1, Vec3(2.0, 0, 0), {4, 1, 1});
    const dofs::DofMap db(b, 1);
    const auto rule = fem::gauss_legendre(1, 2);
    const LocalSpace s1{b, db, rule, 0.1};
    std::vector<double> F(5, 0.0);
    assemble_traction(s1, b.face_sets.at("xmax"), Vec3(7.0, 0, 0), F);
    EXPECT_NEAR(F[4], 0.7, 1e-15);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(F[i], 0.0);
  }
}

TEST(AssemblyLocal, IncludeFilterSelectsCells) {
  const mesh::Mesh m = box(2, Vec3(3, 2, 0), {3, 2, 1});
  const dofs::DofMap dm(m, 2);
  const auto rule = fem::gauss_legendre(2, 2);
  fem::ConstitutiveField field(2, m.num_cells(), 4);
  const int id = field.add_tensor(material(2, 10.0, 0.2));
  for (Index c = 0; c < m.num_cells(); ++c) field.set_cell(c, id);
  const LocalSpace space{m, dm, rule, 1.0};
  DenseInserter all(dm.num_dofs()), even(dm.num_dofs()), odd(dm.num_dofs()), none(dm.num_dofs());
  assemble_elasticity(space, field, all);
  assemble_elasticity(space, field, even, [](Index c) { return c % 2 == 0; });
  assemble_elasticity(space, field, odd, [](Index c) { return c % 2 == 1; });
  assemble_elasticity(space, field, none, [](Index) { return false; });
  EXPECT_EQ(all.calls, 6);
  EXPECT_EQ(even.calls, 3);
  EXPECT_EQ(none.calls, 0);
  EXPECT_TRUE(none.A.isZero(0.0));
  EXPECT_LT((even.A + odd.A - all.A).norm(), 1e-14 * all.A.norm());
  EXPECT_GT(even.A.norm(), 0.0);
  EXPECT_GT((even.A - odd.A).norm(), 0.0);
}

TEST(AssemblyLocal, DiscontinuousCellsDecouple) {
  const mesh::Mesh m = box(3, Vec3(2, 1, 1), {2, 1, 1});
  const std::vector<dofs::Continuity> flags(2, dofs::Continuity::discontinuous);
  const dofs::DofMap dm(m, 3, flags);
  ASSERT_EQ(dm.num_dofs(), 48);
  const auto rule = fem::gauss_legendre(3, 2);
  fem::ConstitutiveField field(3, 2, 8);
  const int id = field.add_tensor(material(3, 5.0, 0.25));
  field.set_cell(0, id);
  field.set_cell(1, id);
  DenseInserter K(dm.num_dofs());
  assemble_elasticity(LocalSpace{m, dm, rule, 1.0}, field, K);
  EXPECT_TRUE(K.A.block(0, 24, 24, 24).isZero(0.0));
  EXPECT_TRUE(K.A.block(24, 0, 24, 24).isZero(0.0));
  const Eigen::VectorXd ev = sorted_eigenvalues(K.A);
  for (int i = 0; i < 12; ++i) EXPECT_LT(std::abs(ev[i]), 1e-12 * ev[47]);
  EXPECT_GT(ev[12], 1e-4 * ev[47]);
}

TEST(AssemblyLocal, BitIdenticalForAnyThreadCount) {
  const mesh::Mesh m = box(3, Vec3(1, 1, 1), {6, 6, 6});
  const dofs::DofMap dm(m, 3);
  const auto rule = fem::gauss_legendre(3, 2);
  fem::ConstitutiveField field(3, m.num_cells(), 8);
  for (Index c = 0; c < m.num_cells(); ++c)  // a different tensor on every cell
    field.set_cell(c, field.add_tensor(material(3, 1.0 + 0.01 * c, 0.2 + 0.001 * (c % 50))));
  const LocalSpace space{m, dm, rule, 1.0};
  const int saved = omp_get_max_threads();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    DenseInserter K(dm.num_dofs());
    assemble_elasticity(space, field, K);
    return K.A;
  };
  const Eigen::MatrixXd K1 = run(1);
  const Eigen::MatrixXd K2 = run(2);
  const Eigen::MatrixXd K4 = run(4);
  omp_set_num_threads(saved);
  ASSERT_EQ(K1.size(), K2.size());
  EXPECT_GT(K1.norm(), 0.0);
  EXPECT_TRUE(K1 == K2);
  EXPECT_TRUE(K1 == K4);
  EXPECT_EQ(std::memcmp(K1.data(), K2.data(), sizeof(double) * static_cast<std::size_t>(K1.size())), 0);
  EXPECT_EQ(std::memcmp(K1.data(), K4.data(), sizeof(double) * static_cast<std::size_t>(K1.size())), 0);
  EXPECT_LT((K1 - K1.transpose()).norm(), 1e-13 * K1.norm());
  // Whole-body rigid motions are in the kernel of the assembled matrix.
  const Eigen::VectorXd u = rigid(m, Vec3(0.1, 0.2, 0.3), Vec3(1, -1, 0.5));
  EXPECT_LT((K1 * u).norm(), 1e-12 * K1.norm() * u.norm());
}

}  // namespace
}  // namespace perimorph::assembly
