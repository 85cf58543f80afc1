// The morphed local stiffness (THEORY §3, eq. 2.28) on models built by
// setup::build_discretization from small cases:
//  - C = C₀ bitwise at points whose horizon has α ≡ 0; C = 0 bitwise (and the
//    cell flagged purely non-local) where α ≡ 1 on the horizon;
//  - in the morphing zone C has major symmetry, equals (1 − α)C₀ + the
//    horizon integral, and that integral has the central (Cauchy) symmetry
//    C_ijkl = C_ikjl;
//  - the partition rule gives exactly (1 − α)C₀;
//  - 1D: C/E₀ = β(x) of THEORY §3 (1D form), β evaluated here by a fine
//    quadrature, to within the quadrature error of the non-local points;
//  - the discrete energy identity of the morphing rule under a uniform strain.

#include "perimorph/assembly/morphed_stiffness.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/fem/shape.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

namespace perimorph {
namespace {

using casefile::KernelKind;

/// Physical position of local quadrature point q of cell c (Q1 map written here).
Vec3 local_point(const setup::Discretization& m, Index c, int q) {
  const Vec3& xi = m.rule[static_cast<std::size_t>(q)].xi;
  Vec3 x = Vec3::Zero();
  const auto nodes = m.mesh.cell(c);
  for (int a = 0; a < m.mesh.nodes_per_cell(); ++a) {
    double N = 1.0;
    for (int d = 0; d < m.dim(); ++d) N *= 0.5 * (1.0 + (((a >> d) & 1) ? 1.0 : -1.0) * xi[d]);
    x += N * m.mesh.node(nodes[static_cast<std::size_t>(a)]);
  }
  return x;
}

/// The box of local quadrature point q of cell c (fem::q1_point_box_half_widths
/// with the local rule's 1D weights).
Vec3 local_box(const setup::Discretization& m, Index c, int q) {
  const int dim = m.dim();
  int n = 1;
  while (fem::gauss_legendre(dim, n).size() < m.rule.size()) ++n;
  const Vec3 w = fem::gauss_legendre_line_weights(dim, n)[static_cast<std::size_t>(q)];
  const auto nodes = m.mesh.cell(c);
  auto box = [&]<int D>() {
    fem::NodeCoords<D> X;
    for (int a = 0; a < fem::q1_nodes<D>; ++a)
      X.col(a) = m.mesh.node(nodes[static_cast<std::size_t>(a)]).template head<D>();
    return fem::q1_point_box_half_widths<D>(X, m.rule[static_cast<std::size_t>(q)].xi, w);
  };
  return dim == 2 ? box.template operator()<2>() : box.template operator()<3>();
}

/// Reference stiffness of the case's (single, isotropic) material, as the model reduces it.
Eigen::MatrixXd reference_C0(const casefile::CaseConfig& c) {
  const auto& mat = c.materials.front();
  return fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{mat.E, mat.nu}), c.dim(),
                               c.model.plane);
}

/// min and max of α over the non-local points within δ of x, and α(x) itself.
std::pair<double, double> horizon_alpha_range(const setup::Discretization& m, const Vec3& x) {
  const auto& nl = *m.nonlocal;
  double lo = nl.alpha(x), hi = lo;
  for (std::size_t k = 0; k < nl.points.x.size(); ++k)
    if ((nl.points.x[k] - x).norm() < nl.kernel.horizon) {
      lo = std::min(lo, nl.points.alpha[k]);
      hi = std::max(hi, nl.points.alpha[k]);
    }
  return {lo, hi};
}

bool bitwise_equal(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::MatrixXd& B) {
  return A.rows() == B.rows() && A.cols() == B.cols() && (A.array() == B.array()).all();
}

/// Voigt index of the tensor pair (i, j): xx | xx yy xy | xx yy zz yz xz xy.
int voigt_index(int dim, int i, int j) {
  if (i == j) return i;
  return dim == 2 ? 2 : 6 - i - j;
}

