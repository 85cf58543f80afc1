// Micromodulus kernels and their calibration (THEORY §1.1, §2, §5): shape
// moments against closed forms or an independent Simpson rule, the calibrated
// scale and moduli against the table of THEORY §2, the G_c factors of §5, the
// Cauchy-relation check, and an independent integration of the bond tensor
// C_ijkl = ∫_H c(ξ) ξiξjξkξl/(2|ξ|²) dξ in polar/spherical coordinates compared
// with the isotropic (λ = μ) local stiffness.

#include "perimorph/peridynamics/micromodulus.hpp"
#include "perimorph/fem/material.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>

namespace perimorph {
namespace {

using peridynamics::KernelShape;
using peridynamics::Micromodulus;

constexpr double pi = std::numbers::pi;

/// Composite Simpson rule on [a, b] with n (even) intervals; the integrand is
/// evaluated on the closed interval, so it must be smooth there.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

/// φ(r) written independently of the library (no cut-off: used on [0, δ]).
double phi(KernelShape s, double r, double delta, double l) {
  switch (s) {
    case KernelShape::constant:
      return 1.0;
    case KernelShape::conical:
      return 1.0 - r / delta;
    case KernelShape::exponential:
      return r * r * std::exp(-r / l);
    case KernelShape::gaussian:
      return r * r * std::exp(-r * r / (l * l));
    case KernelShape::pmb:
      return r > 0.0 ? 1.0 / r : 0.0;  // only ever multiplied by r^k, k ≥ 2: the limit at 0 is 0
  }
  return 0.0;
}

/// ∫₀^δ φ(r) r^k dr by a fine Simpson rule.
double moment_simpson(KernelShape s, double delta, double l, int k) {
  return simpson([&](double r) { return phi(s, r, delta, l) * std::pow(r, k); }, 0.0, delta, 4000);
}

/// ∫₀^δ r^n e^{−r/l} dr = l^{n+1} γ(n+1, x), x = δ/l, with the lower incomplete gamma function
/// γ(n+1, x) = n! (1 − e^{−x} Σ_{j≤n} x^j/j!) = n! e^{−x} Σ_{j>n} x^j/j! (the tail form: no cancellation).
double exponential_closed_form(int n, double delta, double l) {
  const double x = delta / l;
  double term = 1.0, factorial = 1.0;
  for (int j = 1; j <= n + 1; ++j) {
    term *= x / j;
    if (j <= n) factorial *= j;
  }
  double tail = 0.0;
  for (int j = n + 1; j < n + 200 && term > 1e-30 * tail; ++j) {
    tail += term;
    term *= x / (j + 1);
  }
  return std::pow(l, n + 1) * factorial * std::exp(-x) * tail;
}

Micromodulus kernel(KernelShape s, double delta, double l) {
  Micromodulus k;
  k.shape = s;
  k.horizon = delta;
  k.length = l;
  k.scale = 123.0;  // ignored by shape_moment and calibrate_isotropic
  return k;
}

const std::array<KernelShape, 4> all_shapes{KernelShape::constant, KernelShape::conical,
                                            KernelShape::exponential, KernelShape::gaussian};
/// Every kernel the calibration tests cover (pmb is singular at r = 0, where no bond is).
const std::array<KernelShape, 5> calibrated_shapes{KernelShape::constant, KernelShape::conical,
                                                   KernelShape::exponential, KernelShape::gaussian,
                                                   KernelShape::pmb};

TEST(PeridynamicsKernel, ShapeValuesAndCutOff) {
  const double delta = 1.7, l = 0.4;
  for (KernelShape s : all_shapes) {
    const auto k = kernel(s, delta, l);
    for (double r : {0.0, 0.3, 1.1, 1.69})
      EXPECT_DOUBLE_EQ(k.shape_value(r), phi(s, r, delta, l)) << to_string(s) << " r = " << r;
    EXPECT_EQ(k.shape_value(delta), 0.0) << to_string(s);
    EXPECT_EQ(k.shape_value(2.0 * delta), 0.0) << to_string(s);
    EXPECT_DOUBLE_EQ(k(0.9), 123.0 * phi(s, 0.9, delta, l)) << to_string(s);
  }
  EXPECT_STREQ(peridynamics::to_string(KernelShape::gaussian), "gaussian");
}

TEST(PeridynamicsKernel, ShapeMomentsConstantAndConicalClosedForm) {
  for (double delta : {0.3, 1.0, 2.5})
    for (int k = 0; k <= 6; ++k) {
      const double constant = std::pow(delta, k + 1) / (k + 1);
      const double conical = std::pow(delta, k + 1) / ((k + 1) * (k + 2));
      EXPECT_NEAR(kernel(KernelShape::constant, delta, 1.0).shape_moment(k), constant, 1e-13 * constant);
      EXPECT_NEAR(kernel(KernelShape::conical, delta, 1.0).shape_moment(k), conical, 1e-13 * conical);
    }
}

TEST(PeridynamicsKernel, ShapeMomentsExponentialAndGaussian) {
  for (double delta : {0.5, 2.0})
    for (double ratio : {5.0, 3.0, 1.0})  // l = δ/5 (B2), δ/3 (fracture), δ (smooth)
      for (int k = 0; k <= 6; ++k) {
        const double l = delta / ratio;
        const auto e = kernel(KernelShape::exponential, delta, l);
        const auto g = kernel(KernelShape::gaussian, delta, l);
        const double e_closed = exponential_closed_form(k + 2, delta, l);
        const double e_simpson = moment_simpson(KernelShape::exponential, delta, l, k);
        const double g_simpson = moment_simpson(KernelShape::gaussian, delta, l, k);
        // The closed form and the Simpson rule agree with each other first (the reference is sound) ...
        ASSERT_NEAR(e_simpson, e_closed, 1e-11 * e_closed);
        // ... then the library.
        EXPECT_NEAR(e.shape_moment(k), e_closed, 1e-12 * e_closed)
            << "δ " << delta << " l " << l << " k " << k;
        EXPECT_NEAR(g.shape_moment(k), g_simpson, 1e-11 * g_simpson)
            << "δ " << delta << " l " << l << " k " << k;
      }
}

TEST(PeridynamicsKernel, OneDimensionalConstantKernelIs3EOverDeltaCubed) {
  // THEORY (2.44): c = 3E/δ³; G_c = ½ s² ∫ c r³ = (3Eδ/8) s².
  for (double delta : {0.1, 1.0, 3.0}) {
    const double E = 210.0;
    const auto cal =
        peridynamics::calibrate_isotropic(kernel(KernelShape::constant, delta, 1.0), 1, PlaneMode::strain, E);
    EXPECT_NEAR(cal.scale, 3.0 * E / (delta * delta * delta), 1e-13 * cal.scale);
    EXPECT_EQ(cal.E, E);
    EXPECT_TRUE(std::isnan(cal.nu));
    EXPECT_NEAR(cal.gc_factor, 3.0 * E * delta / 8.0, 1e-13 * cal.gc_factor);
  }
}

TEST(PeridynamicsKernel, PmbIsThePrototypeMicroElasticBrittleModel) {
  // Silling & Askari (2005), Ha & Bobaru (2010): a force per unit stretch c_pmb (c_pmb / r per
  // elongation); 3D c = 18K/(πδ⁴), G_0 = (9/5) K δ s₀²; 2D plane stress c = 9E/(πδ³),
  // G_0 = 9Eδ s₀²/(4π); plane strain c = 48E/(5πδ³); 1D c = 2E/δ², G_0 = Eδ s₀²/3.
  const double E = 300.0;
  for (double delta : {0.3, 1.0, 3.015}) {
    const auto k = kernel(KernelShape::pmb, delta, 1.0);
    EXPECT_DOUBLE_EQ(k.shape_value(0.5 * delta), 2.0 / delta);
    EXPECT_EQ(k.shape_value(delta), 0.0);
    for (int m = 2; m <= 6; ++m)
      EXPECT_NEAR(k.shape_moment(m), std::pow(delta, m) / m, 1e-13 * std::pow(delta, m)) << m;
    const double K = E / (3.0 * (1.0 - 2.0 * 0.25));
    const auto c3 = peridynamics::calibrate_isotropic(k, 3, PlaneMode::strain, E);
    EXPECT_NEAR(c3.scale, 18.0 * K / (pi * std::pow(delta, 4)), 1e-12 * c3.scale);
    EXPECT_NEAR(c3.gc_factor, 9.0 / 5.0 * K * delta, 1e-12 * c3.gc_factor);
    const auto ps = peridynamics::calibrate_isotropic(k, 2, PlaneMode::stress, E);
    EXPECT_NEAR(ps.scale, 9.0 * E / (pi * std::pow(delta, 3)), 1e-12 * ps.scale);
    EXPECT_NEAR(ps.gc_factor, 9.0 * E * delta / (4.0 * pi), 1e-12 * ps.gc_factor);
    const auto pe = peridynamics::calibrate_isotropic(k, 2, PlaneMode::strain, E);
    EXPECT_NEAR(pe.scale, 48.0 * E / (5.0 * pi * std::pow(delta, 3)), 1e-12 * pe.scale);
    const auto c1 = peridynamics::calibrate_isotropic(k, 1, PlaneMode::strain, E);
    EXPECT_NEAR(c1.scale, 2.0 * E / (delta * delta), 1e-12 * c1.scale);
    EXPECT_NEAR(c1.gc_factor, E * delta / 3.0, 1e-12 * c1.gc_factor);
  }
  EXPECT_STREQ(peridynamics::to_string(KernelShape::pmb), "pmb");
}

/// Independent reference moments: closed form for constant and conical, Simpson otherwise.
double reference_moment(KernelShape s, double delta, double l, int k) {
  if (s == KernelShape::constant) return std::pow(delta, k + 1) / (k + 1);
  if (s == KernelShape::conical) return std::pow(delta, k + 1) / ((k + 1) * (k + 2));
  return moment_simpson(s, delta, l, k);
}

TEST(PeridynamicsKernel, CalibrationTable) {
  const double E = 90.0, delta = 0.75, l = delta / 5.0;
  for (KernelShape s : calibrated_shapes) {
    const auto k = kernel(s, delta, l);
    SCOPED_TRACE(to_string(s));
    // 1D: E = ∫ c r² dr, G_c factor ½ ∫ c r³.
    {
      const auto cal = peridynamics::calibrate_isotropic(k, 1, PlaneMode::strain, E);
      EXPECT_NEAR(cal.scale * reference_moment(s, delta, l, 2), E, 1e-11 * E);
      EXPECT_NEAR(cal.gc_factor, 0.5 * cal.scale * reference_moment(s, delta, l, 3), 1e-11 * cal.gc_factor);
    }
    // 3D: λ = μ = (2π/15) ĉ ∫ c r⁴, E = 5μ/2, ν = 1/4, G_c factor (π/2) ĉ ∫ c r⁵.
    {
      const auto cal = peridynamics::calibrate_isotropic(k, 3, PlaneMode::strain, E);
      const double mu = 2.0 * pi / 15.0 * cal.scale * reference_moment(s, delta, l, 4);
      EXPECT_NEAR(cal.lame, mu, 1e-11 * mu);
      EXPECT_NEAR(2.5 * mu, E, 1e-11 * E);
      EXPECT_EQ(cal.nu, 0.25);
      const double gc = pi / 2.0 * cal.scale * reference_moment(s, delta, l, 5);
      EXPECT_NEAR(cal.gc_factor, gc, 1e-11 * gc);
    }
    // 2D: μ = (π/8) ĉ ∫ c r³; plane strain E = 5μ/2, plane stress E = 8μ/3; G_c factor ĉ ∫ c r⁴.
    for (PlaneMode mode : {PlaneMode::strain, PlaneMode::stress}) {
      const auto cal = peridynamics::calibrate_isotropic(k, 2, mode, E);
      const double mu = pi / 8.0 * cal.scale * reference_moment(s, delta, l, 3);
      EXPECT_NEAR(cal.lame, mu, 1e-11 * mu);
      EXPECT_NEAR(mode == PlaneMode::strain ? 2.5 * mu : 8.0 / 3.0 * mu, E, 1e-11 * E);
      EXPECT_DOUBLE_EQ(cal.nu, mode == PlaneMode::strain ? 0.25 : 1.0 / 3.0);
      const double gc = cal.scale * reference_moment(s, delta, l, 4);
      EXPECT_NEAR(cal.gc_factor, gc, 1e-11 * gc);
    }
  }
}

TEST(PeridynamicsKernel, CalibrationIgnoresGivenScaleAndIsLinearInE) {
  auto k = kernel(KernelShape::gaussian, 1.2, 0.4);
  const auto a = peridynamics::calibrate_isotropic(k, 3, PlaneMode::strain, 10.0);
  k.scale = 1e6;
  const auto b = peridynamics::calibrate_isotropic(k, 3, PlaneMode::strain, 30.0);
  EXPECT_NEAR(b.scale, 3.0 * a.scale, 1e-14 * b.scale);
  EXPECT_NEAR(b.gc_factor, 3.0 * a.gc_factor, 1e-14 * b.gc_factor);
}

TEST(PeridynamicsKernel, CauchyPoissonRatio) {
  EXPECT_EQ(peridynamics::cauchy_poisson_ratio(3, PlaneMode::strain), 0.25);
  EXPECT_EQ(peridynamics::cauchy_poisson_ratio(3, PlaneMode::stress), 0.25);  // plane mode ignored in 3D
  EXPECT_EQ(peridynamics::cauchy_poisson_ratio(2, PlaneMode::strain), 0.25);
  EXPECT_DOUBLE_EQ(peridynamics::cauchy_poisson_ratio(2, PlaneMode::stress), 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(peridynamics::cauchy_poisson_ratio(1, PlaneMode::strain)));
}

TEST(PeridynamicsKernel, CauchyProblemAcceptsOnlyTheCentralForceRatio) {
  using peridynamics::cauchy_problem;
  EXPECT_EQ(cauchy_problem(3, PlaneMode::strain, 0.25), "");
  EXPECT_EQ(cauchy_problem(2, PlaneMode::strain, 0.25), "");
  EXPECT_EQ(cauchy_problem(2, PlaneMode::stress, 1.0 / 3.0), "");
  for (double nu : {-0.5, 0.0, 0.25, 0.3, 0.49})
    EXPECT_EQ(cauchy_problem(1, PlaneMode::strain, nu), "") << nu;

  struct Bad {
    int dim;
    PlaneMode mode;
    double nu;
    const char* required;
    const char* setting;
  };
  for (const Bad& b :
       {Bad{3, PlaneMode::strain, 0.3, "1/4", "3D"}, Bad{3, PlaneMode::strain, 1.0 / 3.0, "1/4", "3D"},
        Bad{2, PlaneMode::strain, 0.2, "1/4", "plane strain"},
        Bad{2, PlaneMode::strain, 1.0 / 3.0, "1/4", "plane strain"},
        Bad{2, PlaneMode::stress, 0.25, "1/3", "plane stress"},
        Bad{2, PlaneMode::stress, 0.3, "1/3", "plane stress"}}) {
    const std::string m = cauchy_problem(b.dim, b.mode, b.nu);
    SCOPED_TRACE(m);
    EXPECT_NE(m.find("Cauchy"), std::string::npos);
    EXPECT_NE(m.find(b.required), std::string::npos);
    EXPECT_NE(m.find(b.setting), std::string::npos);
  }
}

/// Full 4th-order tensor from a Voigt matrix (engineering shear: the Voigt
/// entries are the tensor components themselves).
double voigt_component(const Eigen::MatrixXd& C, int dim, int i, int j, int k, int l) {
  auto v = [dim](int a, int b) {
    if (a == b) return a;
    if (dim == 2) return 2;
    return 6 - a - b;  // (1,2)→3 yz, (0,2)→4 xz, (0,1)→5 xy
  };
  return C(v(i, j), v(k, l));
}

/// C_ijkl = ∫₀^δ c(r) r^{d+1}/2 dr · ∫_{S^{d−1}} n_i n_j n_k n_l dS, the radial
/// part by Simpson, the angular part by the trapezoid rule in φ (exact for
/// these trigonometric polynomials) and Simpson in θ (3D).
std::array<double, 81> bond_tensor(KernelShape s, double delta, double l, double scale, int dim) {
  const double radial =
      0.5 * scale *
      simpson([&](double r) { return phi(s, r, delta, l) * std::pow(r, dim + 1); }, 0.0, delta, 4000);
  std::array<double, 81> T{};
  auto add = [&](const Vec3& n, double w) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int m = 0; m < 3; ++m)
            T[static_cast<std::size_t>(((i * 3 + j) * 3 + k) * 3 + m)] += w * n[i] * n[j] * n[k] * n[m];
  };
  const int nphi = 64;
  const double dphi = 2.0 * pi / nphi;
  if (dim == 2) {
    for (int p = 0; p < nphi; ++p) add(Vec3(std::cos(p * dphi), std::sin(p * dphi), 0.0), radial * dphi);
  } else {
    const int nth = 2000;
    const double dth = pi / nth;
    for (int t = 0; t <= nth; ++t) {
      const double th = t * dth;
      const double w = (t == 0 || t == nth ? 1.0 : t % 2 == 1 ? 4.0 : 2.0) * dth / 3.0 * std::sin(th);
      if (w == 0.0) continue;
      for (int p = 0; p < nphi; ++p)
        add(Vec3(std::sin(th) * std::cos(p * dphi), std::sin(th) * std::sin(p * dphi), std::cos(th)),
            radial * w * dphi);
    }
  }
  return T;
}

