// The local damage law of THEORY §6 (fem/damage_law.hpp) against its closed
// form on strain paths: uniaxial strain and pure shear, loading, unloading,
// reloading; irreversibility, the cap at d_c, the threshold k0, the
// dissipation along the path and the consistent tangent.

#include "perimorph/fem/damage_law.hpp"
#include "perimorph/fem/material.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <vector>

namespace perimorph {
namespace {

// The thesis' material (§3.4.3): E = 300 GPa, ν = 0.25 (λ = μ = Λ = 120 GPa),
// k0 = 2 GPa, k1 = 10 GPa, d_c = 0.2. Units: GPa.
const fem::DamageLaw law{2.0, 10.0, 0.2};
const Eigen::MatrixXd C0 =
    fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{300.0, 0.25}), 3, PlaneMode::strain);
constexpr double Lambda = 120.0;

Eigen::VectorXd uniaxial(double e) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6);
  v[0] = e;
  return v;
}
Eigen::VectorXd shear(double g) {  // engineering shear γ_xy = g
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6);
  v[5] = g;
  return v;
}

/// The thesis' Y = ½Λ tr(ε)² + Λ tr(ε²) (3.40), for λ = μ = Λ.
double thesis_Y(const Eigen::VectorXd& v) {
  Eigen::Matrix3d e;
  e << v[0], 0.5 * v[5], 0.5 * v[4], 0.5 * v[5], v[1], 0.5 * v[3], 0.5 * v[4], 0.5 * v[3], v[2];
  return 0.5 * Lambda * e.trace() * e.trace() + Lambda * (e * e).trace();
}

/// Closed form of d along a monotone-or-not path: max over the path so far of
/// (Y − k0)/k1, clipped to [0, d_c].
struct Walk {
  double d = 0.0, d_closed = 0.0, Ymax = 0.0;
  void step(const Eigen::VectorXd& eps) {
    const double Y = fem::damage_force(C0.data(), eps.data(), 6);
    d = fem::updated_damage(law, Y, d);
    Ymax = std::max(Ymax, Y);
    d_closed = std::clamp((Ymax - law.k0) / law.k1, 0.0, law.d_c);
  }
};

TEST(DamageLaw, DamageForceIsTheThesisFormulaForLambdaEqualMu) {
  for (const auto& eps :
       {uniaxial(0.01), shear(0.02),
        Eigen::VectorXd((Eigen::VectorXd(6) << 0.01, -0.003, 0.002, 0.004, -0.001, 0.005).finished())}) {
    EXPECT_NEAR(fem::damage_force(C0.data(), eps.data(), 6), thesis_Y(eps), 1e-12 * thesis_Y(eps));
    EXPECT_NEAR(fem::damage_force(C0.data(), eps.data(), 6), 0.5 * eps.dot(C0 * eps), 1e-13);
  }
}

TEST(DamageLaw, UniaxialStrainLoadUnloadReloadFollowsTheClosedForm) {
  // λ + 2μ = 360, Y = ½ (λ + 2μ) e² = 180 e²: onset at e = sqrt(2/180), d_c at sqrt(4/180).
  const double onset = std::sqrt(law.k0 / 180.0), critical = std::sqrt((law.k0 + law.k1 * law.d_c) / 180.0);
  std::vector<double> path;
  for (int k = 0; k <= 40; ++k) path.push_back(0.9 * critical * k / 40.0);  // load past onset
  for (int k = 40; k >= 0; --k) path.push_back(0.9 * critical * k / 40.0);  // unload to 0
  for (int k = 0; k <= 60; ++k) path.push_back(1.3 * critical * k / 60.0);  // reload past d_c
  for (int k = 60; k >= 30; --k) path.push_back(1.3 * critical * k / 60.0);
  Walk w;
  double d_prev = 0.0;
  for (double e : path) {
    w.step(uniaxial(e));
    EXPECT_NEAR(w.d, w.d_closed, 1e-14) << "e = " << e;
    EXPECT_GE(w.d, d_prev) << "d decreased";
    d_prev = w.d;
    if (e < onset) {
      EXPECT_EQ(w.d, w.d_closed);
    }
    // σ = (1 − d) C₀ ε: the unloading branch is secant, through the origin.
    Eigen::VectorXd s(6);
    fem::damaged_stress(C0.data(), uniaxial(e).data(), w.d, 6, s.data());
    EXPECT_NEAR(s[0], (1.0 - w.d) * 360.0 * e, 1e-12);
  }
  EXPECT_EQ(w.d, law.d_c) << "capped at d_c";
}

