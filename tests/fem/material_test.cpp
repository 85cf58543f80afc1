// Elastic materials: Voigt stiffness, reductions to 2D/1D, orthotropy and
// rotation, admissibility checks.
#include "perimorph/fem/material.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace perimorph::fem {
namespace {

OrthotropicElasticity sample_orthotropic() {
  OrthotropicElasticity m;
  m.E1 = 150.0;
  m.E2 = 10.0;
  m.E3 = 8.0;
  m.nu12 = 0.3;
  m.nu13 = 0.25;
  m.nu23 = 0.4;
  m.G12 = 5.0;
  m.G13 = 4.5;
  m.G23 = 3.5;
  return m;
}

Voigt6 to_mandel(const Voigt6& C) {
  Eigen::Matrix<double, 6, 1> w;
  w << 1, 1, 1, std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0);
  return w.asDiagonal() * C * w.asDiagonal();
}

Eigen::Matrix<double, 6, 1> sorted_eigenvalues(const Voigt6& C) {
  Eigen::Matrix<double, 6, 1> ev = Eigen::SelfAdjointEigenSolver<Voigt6>(to_mandel(C)).eigenvalues();
  std::sort(ev.data(), ev.data() + 6);
  return ev;
}

double rel_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(FemMaterial, IsotropicVoigtMatchesLame) {
  // E = 200, ν = 0.25: λ = μ = 80.
  const Voigt6 C = stiffness_voigt(IsotropicElasticity{200.0, 0.25});
  Voigt6 expected = Voigt6::Zero();
  expected.topLeftCorner<3, 3>().setConstant(80.0);
  expected.topLeftCorner<3, 3>().diagonal().setConstant(240.0);
  expected.bottomRightCorner<3, 3>().diagonal().setConstant(80.0);
  EXPECT_LT(rel_diff(C, expected), 1e-15);

  const double E = 210e9, nu = 0.3;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const Voigt6 D = stiffness_voigt(IsotropicElasticity{E, nu});
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double v = 0.0;
      if (i < 3 && j < 3) v = lambda + (i == j ? 2 * mu : 0.0);
      if (i >= 3 && i == j) v = mu;  // engineering shear strain: σ_yz = μ γ_yz
      EXPECT_NEAR(D(i, j), v, 1e-12 * E) << i << "," << j;
    }
}

TEST(FemMaterial, PlaneStrainIsSubBlock) {
  const Voigt6 C = stiffness_voigt(IsotropicElasticity{70.0, 0.33});
  const Eigen::MatrixXd P = reduce_stiffness(C, 2, PlaneMode::strain);
  ASSERT_EQ(P.rows(), 3);
  ASSERT_EQ(P.cols(), 3);
  const std::array<int, 3> idx{0, 1, 5};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(P(a, b), C(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]));
  // Also for an anisotropic (rotated orthotropic) tensor with xy–normal coupling.
  OrthotropicElasticity m = sample_orthotropic();
  m.axes = Eigen::AngleAxisd(0.6, Vec3::UnitZ()).toRotationMatrix();
  const Voigt6 Co = stiffness_voigt(m);
  const Eigen::MatrixXd Po = reduce_stiffness(Co, 2, PlaneMode::strain);
  EXPECT_NE(Co(0, 5), 0.0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(Po(a, b), Co(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]));
  EXPECT_EQ(reduce_stiffness(C, 3, PlaneMode::stress), Eigen::MatrixXd(C));
}

TEST(FemMaterial, PlaneStressIsotropicFormula) {
  const double E = 70.0, nu = 0.33;
  const Eigen::MatrixXd P =
      reduce_stiffness(stiffness_voigt(IsotropicElasticity{E, nu}), 2, PlaneMode::stress);
  Eigen::Matrix3d expected;
  expected << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
  expected *= E / (1 - nu * nu);
  ASSERT_EQ(P.rows(), 3);
  EXPECT_LT(rel_diff(P, expected), 1e-13);
  // Plane stress is softer than plane strain.
  const Eigen::MatrixXd S =
      reduce_stiffness(stiffness_voigt(IsotropicElasticity{E, nu}), 2, PlaneMode::strain);
  EXPECT_GT(S(0, 0), P(0, 0) * 1.05);
}

