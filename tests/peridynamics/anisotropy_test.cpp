// Anisotropic micromodulus (THEORY §2.1, issue 4): the round trip
// C → coefficients → C = ∫_H c(ξ) ξ⊗ξ⊗ξ⊗ξ/(2|ξ|²) dξ (eq. 2.64) integrated
// here independently over the ball/disk in mesh coordinates, through the
// same Micromodulus::bond the assembly uses, for several kernels and rotated
// axes; the closed forms for the constant kernel; the Cauchy relations and
// the nearest central-force tensor.

#include "perimorph/peridynamics/anisotropy.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace perimorph {
namespace {

using peridynamics::AngularKind;
using peridynamics::KernelShape;
using peridynamics::Micromodulus;

constexpr double pi = std::numbers::pi;

/// C_ijkl = ∫_{|ξ|<δ} c(ξ) ξiξjξkξl/(2|ξ|²) dξ (Voigt, mesh axes): composite
/// Gauss–Legendre in r (16 panels × 12 points), Gauss–Legendre in cos θ
/// (12 points) and 32 equal steps in φ (3D), or 32 steps in θ (2D). Exact for
/// the angular degree 8 of Y e⊗e⊗e⊗e; the radial rule converges to round-off.
Eigen::MatrixXd integrate_bulk_tensor(const Micromodulus& c, int dim) {
  static constexpr int v3[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
  static constexpr int v2[2][2] = {{0, 2}, {2, 1}};
  const int nv = dim == 2 ? 3 : 6;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(nv, nv);
  const auto gl = fem::gauss_legendre_1d(12);
  constexpr int panels = 16, steps = 32;
  const double dr = c.horizon / panels;
  auto add = [&](const Vec3& e, double w_angle) {
    for (int p = 0; p < panels; ++p)
      for (const auto& q : gl) {
        const double r = (p + 0.5 * (q.xi.x() + 1.0)) * dr;
        const double w = w_angle * q.weight * 0.5 * dr * std::pow(r, dim - 1);
        const Vec3 xi = r * e;
        const double s = w * c.bond(xi, r) * r * r / 2.0;  // ξ⁴/(2r²) = r² e⁴/2
        for (int i = 0; i < dim; ++i)
          for (int j = i; j < dim; ++j)
            for (int k = 0; k < dim; ++k)
              for (int l = k; l < dim; ++l)
                C(dim == 3 ? v3[i][j] : v2[i][j], dim == 3 ? v3[k][l] : v2[k][l]) +=
                    s * e[i] * e[j] * e[k] * e[l];
      }
  };
  for (int a = 0; a < steps; ++a) {
    const double phi = 2.0 * pi * (a + 0.25) / steps;
    if (dim == 2) {
      add(Vec3(std::cos(phi), std::sin(phi), 0.0), 2.0 * pi / steps);
      continue;
    }
    for (const auto& q : gl) {
      const double x = q.xi.x(), s = std::sqrt(1.0 - x * x);
      add(Vec3(s * std::cos(phi), s * std::sin(phi), x), q.weight * 2.0 * pi / steps);
    }
  }
  return C;
}

/// A central-force orthotropic stiffness in material axes from B4's constants
/// (shear moduli from the Cauchy relations).
Voigt6 central_orthotropic(double E1, double E2, double E3, double nu12, double nu13, double nu23) {
  Eigen::Matrix3d S;
  S << 1 / E1, -nu12 / E1, -nu13 / E1, -nu12 / E1, 1 / E2, -nu23 / E2, -nu13 / E1, -nu23 / E2, 1 / E3;
  Voigt6 C = Voigt6::Zero();
  C.topLeftCorner<3, 3>() = S.inverse();
  C(3, 3) = C(1, 2);
  C(4, 4) = C(0, 2);
  C(5, 5) = C(0, 1);
  return C;
}

Micromodulus kernel(KernelShape s, double delta, double l) {
  Micromodulus k;
  k.shape = s;
  k.horizon = delta;
  k.length = l;
  return k;
}

double rel_diff(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

const Mat3 kRotation = Mat3(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));

TEST(Anisotropy, OrthotropicRoundTripForKernelsAndRotatedAxes) {
  const Voigt6 Cm = central_orthotropic(60e3, 90e3, 150e3, 0.3, 0.1, 0.2);
  for (const Mat3& axes : {Mat3(Mat3::Identity()), kRotation})
    for (auto [shape, l] :
         {std::pair{KernelShape::constant, 1.0}, std::pair{KernelShape::conical, 1.0},
          std::pair{KernelShape::exponential, 0.2 * 0.75}, std::pair{KernelShape::gaussian, 0.75 / 3.0}}) {
      SCOPED_TRACE(::testing::Message()
                   << peridynamics::to_string(shape) << (axes.isIdentity() ? "" : ", rotated"));
      Micromodulus c = kernel(shape, 0.75, l);
      c.angular = peridynamics::calibrate_angular(c, 3, Cm, axes, AngularKind::orthotropic);
      const Eigen::MatrixXd C = integrate_bulk_tensor(c, 3);
      const double err = rel_diff(C, fem::rotate_stiffness(Cm, axes));
      std::printf("3D orthotropic round trip, %s kernel%s: max |C - C_given| / max |C_given| = %.2e\n",
                  peridynamics::to_string(shape), axes.isIdentity() ? "" : ", rotated axes", err);
      EXPECT_LT(err, 1e-10);
      // The library's own map back (used by `perimorph info`) agrees too.
      EXPECT_LT(rel_diff(peridynamics::angular_bulk_tensor(c.angular, 3, c.shape_moment(4)), C), 1e-10);
    }
}

TEST(Anisotropy, TransverselyIsotropicRoundTripAndAgreementWithOrthotropicMap) {
  // E_in = 60, E_axis = 150, nu_axial = 0.1 → nu_in = (1 − 4 · 0.01 · 2.5)/3 = 0.3 (C1122 = C1111/3).
  const double nu_in = (1.0 - 4.0 * 0.01 * 150.0 / 60.0) / 3.0;
  EXPECT_NEAR(nu_in, 0.3, 1e-15);
  const Voigt6 Cm = central_orthotropic(60e3, 60e3, 150e3, nu_in, 0.1, 0.1);
  EXPECT_NEAR(Cm(0, 1), Cm(0, 0) / 3.0, 1e-10 * Cm(0, 0));
  for (const Mat3& axes : {Mat3(Mat3::Identity()), kRotation}) {
    Micromodulus c = kernel(KernelShape::exponential, 0.15, 0.03);
    const auto ti = peridynamics::calibrate_angular(c, 3, Cm, axes, AngularKind::transversely_isotropic);
    const auto ortho = peridynamics::calibrate_angular(c, 3, Cm, axes, AngularKind::orthotropic);
    EXPECT_EQ(ti.kind, AngularKind::transversely_isotropic);
    EXPECT_NEAR(ti.a[0], ortho.a[0], 1e-12 * std::abs(ti.a[0]));
    EXPECT_NEAR(ti.a[1], ortho.a[1], 1e-12 * std::abs(ti.a[0]));
    EXPECT_NEAR(ti.a[3], ortho.a[3], 1e-12 * std::abs(ti.a[0]));
    for (int k : {2, 4, 5}) EXPECT_NEAR(ortho.a[static_cast<std::size_t>(k)], 0.0, 1e-12 * std::abs(ti.a[0]));
    c.angular = ti;
    EXPECT_LT(rel_diff(integrate_bulk_tensor(c, 3), fem::rotate_stiffness(Cm, axes)), 1e-10);
  }
}

TEST(Anisotropy, PlanarRoundTripPlaneStrainAndStressRotated) {
  const Voigt6 Cm = central_orthotropic(60e3, 90e3, 150e3, 0.3, 0.1, 0.2);
  for (const PlaneMode mode : {PlaneMode::strain, PlaneMode::stress})
    for (double angle : {0.0, 0.4, -1.1}) {
      SCOPED_TRACE(::testing::Message()
                   << (mode == PlaneMode::strain ? "strain" : "stress") << ", angle " << angle);
      const Mat3 axes = Mat3(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
      // A 2D central-force tensor: the nearest one to the reduced tensor.
      const Eigen::MatrixXd C2 = peridynamics::nearest_central_force(
          fem::reduce_stiffness(fem::rotate_stiffness(Cm, axes), 2, mode), 2);
      ASSERT_TRUE(peridynamics::cauchy_violations(C2, 2).empty());
      for (auto shape : {KernelShape::constant, KernelShape::exponential}) {
        Micromodulus c = kernel(shape, 1.2, 0.24);
        c.angular = peridynamics::calibrate_angular(c, 2, C2, Mat3::Identity(), AngularKind::planar);
        EXPECT_EQ(c.angular.kind, AngularKind::planar);
        if (angle == 0.0) {  // material axes: the sin terms vanish (Y = a0 + a2 cos2θ + a4 cos4θ)
          EXPECT_EQ(c.angular.a[2], 0.0);
          EXPECT_EQ(c.angular.a[4], 0.0);
        }
        const double err = rel_diff(integrate_bulk_tensor(c, 2), C2);
        std::printf("2D planar round trip, plane %s, %s kernel, axes at %.1f rad: %.2e\n",
                    mode == PlaneMode::strain ? "strain" : "stress", peridynamics::to_string(shape), angle,
                    err);
        EXPECT_LT(err, 1e-10);
      }
    }
}

TEST(Anisotropy, ConstantKernelClosedForms) {
  const double delta = 0.8, d5 = std::pow(delta, 5);
  Micromodulus c = kernel(KernelShape::constant, delta, 1.0);
  EXPECT_NEAR(c.shape_moment(4), d5 / 5.0, 1e-15);
  // Isotropic λ = μ: only a00, equal to the isotropic calibration ĉ = 15 μ / (2π R4) = 75 μ / (2π δ⁵).
  const double mu = 36e3;
  Voigt6 iso = fem::stiffness_voigt(fem::IsotropicElasticity{2.5 * mu, 0.25});
  const auto Y = peridynamics::orthotropic_angular(iso, d5 / 5.0, Mat3::Identity());
  EXPECT_NEAR(Y.a[0], 75.0 * mu / (2.0 * pi * d5), 1e-12 * Y.a[0]);
  EXPECT_NEAR(Y.a[0], peridynamics::calibrate_isotropic(c, 3, PlaneMode::strain, 2.5 * mu).scale,
              1e-12 * Y.a[0]);
  for (int k = 1; k < 6; ++k) EXPECT_NEAR(Y.a[static_cast<std::size_t>(k)], 0.0, 1e-12 * Y.a[0]);
  // Transversely isotropic (2.84)–(2.86), written out with δ⁵.
  const double C11 = 70e3, C13 = 20e3, C33 = 160e3;
  Voigt6 ti = Voigt6::Zero();
  ti(0, 0) = ti(1, 1) = C11;
  ti(2, 2) = C33;
  ti(0, 2) = ti(2, 0) = ti(1, 2) = ti(2, 1) = C13;
  ti(0, 1) = ti(1, 0) = C11 / 3.0;
  const auto T = peridynamics::transversely_isotropic_angular(ti, d5 / 5.0, Mat3::Identity());
  EXPECT_NEAR(T.a[0], 5 * (8 * C11 + 12 * C13 + 3 * C33) / (6 * d5 * pi), 1e-12 * T.a[0]);
  EXPECT_NEAR(T.a[1], -25 * (4 * C11 - 3 * C13 - 3 * C33) / (6 * d5 * pi), 1e-12 * T.a[0]);
  EXPECT_NEAR(T.a[3], 45 * (C11 - 6 * C13 + C33) / (2 * d5 * pi), 1e-12 * T.a[0]);
  // 2D constant kernel: K = π δ⁴/8; isotropic plane strain λ = μ gives a0 = 8μ/(π δ⁴)... = ĉ.
  const Eigen::MatrixXd iso2 = fem::reduce_stiffness(iso, 2, PlaneMode::strain);
  const auto P = peridynamics::planar_angular(iso2, std::pow(delta, 4) / 4.0);
  EXPECT_NEAR(P.a[0], peridynamics::calibrate_isotropic(c, 2, PlaneMode::strain, 2.5 * mu).scale,
              1e-12 * P.a[0]);
  for (int k = 1; k < 5; ++k) EXPECT_NEAR(P.a[static_cast<std::size_t>(k)], 0.0, 1e-12 * P.a[0]);
}

TEST(Anisotropy, AngularPartIsCentrosymmetricAndRotatesWithTheAxes) {
  const Voigt6 Cm = central_orthotropic(60e3, 90e3, 150e3, 0.3, 0.1, 0.2);
  const auto Y0 = peridynamics::orthotropic_angular(Cm, 1.0, Mat3::Identity());
  const auto Y1 = peridynamics::orthotropic_angular(Cm, 1.0, kRotation);
  for (const Vec3& e :
       {Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8).normalized(), Vec3(-0.1, 0.9, 0.2).normalized()}) {
    EXPECT_DOUBLE_EQ(Y0.evaluate(e), Y0.evaluate(-e));
    EXPECT_NEAR(Y1.evaluate(kRotation * e), Y0.evaluate(e), 1e-12 * std::abs(Y0.a[0]));
  }
  const auto [lo, hi] = peridynamics::angular_range(Y0, 3);
  EXPECT_GT(lo, 0.0) << "B4's orthotropic material has a positive micromodulus in every direction";
  EXPECT_GT(hi, lo);
}

TEST(Anisotropy, CauchyRelationsAndNearestCentralForceTensor) {
  // Isotropic ν = 0.3 breaks λ = μ; the nearest tensor has λ' = μ' = (λ + 2μ)/3.
  const double E = 100.0, nu = 0.3;
  const Voigt6 C = fem::stiffness_voigt(fem::IsotropicElasticity{E, nu});
  const double lambda = C(0, 1), mu = C(5, 5);
  const auto v = peridynamics::cauchy_violations(C, 3);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].relation, "C1212 = C1122");
  EXPECT_DOUBLE_EQ(v[0].shear_value, mu);
  EXPECT_DOUBLE_EQ(v[0].normal_value, lambda);
  const Eigen::MatrixXd N = peridynamics::nearest_central_force(C, 3);
  EXPECT_NEAR(N(0, 1), (lambda + 2 * mu) / 3, 1e-12);
  EXPECT_NEAR(N(5, 5), (lambda + 2 * mu) / 3, 1e-12);
  EXPECT_EQ(N(0, 0), C(0, 0));
  EXPECT_TRUE(peridynamics::cauchy_violations(N, 3).empty());
  EXPECT_EQ((peridynamics::nearest_central_force(N, 3) - N).cwiseAbs().maxCoeff(), 0.0);  // a projection
  // Nearest in the tensor norm: the residual C − N is orthogonal to every
  // central-force tensor, e.g. to N itself and to a rotated orthotropic one.
  auto tensor_dot = [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
    // Voigt → tensor weights: normal–normal 1, normal–shear 2, shear–shear 4.
    double s = 0.0;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) s += (i < 3 ? 1 : 2) * (j < 3 ? 1 : 2) * A(i, j) * B(i, j);
    return s;
  };
  const Eigen::MatrixXd other =
      fem::rotate_stiffness(central_orthotropic(6, 9, 15, 0.3, 0.1, 0.2), kRotation);
  EXPECT_NEAR(tensor_dot(C - N, N), 0.0, 1e-10 * tensor_dot(N, N));
  EXPECT_NEAR(tensor_dot(C - N, other), 0.0, 1e-10 * std::sqrt(tensor_dot(C, C) * tensor_dot(other, other)));
  // A rotated central-force tensor still obeys all six relations (incl. C1123 = C1312, ...).
  EXPECT_TRUE(peridynamics::cauchy_violations(other, 3).empty());
  // 2D: plane stress of a 3D central-force material is not central (ν = 1/4 → 1/3 needed).
  const Eigen::MatrixXd ps =
      fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{E, 0.25}), 2, PlaneMode::stress);
  EXPECT_EQ(peridynamics::cauchy_violations(ps, 2).size(), 1u);
}

}  // namespace
}  // namespace perimorph