/// The hybrid cases of the tests: an α ball in the middle of a box, wide enough
/// that its centre has α ≡ 1 on the horizon and the corners α ≡ 0.
/// Makes the single material orthotropic (B4's constants scaled, axes rotated
/// about z in 2D and about (1, 2, 3) in 3D), shear moduli from Cauchy.
void make_orthotropic(casefile::CaseConfig& c) {
  auto& m = c.materials.front();
  m.kind = casefile::MaterialKind::orthotropic;
  const double E = m.E;
  m.E1 = 0.6 * E;
  m.E2 = 0.9 * E;
  m.E3 = 1.5 * E;
  m.nu12 = 0.3;
  m.nu13 = 0.1;
  m.nu23 = 0.2;
  m.G12 = m.G13 = m.G23 = std::numeric_limits<double>::quiet_NaN();
  m.axes = c.dim() == 2 ? Mat3(Eigen::AngleAxisd(0.4, Vec3::UnitZ()))
                        : Mat3(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));
}

casefile::CaseConfig ball_case(int dim, casefile::AlphaProfile profile = casefile::AlphaProfile::cubic) {
  if (dim == 2) {
    // h = 0.25, δ = 0.6: α ≡ 1 on the horizon within 0.4 of the centre, α ≡ 0 beyond 2.3.
    auto c = testing::box_case(2, {16, 16, 1}, Vec3(4.0, 4.0, 1.0), 200.0, 0.25);
    testing::add_nonlocal(c, KernelKind::exponential, 0.6, 0.12, 2);
    c.alpha.regions = {testing::alpha_ball(Vec3(2.0, 2.0, 0.0), 1.0, 0.7, profile)};
    return c;
  }
  // h = 0.25, δ = 0.5: α ≡ 1 on the horizon within 0.4 of the centre, α ≡ 0 beyond 1.75.
  auto c = testing::box_case(3, {10, 10, 10}, Vec3(2.5, 2.5, 2.5), 90.0, 0.25);
  testing::add_nonlocal(c, KernelKind::gaussian, 0.5, 0.5 / 3.0, 2);
  c.alpha.regions = {testing::alpha_ball(Vec3(1.25, 1.25, 1.25), 0.9, 0.35, profile)};
  return c;
}

TEST(AssemblyMorphed, LocalWhereAlphaVanishesOnHorizonNonlocalWhereAlphaIsOne) {
  for (const bool orthotropic : {false, true})
    for (int dim : {2, 3}) {
      SCOPED_TRACE(::testing::Message() << dim << "D" << (orthotropic ? ", orthotropic" : ""));
      auto c = ball_case(dim);
      if (orthotropic) make_orthotropic(c);
      const auto m = setup::build_discretization(c);
      const Eigen::MatrixXd C0 = orthotropic ? m.nonlocal->material.C0 : reference_C0(c);
      const auto& morph = m.nonlocal->morph;
      const int nq = static_cast<int>(m.rule.size());
      int local_points = 0, nonlocal_points = 0, nonlocal_cells = 0, flagged = 0;
      for (Index cell = 0; cell < m.mesh.num_cells(); ++cell) {
        bool all_one = true;
        for (int q = 0; q < nq; ++q) {
          const auto [lo, hi] = horizon_alpha_range(m, local_point(m, cell, q));
          const auto C = m.stiffness.matrix(cell, q);
          if (hi == 0.0) {
            ++local_points;
            EXPECT_TRUE(bitwise_equal(C, C0)) << "cell " << cell << " point " << q << "\n" << C;
          }
          if (lo == 1.0) {
            ++nonlocal_points;
            EXPECT_EQ(C.cwiseAbs().maxCoeff(), 0.0) << "cell " << cell << " point " << q;
          }
          all_one = all_one && lo == 1.0;
        }
        const bool flag = morph.purely_nonlocal[static_cast<std::size_t>(cell)] != 0;
        flagged += flag ? 1 : 0;
        if (all_one) {
          ++nonlocal_cells;
          EXPECT_TRUE(flag) << "cell " << cell;
        }
        if (flag) {
          for (int q = 0; q < nq; ++q)
            EXPECT_EQ(m.stiffness.matrix(cell, q).cwiseAbs().maxCoeff(), 0.0) << cell;
        }
        EXPECT_TRUE(m.has_local_stiffness(cell) == !flag);
      }
      std::printf(
          "%dD: %d points with α ≡ 0 on the horizon, %d with α ≡ 1; %d cells with α ≡ 1 everywhere, %d "
          "flagged\n",
          dim, local_points, nonlocal_points, nonlocal_cells, flagged);
      EXPECT_GT(local_points, 0);
      EXPECT_GT(nonlocal_cells, 0);
      EXPECT_GT(morph.morphing_cells, 0);
    }
}