TEST(FemMaterial, UniaxialReduction) {
  const Eigen::MatrixXd P =
      reduce_stiffness(stiffness_voigt(IsotropicElasticity{70.0, 0.33}), 1, PlaneMode::strain);
  ASSERT_EQ(P.rows(), 1);
  ASSERT_EQ(P.cols(), 1);
  EXPECT_NEAR(P(0, 0), 70.0, 1e-12);
  OrthotropicElasticity m = sample_orthotropic();
  EXPECT_NEAR(reduce_stiffness(stiffness_voigt(m), 1, PlaneMode::stress)(0, 0), m.E1, 1e-10);
  m.axes = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(reduce_stiffness(stiffness_voigt(m), 1, PlaneMode::stress)(0, 0), m.E2, 1e-10);
}

TEST(FemMaterial, OrthotropicComplianceMatchesEngineeringConstants) {
  const OrthotropicElasticity m = sample_orthotropic();
  const Voigt6 C = stiffness_voigt(m);
  EXPECT_LT((C - C.transpose()).norm(), 1e-12 * C.norm());
  const Eigen::FullPivLU<Voigt6> lu(C);
  const double s = 2.5;
  auto strain = [&](int i) {
    Eigen::Matrix<double, 6, 1> sigma = Eigen::Matrix<double, 6, 1>::Zero();
    sigma[i] = s;
    return Eigen::Matrix<double, 6, 1>(lu.solve(sigma));
  };
  const double tol = 1e-12;
  const auto e1 = strain(0);
  EXPECT_NEAR(e1[0], s / m.E1, tol);
  EXPECT_NEAR(e1[1], -m.nu12 * s / m.E1, tol);
  EXPECT_NEAR(e1[2], -m.nu13 * s / m.E1, tol);
  EXPECT_NEAR(e1.tail<3>().norm(), 0.0, tol);
  const auto e2 = strain(1);
  EXPECT_NEAR(e2[1], s / m.E2, tol);
  EXPECT_NEAR(e2[0], -m.nu12 * s / m.E1, tol);  // ν21/E2 = ν12/E1
  EXPECT_NEAR(e2[2], -m.nu23 * s / m.E2, tol);
  const auto e3 = strain(2);
  EXPECT_NEAR(e3[2], s / m.E3, tol);
  EXPECT_NEAR(e3[0], -m.nu13 * s / m.E1, tol);
  EXPECT_NEAR(e3[1], -m.nu23 * s / m.E2, tol);
  // Shear: engineering strains γ = τ / G; Voigt order yz, xz, xy.
  const auto g23 = strain(3);
  EXPECT_NEAR(g23[3], s / m.G23, tol);
  EXPECT_NEAR(g23.head<3>().norm() + g23.tail<2>().norm(), 0.0, tol);
  EXPECT_NEAR(strain(4)[4], s / m.G13, tol);
  EXPECT_NEAR(strain(5)[5], s / m.G12, tol);
}

TEST(FemMaterial, OrthotropicWithEqualConstantsIsIsotropic) {
  const double E = 12.0, nu = 0.2;
  OrthotropicElasticity m;
  m.E1 = m.E2 = m.E3 = E;
  m.nu12 = m.nu13 = m.nu23 = nu;
  m.G12 = m.G13 = m.G23 = E / (2 * (1 + nu));
  EXPECT_LT(rel_diff(stiffness_voigt(m), stiffness_voigt(IsotropicElasticity{E, nu})), 1e-14);
}

TEST(FemMaterial, Rotation90AboutZSwapsAxes1And2) {
  const OrthotropicElasticity m = sample_orthotropic();
  const Voigt6 C = stiffness_voigt(m);
  OrthotropicElasticity r = m;
  r.axes = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()).toRotationMatrix();  // e1 → y, e2 → -x
  const Voigt6 Cr = stiffness_voigt(r);
  // Mesh x is material 2, mesh y is material 1: swap xx↔yy and yz↔xz.
  const std::array<int, 6> perm{1, 0, 2, 4, 3, 5};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(Cr(i, j), C(perm[static_cast<std::size_t>(i)], perm[static_cast<std::size_t>(j)]),
                  1e-10 * C.norm())
          << i << "," << j;
  // Uniaxial stress along mesh x now stretches by σ/E2.
  Eigen::Matrix<double, 6, 1> sigma = Eigen::Matrix<double, 6, 1>::Zero();
  sigma[0] = 1.0;
  const Eigen::Matrix<double, 6, 1> eps = Cr.fullPivLu().solve(sigma);
  EXPECT_NEAR(eps[0], 1.0 / m.E2, 1e-12);
  EXPECT_NEAR(eps[1], -m.nu12 / m.E1, 1e-12);
  EXPECT_NEAR(eps[2], -m.nu23 / m.E2, 1e-12);
}