TEST(PeridynamicsKernel, CalibratedScaleReproducesIsotropicStiffness) {
  const double E = 70.0, delta = 1.3;
  for (KernelShape s : calibrated_shapes)
    for (double l : {delta / 5.0, delta / 3.0}) {
      if ((s == KernelShape::constant || s == KernelShape::conical || s == KernelShape::pmb) &&
          l != delta / 5.0)
        continue;
      for (int dim : {2, 3})
        for (PlaneMode mode : {PlaneMode::strain, PlaneMode::stress}) {
          if (dim == 3 && mode == PlaneMode::stress) continue;
          SCOPED_TRACE(::testing::Message() << to_string(s) << " l " << l << " dim " << dim
                                            << (mode == PlaneMode::strain ? " strain" : " stress"));
          const auto cal = peridynamics::calibrate_isotropic(kernel(s, delta, l), dim, mode, E);
          const auto T = bond_tensor(s, delta, l, cal.scale, dim);
          // Isotropic λ = μ tensor, and the library's reduced local stiffness for (E, ν = cal.nu).
          const double mu = cal.lame;
          const Eigen::MatrixXd C0 =
              fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{E, cal.nu}), dim, mode);
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j)
              for (int k = 0; k < dim; ++k)
                for (int m = 0; m < dim; ++m) {
                  const double t = T[static_cast<std::size_t>(((i * 3 + j) * 3 + k) * 3 + m)];
                  const double iso = mu * ((i == j) * (k == m) + (i == k) * (j == m) + (i == m) * (j == k));
                  EXPECT_NEAR(t, iso, 1e-8 * mu) << i << j << k << m;
                  EXPECT_NEAR(t, voigt_component(C0, dim, i, j, k, m), 1e-8 * mu) << i << j << k << m;
                }
        }
    }
}

}  // namespace
}  // namespace perimorph