TEST(AssemblyMorphed, MorphingZoneSymmetries) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(::testing::Message() << dim << "D");
    const auto c = ball_case(dim);
    const auto m = setup::build_discretization(c);
    const auto& nl = *m.nonlocal;
    const Eigen::MatrixXd C0 = reference_C0(c);
    const int nq = static_cast<int>(m.rule.size());
    const double c0max = C0.cwiseAbs().maxCoeff();
    int checked = 0;
    double largest_integral = 0.0;
    for (Index cell = 0; cell < m.mesh.num_cells(); ++cell)
      for (int q = 0; q < nq; ++q) {
        const Vec3 x = local_point(m, cell, q);
        const auto [lo, hi] = horizon_alpha_range(m, x);
        if (lo == hi) continue;  // not in the morphing zone
        ++checked;
        const Eigen::MatrixXd C = m.stiffness.matrix(cell, q);
        const double a = nl.alpha(x);
        EXPECT_NEAR(
            assembly::alpha_at_local_point(m.mesh, nl.alpha, cell, m.rule[static_cast<std::size_t>(q)].xi), a,
            1e-14);
        // Major symmetry, exactly.
        EXPECT_TRUE(bitwise_equal(C, C.transpose())) << "cell " << cell << " point " << q;
        // C = (1 − α) C₀ + horizon integral (over the cell's graph row).
        const Eigen::MatrixXd I =
            assembly::horizon_integral(x, a, nl.graph.row(cell), nl.points, nl.kernel, m.mesh);
        EXPECT_LE((C - (1.0 - a) * C0 - I).cwiseAbs().maxCoeff(), 1e-14 * c0max);
        largest_integral = std::max(largest_integral, I.cwiseAbs().maxCoeff());
        // Central symmetry of the integral, C_ijkl = C_ikjl, on the full tensor.
        const double imax = std::max(I.cwiseAbs().maxCoeff(), 1e-300);
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            for (int k = 0; k < dim; ++k)
              for (int l = 0; l < dim; ++l) {
                const double ijkl = I(voigt_index(dim, i, j), voigt_index(dim, k, l));
                const double ikjl = I(voigt_index(dim, i, k), voigt_index(dim, j, l));
                EXPECT_LE(std::abs(ijkl - ikjl), 1e-14 * imax) << i << j << k << l;
              }
        // C₀ has λ = μ, so the whole morphed C keeps the central symmetry too.
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            for (int k = 0; k < dim; ++k)
              for (int l = 0; l < dim; ++l)
                EXPECT_LE(std::abs(C(voigt_index(dim, i, j), voigt_index(dim, k, l)) -
                                   C(voigt_index(dim, i, k), voigt_index(dim, j, l))),
                          1e-13 * c0max);
      }
    EXPECT_GT(checked, 0);
    // The integral is not negligible there: the test is not about (1 − α) C₀ alone.
    EXPECT_GT(largest_integral, 1e-3 * c0max);
  }
}

