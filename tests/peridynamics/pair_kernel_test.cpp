// The pair kernel (peridynamics/pair_kernel.hpp) against a brute-force
// assembly of K = Σ_bonds W ᾱ c bᵀb written directly here (THEORY §4), on tiny
// hand-made cells: 2 or 3 points per cell, Q1 shape values computed here,
// α varying point by point. Also: bonds at or beyond δ are left out, a cut
// between the cells removes exactly the bonds that cross it, and the block is
// symmetric positive semi-definite with rigid motions in its null space.

#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <vector>

namespace perimorph {
namespace {

using peridynamics::CellPoints;
using peridynamics::KernelShape;
using peridynamics::Micromodulus;

/// A cell: the box lower + h·[0,1]^D (Q1 nodes in binary order, node a at
/// corner bit d of a), with points given in reference coordinates ξ ∈ [−1, 1]^D.
struct TestCell {
  int dim = 1;
  std::vector<Vec3> nodes;
  std::vector<Vec3> x;
  std::vector<double> weight, alpha, shape;

  TestCell(int d, const Vec3& lower, double h, const std::vector<Vec3>& xi, const std::vector<double>& w,
           const std::vector<double>& a)
      : dim(d), weight(w), alpha(a) {
    const int nn = 1 << d;
    for (int n = 0; n < nn; ++n) {
      Vec3 X = lower;
      for (int k = 0; k < d; ++k) X[k] += ((n >> k) & 1) ? h : 0.0;
      nodes.push_back(X);
    }
    for (const Vec3& p : xi) {
      Vec3 xp = Vec3::Zero();
      for (int n = 0; n < nn; ++n) {
        double Na = 1.0;
        for (int k = 0; k < d; ++k) Na *= ((n >> k) & 1) ? 0.5 * (1.0 + p[k]) : 0.5 * (1.0 - p[k]);
        shape.push_back(Na);
        xp += Na * nodes[static_cast<std::size_t>(n)];
      }
      x.push_back(xp);
    }
  }
  int nodes_count() const { return 1 << dim; }
  int count() const { return static_cast<int>(x.size()); }
  double N(int q, int a) const { return shape[static_cast<std::size_t>(q * nodes_count() + a)]; }
  CellPoints view() const {
    return CellPoints{x.data(), weight.data(), alpha.data(), count(), shape.data(), nodes_count()};
  }
};

/// Brute-force K = Σ W ᾱ c bᵀb over the bonds (g ∈ E, h ∈ F), unordered pairs
/// g < h when same_cell. `crosses` decides whether a cut removes a bond.
template <int D, class Crosses>
Eigen::MatrixXd brute_force(const TestCell& E, const TestCell& F, bool same_cell, const Micromodulus& c,
                            bool unit_alpha, Crosses crosses, std::size_t& bonds) {
  const int nE = E.nodes_count(), nF = F.nodes_count();
  const int n = same_cell ? nE * D : (nE + nF) * D;
  const int offF = same_cell ? 0 : nE;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  bonds = 0;
  for (int g = 0; g < E.count(); ++g)
    for (int h = same_cell ? g + 1 : 0; h < F.count(); ++h) {
      const Vec3 xi = F.x[static_cast<std::size_t>(h)] - E.x[static_cast<std::size_t>(g)];
      const double r = xi.norm();
      if (r == 0.0 || r * r >= c.horizon * c.horizon * (1.0 - 1e-10))
        continue;  // open horizon, ties left out
      if (crosses(E.x[static_cast<std::size_t>(g)], F.x[static_cast<std::size_t>(h)])) continue;
      const double abar =
          unit_alpha ? 1.0
                     : 0.5 * (E.alpha[static_cast<std::size_t>(g)] + F.alpha[static_cast<std::size_t>(h)]);
      if (abar == 0.0) continue;
      ++bonds;
      const Vec3 e = xi / r;
      Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
      for (int a = 0; a < nE; ++a)
        for (int i = 0; i < D; ++i) b[a * D + i] -= E.N(g, a) * e[i];
      for (int a = 0; a < nF; ++a)
        for (int i = 0; i < D; ++i) b[(offF + a) * D + i] += F.N(h, a) * e[i];
      const double W = E.weight[static_cast<std::size_t>(g)] * F.weight[static_cast<std::size_t>(h)];
      K += W * abar * c(r) * b * b.transpose();
    }
  return K;
}

template <int D>
Eigen::MatrixXd kernel_block(const TestCell& E, const TestCell& F, bool same_cell, const Micromodulus& c,
                             std::span<const Cut> cuts, bool unit_alpha, std::size_t& bonds) {
  const int n = same_cell ? E.nodes_count() * D : (E.nodes_count() + F.nodes_count()) * D;
  std::vector<double> block(static_cast<std::size_t>(n * n), -7.0);  // garbage: the kernel must overwrite
  CellPoints e = E.view(), f = F.view();
  if (unit_alpha) e.alpha = f.alpha = nullptr;
  bonds = peridynamics::pair_stiffness<D>(e, f, same_cell, c, cuts, unit_alpha, block.data());
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      block.data(), n, n);
}

Micromodulus make_kernel(KernelShape s, double delta, double l, double scale) {
  Micromodulus c;
  c.shape = s;
  c.horizon = delta;
  c.length = l;
  c.scale = scale;
  return c;
}

const auto no_cut = [](const Vec3&, const Vec3&) { return false; };

double rel_diff(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const double scale = std::max(B.cwiseAbs().maxCoeff(), 1e-300);
  return (A - B).cwiseAbs().maxCoeff() / scale;
}

// ---- 1D: two-node bars, 3 points per cell
// -------------------------------------------------------------------

TestCell bar(double lower, std::vector<double> xi, std::vector<double> alpha) {
  std::vector<Vec3> p;
  for (double s : xi) p.emplace_back(s, 0.0, 0.0);
  std::vector<double> w(xi.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = 0.3 + 0.1 * static_cast<double>(i);  // arbitrary weights
  return TestCell(1, Vec3(lower, 0, 0), 1.0, p, w, std::move(alpha));
}

TEST(PeridynamicsPairKernel, OneDimensionalAgainstBruteForce) {
  const TestCell E = bar(0.0, {-0.7, 0.1, 0.8}, {0.0, 0.4, 1.0});
  const TestCell F = bar(1.0, {-0.5, 0.3, 0.9}, {0.2, 0.7, 1.0});
  for (KernelShape s :
       {KernelShape::constant, KernelShape::conical, KernelShape::exponential, KernelShape::gaussian})
    for (double delta : {0.5, 1.2, 5.0}) {
      const auto c = make_kernel(s, delta, delta / 3.0, 17.0);
      for (bool same : {false, true}) {
        SCOPED_TRACE(::testing::Message()
                     << to_string(s) << " δ " << delta << (same ? " same cell" : " two cells"));
        std::size_t nb = 0, nk = 0;
        const Eigen::MatrixXd B = brute_force<1>(E, same ? E : F, same, c, false, no_cut, nb);
        const Eigen::MatrixXd K = kernel_block<1>(E, same ? E : F, same, c, {}, false, nk);
        EXPECT_EQ(nk, nb);
        if (nb == 0) {
          EXPECT_EQ(K.cwiseAbs().maxCoeff(), 0.0);
        } else {
          EXPECT_LT(rel_diff(K, B), 1e-14);
        }
      }
    }
}

// ---- 2D: four-node quads, 3 points per cell
// -----------------------------------------------------------------

TestCell quad(Vec3 lower, double h, std::vector<double> alpha) {
  const std::vector<Vec3> xi{Vec3(-0.6, -0.3, 0), Vec3(0.5, -0.8, 0), Vec3(0.2, 0.7, 0)};
  return TestCell(2, lower, h, xi, {0.21, 0.37, 0.42}, std::move(alpha));
}

TEST(PeridynamicsPairKernel, TwoDimensionalAgainstBruteForce) {
  const TestCell E = quad(Vec3(0, 0, 0), 1.0, {0.0, 0.3, 0.9});
  const TestCell Fs[] = {quad(Vec3(1, 0, 0), 1.0, {1.0, 0.5, 0.25}),   // side neighbour
                         quad(Vec3(1, 1, 0), 1.0, {0.1, 0.0, 0.6}),    // corner neighbour
                         quad(Vec3(-1, 2, 0), 1.0, {0.8, 0.8, 0.2})};  // farther away
  for (KernelShape s : {KernelShape::constant, KernelShape::exponential, KernelShape::gaussian})
    for (double delta : {0.9, 1.6, 3.0}) {
      const auto c = make_kernel(s, delta, delta / 5.0, 3.0e4);
      for (int k = 0; k < 4; ++k) {
        const bool same = k == 3;
        const TestCell& F = same ? E : Fs[k];
        SCOPED_TRACE(::testing::Message() << to_string(s) << " δ " << delta << " case " << k);
        std::size_t nb = 0, nk = 0;
        const Eigen::MatrixXd B = brute_force<2>(E, F, same, c, false, no_cut, nb);
        const Eigen::MatrixXd K = kernel_block<2>(E, F, same, c, {}, false, nk);
        EXPECT_EQ(nk, nb);
        if (nb == 0) {
          EXPECT_EQ(K.cwiseAbs().maxCoeff(), 0.0);
        } else {
          EXPECT_LT(rel_diff(K, B), 1e-14);
        }
      }
    }
}

TEST(PeridynamicsPairKernel, ThreeDimensionalAgainstBruteForce) {
  const std::vector<Vec3> xi{Vec3(-0.6, -0.3, 0.4), Vec3(0.5, -0.8, -0.2), Vec3(0.2, 0.7, 0.9)};
  const TestCell E(3, Vec3(0, 0, 0), 0.5, xi, {0.1, 0.2, 0.3}, {0.0, 0.5, 1.0});
  const TestCell F(3, Vec3(0.5, 0, 0.5), 0.5, xi, {0.15, 0.25, 0.05}, {1.0, 0.2, 0.0});
  const auto c = make_kernel(KernelShape::exponential, 0.8, 0.16, 2.0e5);
  for (bool same : {false, true}) {
    std::size_t nb = 0, nk = 0;
    const Eigen::MatrixXd B = brute_force<3>(E, same ? E : F, same, c, false, no_cut, nb);
    const Eigen::MatrixXd K = kernel_block<3>(E, same ? E : F, same, c, {}, false, nk);
    EXPECT_EQ(nk, nb);
    EXPECT_GT(nb, 0u);
    EXPECT_LT(rel_diff(K, B), 1e-14) << (same ? "same cell" : "two cells");
  }
}

TEST(PeridynamicsPairKernel, UnitAlphaIsAlphaOneAndZeroAlphaBondsDrop) {
  TestCell E = quad(Vec3(0, 0, 0), 1.0, {1.0, 1.0, 1.0});
  TestCell F = quad(Vec3(1, 0, 0), 1.0, {1.0, 1.0, 1.0});
  const auto c = make_kernel(KernelShape::gaussian, 1.5, 0.5, 1.0);
  std::size_t n1 = 0, n2 = 0, nb = 0;
  const Eigen::MatrixXd A = kernel_block<2>(E, F, false, c, {}, true, n1);  // α pointers null
  const Eigen::MatrixXd B = kernel_block<2>(E, F, false, c, {}, false, n2);
  const Eigen::MatrixXd R = brute_force<2>(E, F, false, c, true, no_cut, nb);
  EXPECT_EQ(n1, nb);
  EXPECT_EQ(n2, nb);
  EXPECT_EQ((A - B).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(rel_diff(A, R), 1e-14);
  // α = 0 at both ends of some bonds: those bonds are not counted, the block is the brute-force one.
  E.alpha = {0.0, 0.0, 0.5};
  F.alpha = {0.0, 0.0, 0.0};
  const Eigen::MatrixXd C = kernel_block<2>(E, F, false, c, {}, false, n2);
  const Eigen::MatrixXd S = brute_force<2>(E, F, false, c, false, no_cut, nb);
  EXPECT_EQ(n2, nb);
  EXPECT_LT(n2, n1);
  EXPECT_LT(rel_diff(C, S), 1e-14);
}

TEST(PeridynamicsPairKernel, BondsAtOrBeyondTheHorizonAreLeftOut) {
  // Two single-point "cells" whose points are exactly 1 apart: a bond for δ > 1, none for δ ≤ 1;
  // a distance within a relative 1e-10 of δ counts as a tie (exactly δ) and is left out.
  const TestCell E = bar(0.0, {0.0}, {1.0});  // x = 0.5
  const TestCell F = bar(1.0, {0.0}, {1.0});  // x = 1.5
  std::size_t n = 0;
  for (double delta : {0.5, 1.0, 1.0 + 1e-12}) {
    const Eigen::MatrixXd K =
        kernel_block<1>(E, F, false, make_kernel(KernelShape::constant, delta, 1, 1), {}, false, n);
    EXPECT_EQ(n, 0u) << delta;
    EXPECT_EQ(K.cwiseAbs().maxCoeff(), 0.0) << delta;
  }
  const Eigen::MatrixXd K =
      kernel_block<1>(E, F, false, make_kernel(KernelShape::constant, 1.0 + 1e-9, 1, 1), {}, false, n);
  EXPECT_EQ(n, 1u);
  // One bond, e = +1, W = 0.3², c = 1, N = (½, ½) at both points: K = 0.09 · b bᵀ, b = (−½, −½, ½, ½).
  Eigen::VectorXd b(4);
  b << -0.5, -0.5, 0.5, 0.5;
  EXPECT_LT(rel_diff(K, 0.09 * b * b.transpose()), 1e-15);
  // In 2D, with δ between the shortest and the longest point distance, some bonds are in, some out.
  const TestCell Q = quad(Vec3(0, 0, 0), 1.0, {1, 1, 1});
  const TestCell P = quad(Vec3(1, 0, 0), 1.0, {1, 1, 1});
  double rmin = 1e300, rmax = 0;
  for (const Vec3& a : Q.x)
    for (const Vec3& p : P.x) {
      rmin = std::min(rmin, (p - a).norm());
      rmax = std::max(rmax, (p - a).norm());
    }
  std::size_t nb = 0;
  const auto c = make_kernel(KernelShape::constant, 0.5 * (rmin + rmax), 1, 1);
  const Eigen::MatrixXd A = kernel_block<2>(Q, P, false, c, {}, false, n);
  const Eigen::MatrixXd B = brute_force<2>(Q, P, false, c, false, no_cut, nb);
  EXPECT_GT(n, 0u);
  EXPECT_LT(n, 9u);
  EXPECT_EQ(n, nb);
  EXPECT_LT(rel_diff(A, B), 1e-14);
}

TEST(PeridynamicsPairKernel, CutBetweenCellsRemovesCrossingBonds) {
  const TestCell E = quad(Vec3(0, 0, 0), 1.0, {0.2, 0.6, 1.0});
  const TestCell F = quad(Vec3(1, 0, 0), 1.0, {1.0, 0.4, 0.7});
  const auto c = make_kernel(KernelShape::gaussian, 2.0, 2.0 / 3.0, 50.0);
  // A segment on x = 1 from y = y0 to y = y1; a bond a–b crosses it where the
  // straight line meets x = 1 within [y0, y1] (independent of Cut).
  auto cut_on_x1 = [](double y0, double y1) {
    return Cut{2, Vec3(1.0, y0, 0.0), Vec3(0.0, y1 - y0, 0.0), Vec3::Zero()};
  };
  auto crosses_x1 = [](double y0, double y1) {
    return [y0, y1](const Vec3& a, const Vec3& b) {
      if ((a.x() - 1.0) * (b.x() - 1.0) > 0.0) return false;
      const double t = (1.0 - a.x()) / (b.x() - a.x());
      const double y = a.y() + t * (b.y() - a.y());
      return y >= y0 && y <= y1;
    };
  };
  std::size_t n_uncut = 0, n = 0, nb = 0;
  kernel_block<2>(E, F, false, c, {}, false, n_uncut);
  ASSERT_EQ(n_uncut, 9u);
  {  // The whole interface: every E–F bond crosses, the block is zero; bonds inside E survive.
    const std::vector<Cut> cuts{cut_on_x1(-1.0, 2.0)};
    const Eigen::MatrixXd K = kernel_block<2>(E, F, false, c, cuts, false, n);
    EXPECT_EQ(n, 0u);
    EXPECT_EQ(K.cwiseAbs().maxCoeff(), 0.0);
    const Eigen::MatrixXd S = kernel_block<2>(E, E, true, c, cuts, false, n);
    const Eigen::MatrixXd R = brute_force<2>(E, E, true, c, false, no_cut, nb);
    EXPECT_EQ(n, 3u);
    EXPECT_LT(rel_diff(S, R), 1e-14);
  }
  {  // Part of the interface: only the bonds through the segment go.
    const double y0 = 0.0, y1 = 0.5;
    const std::vector<Cut> cuts{cut_on_x1(y0, y1)};
    const Eigen::MatrixXd K = kernel_block<2>(E, F, false, c, cuts, false, n);
    const Eigen::MatrixXd B = brute_force<2>(E, F, false, c, false, crosses_x1(y0, y1), nb);
    EXPECT_EQ(n, nb);
    EXPECT_GT(n, 0u);
    EXPECT_LT(n, n_uncut);
    EXPECT_LT(rel_diff(K, B), 1e-14);
  }
  {  // A cut elsewhere (x = 1, far above) removes nothing.
    const std::vector<Cut> cuts{cut_on_x1(5.0, 6.0)};
    const Eigen::MatrixXd K = kernel_block<2>(E, F, false, c, cuts, false, n);
    const Eigen::MatrixXd B = brute_force<2>(E, F, false, c, false, no_cut, nb);
    EXPECT_EQ(n, n_uncut);
    EXPECT_LT(rel_diff(K, B), 1e-14);
  }
}

/// Rigid translations and (in 2D/3D) infinitesimal rotations u = ω × x, as columns, at the nodes of E then F.
template <int D>
Eigen::MatrixXd rigid_modes(const TestCell& E, const TestCell* F) {
  std::vector<Vec3> X = E.nodes;
  if (F) X.insert(X.end(), F->nodes.begin(), F->nodes.end());
  const int n = static_cast<int>(X.size()) * D;
  const int nrot = D == 2 ? 1 : D == 3 ? 3 : 0;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, D + nrot);
  for (std::size_t a = 0; a < X.size(); ++a) {
    const int row = static_cast<int>(a) * D;
    for (int i = 0; i < D; ++i) R(row + i, i) = 1.0;
    if constexpr (D == 2) {
      R(row + 0, D) = -X[a].y();
      R(row + 1, D) = X[a].x();
    }
    if constexpr (D == 3)
      for (int k = 0; k < 3; ++k) {
        const Vec3 u = Vec3::Unit(k).cross(X[a]);
        for (int i = 0; i < 3; ++i) R(row + i, D + k) = u[i];
      }
  }
  return R;
}

template <int D>
void check_symmetric_psd_with_rigid_null_space(const TestCell& E, const TestCell& F, const Micromodulus& c) {
  for (bool same : {false, true}) {
    SCOPED_TRACE(::testing::Message() << D << "D " << (same ? "same cell" : "two cells"));
    std::size_t n = 0;
    const Eigen::MatrixXd K = kernel_block<D>(E, same ? E : F, same, c, {}, false, n);
    ASSERT_GT(n, 0u);
    const double kmax = K.cwiseAbs().maxCoeff();
    EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-15 * kmax);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (K + K.transpose()));
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-13 * kmax);
    const Eigen::MatrixXd R = rigid_modes<D>(E, same ? nullptr : &F);
    EXPECT_LE((K * R).cwiseAbs().maxCoeff(), 1e-13 * kmax * R.cwiseAbs().maxCoeff());
  }
}