TEST(FemMaterial, RotationPreservesMandelEigenvalues) {
  const Voigt6 C = stiffness_voigt(sample_orthotropic());
  std::mt19937 gen(20240607u);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 R =
        (Eigen::AngleAxisd(angle(gen), Vec3::UnitZ()) * Eigen::AngleAxisd(angle(gen), Vec3::UnitY()) *
         Eigen::AngleAxisd(angle(gen), Vec3::UnitX()))
            .toRotationMatrix();
    const Voigt6 Cr = rotate_stiffness(C, R);
    EXPECT_GT(rel_diff(Cr, C), 1e-3) << "the rotation should change the tensor";
    EXPECT_LT((Cr - Cr.transpose()).norm(), 1e-12 * C.norm());
    const auto ev = sorted_eigenvalues(C), evr = sorted_eigenvalues(Cr);
    EXPECT_LT((ev - evr).norm(), 1e-12 * ev.norm()) << ev.transpose() << "\n" << evr.transpose();
    // Rotating back recovers the original.
    EXPECT_LT(rel_diff(rotate_stiffness(Cr, R.transpose()), C), 1e-13);
    // Orthotropic via its axes equals rotate_stiffness of the unrotated tensor.
    OrthotropicElasticity m = sample_orthotropic();
    m.axes = R;
    EXPECT_LT(rel_diff(stiffness_voigt(m), Cr), 1e-13);
  }
  // Isotropic tensors are invariant.
  const Voigt6 Ci = stiffness_voigt(IsotropicElasticity{3.0, 0.1});
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_LT(rel_diff(rotate_stiffness(Ci, R), Ci), 1e-14);
}

TEST(FemMaterial, AdmissibilityMessages) {
  EXPECT_EQ(admissibility_problem(IsotropicElasticity{200.0, 0.3}), "");
  EXPECT_EQ(admissibility_problem(IsotropicElasticity{200.0, -0.5}), "");
  const std::string incompressible = admissibility_problem(IsotropicElasticity{200.0, 0.5});
  EXPECT_TRUE(contains(incompressible, "nu = 0.5")) << incompressible;
  EXPECT_TRUE(contains(incompressible, "(-1, 0.5)")) << incompressible;
  EXPECT_FALSE(admissibility_problem(IsotropicElasticity{200.0, -1.0}).empty());
  const std::string negative = admissibility_problem(IsotropicElasticity{-1.0, 0.3});
  EXPECT_TRUE(contains(negative, "E = -1")) << negative;
  EXPECT_TRUE(contains(negative, "positive")) << negative;
  EXPECT_FALSE(admissibility_problem(IsotropicElasticity{0.0, 0.3}).empty());
  EXPECT_FALSE(admissibility_problem(IsotropicElasticity{std::nan(""), 0.3}).empty());

  EXPECT_EQ(admissibility_problem(sample_orthotropic()), "");
  OrthotropicElasticity bad = sample_orthotropic();
  bad.E1 = bad.E2 = bad.E3 = 10.0;
  bad.nu12 = bad.nu13 = bad.nu23 = 0.9;  // compliance eigenvalue (1 - 1.8)/E < 0
  const std::string indefinite = admissibility_problem(bad);
  EXPECT_TRUE(contains(indefinite, "indefinite")) << indefinite;
  EXPECT_TRUE(contains(indefinite, "nu12 = 0.9")) << indefinite;
  OrthotropicElasticity shear = sample_orthotropic();
  shear.G13 = 0.0;
  const std::string g = admissibility_problem(shear);
  EXPECT_TRUE(contains(g, "G13")) << g;
  EXPECT_TRUE(contains(g, "positive")) << g;
  OrthotropicElasticity mirrored = sample_orthotropic();
  mirrored.axes = Mat3::Identity();
  mirrored.axes(2, 2) = -1.0;
  EXPECT_TRUE(contains(admissibility_problem(mirrored), "rotation"));
  OrthotropicElasticity skewed = sample_orthotropic();
  skewed.axes(0, 1) = 0.1;
  EXPECT_TRUE(contains(admissibility_problem(skewed), "rotation"));
}

}  // namespace
}  // namespace perimorph::fem