TEST(AssemblyMorphed, PartitionRuleIsExactlyOneMinusAlphaTimesC0) {
  for (int dim : {2, 3})
    for (auto profile : {casefile::AlphaProfile::linear, casefile::AlphaProfile::cubic}) {
      auto c = ball_case(dim, profile);
      c.nonlocal.coupling = casefile::Coupling::partition;
      const auto m = setup::build_discretization(c);
      const Eigen::MatrixXd C0 = reference_C0(c);
      const int nq = static_cast<int>(m.rule.size());
      int fractional = 0;
      for (Index cell = 0; cell < m.mesh.num_cells(); ++cell) {
        bool all_one = true;
        for (int q = 0; q < nq; ++q) {
          // α at the point as the model computes it (the same as the field at our own point, to round-off).
          const double a = assembly::alpha_at_local_point(m.mesh, m.nonlocal->alpha, cell,
                                                          m.rule[static_cast<std::size_t>(q)].xi);
          EXPECT_NEAR(a, m.nonlocal->alpha(local_point(m, cell, q)), 1e-14);
          fractional += a > 0.0 && a < 1.0 ? 1 : 0;
          all_one = all_one && a == 1.0;
          const Eigen::MatrixXd expected = (1.0 - a) * C0;
          EXPECT_TRUE(bitwise_equal(m.stiffness.matrix(cell, q), expected))
              << dim << "D cell " << cell << " α " << a;
        }
        EXPECT_EQ(m.nonlocal->morph.purely_nonlocal[static_cast<std::size_t>(cell)] != 0, all_one) << cell;
      }
      EXPECT_GT(fractional, 0);
    }
}

// ---- 1D: C/E₀ = β(x) --------------------------------------------------------------------------------------

double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  if (b <= a) return 0.0;
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

/// β(x) = 1 − α(x) + ∫_{x−δ}^{x+δ} (α(x) − α(p)) c(|p − x|) (p − x)² / (4E₀) dp (THEORY §3, 1D),
/// by Simpson on the pieces between the kinks of α and of c (p = x) and the bar's ends.
double beta(double x, const std::function<double(double)>& alpha, const std::function<double(double)>& c,
            double E0, double delta, std::vector<double> breaks, double length) {
  breaks.push_back(x);
  breaks.push_back(std::max(0.0, x - delta));
  breaks.push_back(std::min(length, x + delta));
  std::sort(breaks.begin(), breaks.end());
  const double a0 = std::max(0.0, x - delta), a1 = std::min(length, x + delta);
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a0, breaks[i]), hi = std::min(a1, breaks[i + 1]);
    integral +=
        simpson([&](double p) { return (alpha(x) - alpha(p)) * c(std::abs(p - x)) * (p - x) * (p - x); }, lo,
                hi, 2000);
  }
  return 1.0 - alpha(x) + integral / (4.0 * E0);
}

