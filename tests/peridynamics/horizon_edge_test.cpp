// Partial-volume bond weights (peridynamics/horizon_edge.hpp): the closed
// form against a Monte Carlo of its own definition, its limits, and what it is
// for: the bulk tensor of the lattice converges to C₀ at second order in the
// point spacing, where the plain cut-off converges at first order.

#include "perimorph/peridynamics/horizon_edge.hpp"
#include "perimorph/assembly/discrete_calibration.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace perimorph {
namespace {

using peridynamics::edge_weight;

/// The exact box-pair quantities the closed form approximates, sampled: φ =
/// P(|ξ + v_h − v_g| < δ) and E[r + Z | inside], Z = e·(v_h − v_g), v uniform
/// in the boxes (the true sphere, not its plane approximation).
template <int D>
peridynamics::EdgeWeight monte_carlo(const Vec3& xi, const Vec3& bg, const Vec3& bh, double delta,
                                     std::mt19937_64& rng, int samples) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r = xi.norm();
  const Vec3 e = xi / r;
  long inside = 0;
  double sum = 0.0;
  for (int s = 0; s < samples; ++s) {
    Vec3 v = Vec3::Zero();
    for (int i = 0; i < D; ++i) v[i] = u(rng) * bh[i] - u(rng) * bg[i];
    const double z = e.dot(v);
    if ((xi + v).norm() < delta) {
      ++inside;
      sum += r + z;
    }
  }
  return {static_cast<double>(inside) / samples, inside > 0 ? sum / static_cast<double>(inside) : r};
}

template <int D>
void check_against_monte_carlo(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double delta = 1.0;
  for (int trial = 0; trial < 40; ++trial) {
    Vec3 xi = Vec3::Zero(), bg = Vec3::Zero(), bh = Vec3::Zero();
    for (int i = 0; i < D; ++i) {
      xi[i] = u(rng) - 0.5;
      bg[i] = 0.02 + 0.08 * u(rng);
      bh[i] = 0.02 + 0.08 * u(rng);
    }
    const double reach = peridynamics::edge_reach<D>(xi, xi.norm(), bg, bh);
    xi *= (delta + (2.0 * u(rng) - 1.0) * reach) / xi.norm();  // within reach of the edge
    const auto exact = edge_weight<D>(xi, xi.norm(), bg, bh, delta);
    const auto mc = monte_carlo<D>(xi, bg, bh, delta, rng, 200000);
    // Binomial standard error ≤ 1.1e-3 at 2e5 samples; the plane-plus-mean-
    // curvature model is exact to O(b³/δ²) ≈ 1e-3 for these boxes.
    EXPECT_NEAR(exact.fraction, mc.fraction, 5e-3) << D << "D trial " << trial;
    if (mc.fraction > 0.05) {
      EXPECT_NEAR(exact.r_eff, mc.r_eff, 2e-3) << D << "D trial " << trial;
    }
    EXPECT_LT(exact.r_eff, delta);
  }
}

TEST(PeridynamicsHorizonEdge, ClosedFormMatchesMonteCarlo) {
  std::mt19937_64 rng(12345);
  check_against_monte_carlo<1>(rng);
  check_against_monte_carlo<2>(rng);
  check_against_monte_carlo<3>(rng);
}