TEST(PeridynamicsPairKernel, BlockIsSymmetricPsdWithRigidNullSpace) {
  check_symmetric_psd_with_rigid_null_space<1>(bar(0.0, {-0.7, 0.1, 0.8}, {0.0, 0.4, 1.0}),
                                               bar(1.0, {-0.5, 0.3, 0.9}, {0.2, 0.7, 1.0}),
                                               make_kernel(KernelShape::constant, 1.3, 1.0, 9.0));
  check_symmetric_psd_with_rigid_null_space<2>(quad(Vec3(0, 0, 0), 1.0, {0.0, 0.3, 0.9}),
                                               quad(Vec3(1, 1, 0), 1.0, {0.1, 0.0, 0.6}),
                                               make_kernel(KernelShape::exponential, 2.0, 0.4, 9.0));
  const std::vector<Vec3> xi{Vec3(-0.6, -0.3, 0.4), Vec3(0.5, -0.8, -0.2), Vec3(0.2, 0.7, 0.9)};
  check_symmetric_psd_with_rigid_null_space<3>(
      TestCell(3, Vec3(0, 0, 0), 0.5, xi, {0.1, 0.2, 0.3}, {0.0, 0.5, 1.0}),
      TestCell(3, Vec3(0.5, 0, 0.5), 0.5, xi, {0.15, 0.25, 0.05}, {1.0, 0.2, 0.0}),
      make_kernel(KernelShape::gaussian, 0.9, 0.3, 9.0));
}

}  // namespace
}  // namespace perimorph