TEST(AssemblyMorphed, OneDimensionalStiffnessIsBetaTimesE0) {
  // Bar [0, 10], h = 0.25, δ = 1 (δ/h = 4), 4 non-local points per cell; α = 1 on
  // [6, 20] with a transition of width 3 (α > 0 from x = 3).
  //
  // Tolerance. The library integrates (α(x) − α(p)) c ξ² with the cells' Gauss
  // points; where c(δ) ≠ 0 that integrand jumps at p = x ± δ by
  //   J± = |α(x) − α(x ± δ)| c(δ) δ² / (4E₀),
  // and a Gauss rule misses a jump by at most J times its largest weight
  // (Chebyshev–Markov–Stieltjes separation theorem): w_max = 0.6521·h/2 = 0.0815
  // here. The rest of the integrand is continuous (kinks of α only) and its
  // error is what the gaussian kernel shows (c(δ) ∝ e^{−9}): observed below
  // 1e-4, allowed 2e-4. So |C/E₀ − β| ≤ w_max (J₋ + J₊) + 2e-4 at every point;
  // for the constant kernel the jump term dominates (observed ≈ 6e-3, about a
  // tenth of the horizon correction β − (1 − α) itself: a first-order error).
  const double length = 10.0, delta = 1.0, E0 = 1.0, x_in = 6.0, L = 3.0, h = 0.25;
  const double w_max = 0.6521451548625461 * h / 2.0;
  const double smooth_allowance = 2e-4;
  for (KernelKind kernel : {KernelKind::constant, KernelKind::gaussian})
    for (auto profile : {casefile::AlphaProfile::linear, casefile::AlphaProfile::cubic}) {
      auto c = testing::box_case(1, {40, 1, 1}, Vec3(length, 1, 1), E0, 0.3);
      testing::add_nonlocal(c, kernel, delta, delta / 3.0, 4);
      casefile::AlphaRegionSpec region;
      region.shape = casefile::AlphaShapeKind::interval;
      region.lower = Vec3(x_in, 0, 0);
      region.upper = Vec3(20.0, 0, 0);
      region.transition = L;
      region.profile = profile;
      c.alpha.regions = {region};
      const auto m = setup::build_discretization(c);
      const double E = reference_C0(c)(0, 0);
      const bool cubic = profile == casefile::AlphaProfile::cubic;
      // α and c written independently of the library.
      auto alpha = [&](double x) {
        const double t = std::clamp(1.0 - (x_in - x) / L, 0.0, 1.0);
        return cubic ? t * t * (3.0 - 2.0 * t) : t;
      };
      const double chat = m.nonlocal->kernel.scale;
      const double l = delta / 3.0;
      auto micro = [&](double r) {
        return kernel == KernelKind::constant ? chat : chat * r * r * std::exp(-r * r / (l * l));
      };
      if (kernel == KernelKind::constant) {
        EXPECT_NEAR(chat, 3.0 * E0 / (delta * delta * delta), 1e-12);
      }
      double worst = 0.0, worst_x = 0.0, worst_bound = 0.0, largest_change = 0.0;
      for (Index cell = 0; cell < m.mesh.num_cells(); ++cell)
        for (int q = 0; q < static_cast<int>(m.rule.size()); ++q) {
          const double x = local_point(m, cell, q).x();
          const double b = beta(x, alpha, micro, E0, delta, {x_in - L, x_in}, length);
          const double ratio = m.stiffness.matrix(cell, q)(0, 0) / E;
          double jumps = 0.0;
          for (double p : {x - delta, x + delta})
            if (p > 0.0 && p < length)
              jumps += std::abs(alpha(x) - alpha(p)) * micro(delta) * delta * delta / (4.0 * E0);
          const double bound = w_max * jumps + smooth_allowance;
          largest_change = std::max(largest_change, std::abs(b - (1.0 - alpha(x))));
          if (std::abs(ratio - b) > worst) {
            worst = std::abs(ratio - b);
            worst_x = x;
            worst_bound = bound;
          }
          EXPECT_LE(std::abs(ratio - b), bound) << "x = " << x;
        }
      std::printf(
          "1D %s kernel, %s α: max |C/E0 − β| = %.3e at x = %.3f (bound there %.3e); max |β − (1 − α)| = "
          "%.3e\n",
          kernel == KernelKind::constant ? "constant" : "gaussian", cubic ? "cubic" : "linear", worst,
          worst_x, worst_bound, largest_change);
      // The horizon correction is well above the error: the test sees it.
      EXPECT_GT(largest_change, 5.0 * worst);
    }
}

// ---- Energy identity -------------------------------------------------------------------------------------