TEST(PeridynamicsHorizonEdge, OneDimensionalClosedForms) {
  // Two boxes of half-width b: Z is triangular on [−2b, 2b].
  const double b = 0.1, delta = 1.0;
  const Vec3 hb(b, 0, 0);
  for (double d : {-0.15, -0.05, 0.0, 0.05, 0.15}) {
    const Vec3 xi(delta - d, 0, 0);
    const auto w = edge_weight<1>(xi, xi.norm(), hb, hb, delta);
    const double s = d + 2.0 * b;  // P(S < s), S = Z + 2b triangular on [0, 4b]
    const double F = s <= 2 * b ? s * s / (8 * b * b) : 1.0 - (4 * b - s) * (4 * b - s) / (8 * b * b);
    EXPECT_NEAR(w.fraction, F, 1e-14) << d;
  }
  // Symmetric about the edge, and exactly the limits away from it.
  EXPECT_NEAR(edge_weight<1>(Vec3(delta, 0, 0), delta, hb, hb, delta).fraction, 0.5, 1e-15);
  EXPECT_EQ(edge_weight<1>(Vec3(delta - 0.25, 0, 0), delta - 0.25, hb, hb, delta).fraction, 1.0);
  EXPECT_EQ(edge_weight<1>(Vec3(delta + 0.25, 0, 0), delta + 0.25, hb, hb, delta).fraction, 0.0);
  // A box pair with no extent normal to the bond reduces to the cut-off.
  const Vec3 side(0, b, 0);
  EXPECT_EQ(edge_weight<2>(Vec3(delta - 1e-9, 0, 0), delta - 1e-9, side, side, delta).fraction, 1.0);
  EXPECT_EQ(edge_weight<2>(Vec3(delta + 1e-9, 0, 0), delta + 1e-9, side, side, delta).fraction, 0.0);
}

TEST(PeridynamicsHorizonEdge, NearlyAxisAlignedBondsAreStable) {
  // Components of e below 1e-4 of the largest drop out; the result stays
  // continuous across that switch.
  const double delta = 1.0;
  const Vec3 b(0.05, 0.05, 0.05);
  for (double t : {1e-3, 1e-4, 2e-5, 1e-6, 0.0}) {
    const Vec3 xi = Vec3(1.0, t, 0.5 * t).normalized() * (delta - 0.02);
    const auto w = edge_weight<3>(xi, xi.norm(), b, b, delta);
    const auto w0 = edge_weight<3>(Vec3(delta - 0.02, 0, 0), delta - 0.02, b, b, delta);
    EXPECT_NEAR(w.fraction, w0.fraction, 1e-4) << t;
    EXPECT_GT(w.fraction, 0.5);
    EXPECT_LT(w.fraction, 1.0);
  }
}

/// Relative error of the lattice bulk tensor against the continuum C₀.
double bulk_error(int dim, double h, int n, bool partial) {
  mesh::StructuredLayout layout;
  layout.spacing = Vec3::Constant(h);
  const double delta = 1.0;
  peridynamics::Micromodulus k{peridynamics::KernelShape::exponential, delta, delta / 5.0, 1.0, {}};
  k.scale = peridynamics::calibrate_isotropic(k, dim, PlaneMode::strain, 1.0).scale;
  const Eigen::MatrixXd C0 = fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{1.0, 0.25}),
                                                   dim, PlaneMode::strain);
  const Eigen::MatrixXd D = assembly::lattice_bulk_tensor(layout, dim, n, k, partial);
  return (D - C0).norm() / C0.norm();
}

TEST(PeridynamicsHorizonEdge, BulkTensorConvergesAtSecondOrder) {
  // Exponential kernel l = δ/5 (BENCHMARKS B2/B4): c r⁴ is largest at r = δ,
  // so the cut-off dominates the quadrature error.
  struct Case {
    int dim, n;
    std::vector<double> ratios;  // δ/h
  };
  for (const Case& cs : {Case{2, 4, {3.5, 7.0, 14.0}}, Case{3, 2, {3.0, 6.0, 12.0}}}) {
    std::vector<double> cut, pv;
    for (double q : cs.ratios) {
      cut.push_back(bulk_error(cs.dim, 1.0 / q, cs.n, false));
      pv.push_back(bulk_error(cs.dim, 1.0 / q, cs.n, true));
      std::printf("%dD n=%d delta/h=%5.1f  |D-C0|/|C0|: cutoff %.3e  partial volume %.3e\n", cs.dim, cs.n, q,
                  cut.back(), pv.back());
    }
    const double order_pv = std::log2(pv[1] / pv[2]);
    std::printf("%dD observed order (last pair): cutoff %.2f, partial volume %.2f\n", cs.dim,
                std::log2(cut[1] / cut[2]), order_pv);
    for (std::size_t i = 0; i < pv.size(); ++i) EXPECT_LT(pv[i], cut[i]);
    EXPECT_GT(order_pv, 1.7);
  }
}

}  // namespace
}  // namespace perimorph