TEST(DamageLaw, PureShearFollowsTheClosedForm) {
  // Y = ½ μ γ² = 60 γ².
  Walk w;
  for (int k = 0; k <= 50; ++k) {
    const double g = 0.4 * k / 50.0;
    w.step(shear(g));
    EXPECT_NEAR(w.d, std::clamp((60.0 * g * g - law.k0) / law.k1, 0.0, law.d_c), 1e-14);
  }
  for (int k = 50; k >= 0; --k) {
    const double before = w.d;
    w.step(shear(0.4 * k / 50.0));
    EXPECT_EQ(w.d, before) << "unloading leaves d";
  }
}

TEST(DamageLaw, BelowTheThresholdNothingChangesBitwise) {
  for (double e : {0.0, 1e-6, 0.05, std::sqrt(law.k0 / 180.0) * 0.999}) {
    const Eigen::VectorXd eps = uniaxial(e);
    const double d = fem::updated_damage(law, fem::damage_force(C0.data(), eps.data(), 6), 0.0);
    EXPECT_EQ(d, 0.0);
    Eigen::VectorXd s(6), s0 = C0 * eps;
    fem::damaged_stress(C0.data(), eps.data(), d, 6, s.data());
    for (int i = 0; i < 6; ++i) {
      double ref = 0.0;
      for (int j = 0; j < 6; ++j) ref += C0(i, j) * eps[j];
      EXPECT_EQ(s[i], ref) << "d = 0 is elasticity bit for bit";
    }
  }
}

TEST(DamageLaw, DissipationIsTheThresholdIntegratedAlongThePath) {
  // Σ over fine steps of (k0 + k1 d) Δd equals k0 d + ½ k1 d².
  double sum = 0.0, d = 0.0;
  const int n = 20000;
  for (int k = 1; k <= n; ++k) {
    const double dn = law.d_c * k / n;
    sum += (law.k0 + law.k1 * 0.5 * (d + dn)) * (dn - d);
    d = dn;
  }
  EXPECT_NEAR(sum, fem::damage_dissipation(law, law.d_c), 1e-12);
  EXPECT_DOUBLE_EQ(fem::damage_dissipation(law, 0.2), 2.0 * 0.2 + 0.5 * 10.0 * 0.04);
}

TEST(DamageLaw, ConsistentTangentIsTheDerivativeOfTheStress) {
  const Eigen::VectorXd eps = (Eigen::VectorXd(6) << 0.14, -0.02, 0.01, 0.03, -0.01, 0.02).finished();
  const double d_prev = 0.01;
  ASSERT_TRUE(fem::damage_loading(law, fem::damage_force(C0.data(), eps.data(), 6), d_prev));
  auto stress = [&](const Eigen::VectorXd& e) {
    const double d = fem::updated_damage(law, fem::damage_force(C0.data(), e.data(), 6), d_prev);
    Eigen::VectorXd s(6);
    fem::damaged_stress(C0.data(), e.data(), d, 6, s.data());
    return s;
  };
  Eigen::MatrixXd T(6, 6);
  fem::damage_tangent(law, C0.data(), eps.data(), d_prev, 6, T.data());
  const double h = 1e-7;
  for (int j = 0; j < 6; ++j) {
    Eigen::VectorXd ep = eps, em = eps;
    ep[j] += h;
    em[j] -= h;
    const Eigen::VectorXd col = (stress(ep) - stress(em)) / (2 * h);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(T(i, j), col[i], 1e-5 * C0.norm()) << i << "," << j;
  }
  EXPECT_NEAR((T - T.transpose()).norm(), 0.0, 1e-12) << "symmetric";
}

}  // namespace
}  // namespace perimorph