/// Under a uniform strain ε, at a local point x whose horizon lies inside the body,
///   ½ε:C(x):ε + ¼ Σ_h w_h ᾱ c η²  =  (1 − α(x)) ½ε:C₀:ε + α(x) ½ε:D:ε,
/// with D = Σ_h w_h c ξξξξ/(2|ξ|²) the discrete bulk tensor on the same points (sums over
/// the non-local points within δ). Exact to round-off: the α_h terms cancel between the
/// horizon integral of C and the bond energy. So the hybrid energy equals ½ε:D:ε only
/// where α(x) = 1 or to within (1 − α)·½ε:(C₀ − D):ε, the quadrature error of D
/// (measured in quadrature_energy_test.cpp), and equals the local ½ε:C₀:ε up to α·½ε:(D − C₀):ε.
TEST(AssemblyMorphed, DiscreteEnergyIdentityUnderUniformStrain) {
  // 2D also with a thickness t ≠ 1: the point weights then carry t, and the
  // identity holds per unit volume only if the micromodulus is ĉ/t.
  // With partial-volume bonds the same identity holds with the box-pair weights
  // (the local point's box being that of the local rule).
  struct Setting {
    int dim;
    double thickness;
    casefile::HorizonEdge edge;
    bool orthotropic = false;  // rotated axes, anisotropic micromodulus (issue 4)
  };
  for (const auto& [dim, thickness, edge, orthotropic] :
       {Setting{2, 1.0, casefile::HorizonEdge::cutoff}, Setting{2, 0.4, casefile::HorizonEdge::cutoff},
        Setting{3, 1.0, casefile::HorizonEdge::cutoff},
        Setting{2, 0.4, casefile::HorizonEdge::partial_volume},
        Setting{3, 1.0, casefile::HorizonEdge::partial_volume},
        Setting{2, 0.4, casefile::HorizonEdge::cutoff, true},
        Setting{3, 1.0, casefile::HorizonEdge::cutoff, true},
        Setting{3, 1.0, casefile::HorizonEdge::partial_volume, true}}) {
    const bool partial = edge == casefile::HorizonEdge::partial_volume;
    SCOPED_TRACE(::testing::Message()
                 << dim << "D, thickness " << thickness << (partial ? ", partial volume" : "")
                 << (orthotropic ? ", orthotropic" : ""));
    auto c = ball_case(dim);
    c.model.thickness = thickness;
    c.nonlocal.horizon_edge = edge;
    if (orthotropic) make_orthotropic(c);
    const auto m = setup::build_discretization(c);
    const auto& nl = *m.nonlocal;
    const Eigen::MatrixXd C0 = orthotropic ? nl.material.C0 : reference_C0(c);
    if (orthotropic) {
      EXPECT_NE(nl.kernel.angular.kind, peridynamics::AngularKind::isotropic);
      EXPECT_GT(std::abs(C0(0, 0) - C0(1, 1)), 0.1 * C0(0, 0));
    }
    Mat3 eps;
    eps << 1e-3, 4e-4, -2e-4, 4e-4, -6e-4, 3e-4, -2e-4, 3e-4, 5e-4;
    if (dim == 2) {
      eps.row(2).setZero();
      eps.col(2).setZero();
    }
    Eigen::VectorXd ev(fem::voigt_size(dim));  // engineering shear
    if (dim == 2)
      ev << eps(0, 0), eps(1, 1), 2 * eps(0, 1);
    else
      ev << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(1, 2), 2 * eps(0, 2), 2 * eps(0, 1);
    const double local_energy = 0.5 * ev.dot(C0 * ev);
    const double delta = nl.kernel.horizon;
    const Vec3 upper = c.mesh.box.upper;
    int checked = 0;
    double worst = 0.0, worst_vs_D = 0.0, worst_vs_C0 = 0.0;
    for (Index cell = 0; cell < m.mesh.num_cells(); ++cell)
      for (int q = 0; q < static_cast<int>(m.rule.size()); ++q) {
        const Vec3 x = local_point(m, cell, q);
        const double a = nl.alpha(x);
        if (a <= 0.0 || a >= 1.0) continue;
        bool complete = true;
        for (int d = 0; d < dim; ++d) complete = complete && x[d] > delta && upper[d] - x[d] > delta;
        if (!complete) continue;
        ++checked;
        double bond = 0.0, bulk = 0.0;  // ¼ Σ w ᾱ c η², ½ ε:D:ε
        const Vec3 box = partial ? local_box(m, cell, q) : Vec3::Zero();
        for (std::size_t k = 0; k < nl.points.x.size(); ++k) {
          const Vec3 xi = nl.points.x[k] - x;
          const double r = xi.norm();
          double cr = 0.0;
          if (!partial) {
            if (r == 0.0 || r * r >= delta * delta * (1.0 - 1e-10)) continue;  // open horizon, ties left out
            cr = nl.kernel.bond(xi, r);
          } else {
            if (r == 0.0) continue;
            cr = dim == 2
                     ? peridynamics::bond_micromodulus<2>(nl.kernel, xi, r * r, &box, &nl.points.half[k])
                     : peridynamics::bond_micromodulus<3>(nl.kernel, xi, r * r, &box, &nl.points.half[k]);
            if (cr == 0.0) continue;
          }
          const double w = nl.points.weight[k], abar = 0.5 * (a + nl.points.alpha[k]);
          const double eta = xi.dot(eps * xi) / r;
          bond += 0.25 * w * abar * cr * eta * eta;
          bulk += 0.5 * w * cr * eta * eta * 0.5;  // ½ ε:(w c ξξξξ/(2r²)):ε = ¼ w c η²
        }
        const double hybrid = 0.5 * ev.dot(m.stiffness.matrix(cell, q) * ev) + bond;
        const double identity = (1.0 - a) * local_energy + a * bulk;
        worst = std::max(worst, std::abs(hybrid - identity) / local_energy);
        worst_vs_D = std::max(worst_vs_D, std::abs(hybrid - bulk) / local_energy);
        worst_vs_C0 = std::max(worst_vs_C0, std::abs(hybrid - local_energy) / local_energy);
        EXPECT_LT(std::abs(hybrid - identity), 1e-12 * local_energy) << "cell " << cell << " point " << q;
      }
    std::printf(
        "%dD (t = %.1f%s%s) energy identity at %d morphing-zone points: max rel. deviation %.2e; "
        "hybrid vs ½ε:D:ε %.2e, vs ½ε:C0:ε %.2e\n",
        dim, thickness, partial ? ", partial volume" : "", orthotropic ? ", orthotropic" : "", checked, worst,
        worst_vs_D, worst_vs_C0);
    EXPECT_GT(checked, 0);
  }
}

/// ½ uᵀKu for u = G x on every node.
double uniform_strain_energy(const casefile::CaseConfig& c) {
  const auto m = setup::build_discretization(c);
  const Eigen::MatrixXd K = system::assemble_stiffness(m).K.to_dense();
  Mat3 G = Mat3::Zero();
  G(0, 0) = 1e-3;
  if (c.dim() > 1) G.row(1) << 3e-4, -2e-4, 0.0;
  Eigen::VectorXd u(K.rows());
  const int dim = c.dim();
  for (Index a = 0; a < m.dofmap.num_nodes(); ++a) {
    const Vec3 ua = G * m.dofmap.node_coordinate(m.mesh, a);
    for (int d = 0; d < dim; ++d) u[a * dim + d] = ua[d];
  }
  return 0.5 * u.dot(K * u);
}

TEST(AssemblyMorphed, ThicknessScalesLocalAndNonlocalAlike) {
  // The 2D thickness (1D cross-section) multiplies every energy once: the
  // ratio of the energies of a uniform strain in a fully non-local and in a
  // local model does not depend on it. (Regression: the bond weights W = t² w w
  // carried it twice, so the non-local part was t times too stiff.)
  for (int dim : {1, 2}) {
    auto c = testing::box_case(dim, {8, 8, 1}, Vec3(2.0, 2.0, 1.0), 100.0, 0.25);
    testing::add_nonlocal(c, KernelKind::gaussian, 0.6, 0.2, 2);
    std::vector<double> ratios;
    for (double t : {1.0, 0.5, 2.0}) {
      c.model.thickness = t;
      c.alpha.value = 0.0;
      const double local = uniform_strain_energy(c);
      c.alpha.value = 1.0;
      const double nonlocal = uniform_strain_energy(c);
      ratios.push_back(nonlocal / local);
    }
    std::printf("%dD: non-local/local energy ratio %.6f %.6f %.6f for t = 1, 0.5, 2\n", dim, ratios[0],
                ratios[1], ratios[2]);
    EXPECT_NEAR(ratios[1], ratios[0], 1e-12 * ratios[0]) << dim << "D";
    EXPECT_NEAR(ratios[2], ratios[0], 1e-12 * ratios[0]) << dim << "D";
  }
}

}  // namespace
}  // namespace perimorph
