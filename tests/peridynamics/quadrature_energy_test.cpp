// Quadrature error of the non-local energy (THEORY §2, §4): under a uniform
// strain the non-local energy of a point with a complete horizon is ½ε:D:ε,
// D = Σ_h w_h c(ξ) ξξξξ/(2|ξ|²) over the non-local quadrature points, whereas
// the calibration gives ½ε:C₀:ε. D − C₀ is the quadrature error of the
// horizon integral on the cell-wise Gauss points, which do not follow the
// circle/sphere |ξ| = δ. This test measures it for the central cell of a
// fully non-local box, for 1..5 points per direction, several δ/h and the
// three kernels of the benchmarks, prints the table (recorded in
// docs/verification/quadrature-energy.md), and checks that it is small
// against the benchmark pass bars (B2: 0.5%, B4: 0.3% strain error).

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/assembly/morphed_stiffness.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <gtest/gtest.h>

#include <iterator>
#include <map>
#include <tuple>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace perimorph {
namespace {

using peridynamics::KernelShape;

struct QuadratureError {
  double cell = 0.0;   ///< max |D̄ − C0| / max |C0|, D̄ the cell average of D (the energy of the cell)
  double point = 0.0;  ///< the same for D at the worst single point of the cell
  /// Component errors of D̄: D̄/C0 − 1 for xxxx, xxyy and the (last) shear entry, and the
  /// error of the uniaxial-stress modulus 1/(D̄⁻¹)_xx against 1/(C0⁻¹)_xx.
  double normal = 0.0, cross = 0.0, shear = 0.0, uniaxial = 0.0;
};

/// D at the points of the central cell of a (2m+1)^dim box of cells of size h
/// = 1, m = ceil(δ/h), so that every point of that cell has a complete
/// horizon. D is 2 × the library's horizon integral with α_g = 1 and α ≡ 0 on
/// the points ((α_g − α_p)/2 = 1/2).
QuadratureError measure(int dim, double delta_over_h, KernelShape shape, double l_over_delta, int order,
                        bool partial_volume = false) {
  const double h = 1.0, delta = delta_over_h * h;
  // Partial-volume bonds reach up to δ + |b_g| + |b_h| < δ + h.
  const auto m = static_cast<Index>(std::ceil(delta_over_h)) + (partial_volume ? 1 : 0);
  const Index n = 2 * m + 1;
  mesh::BoxSpec spec;
  spec.dim = dim;
  spec.upper = Vec3::Constant(static_cast<double>(n) * h);
  spec.cells = {n, dim > 1 ? n : 1, dim > 2 ? n : 1};
  const mesh::Mesh mesh = mesh::make_box(spec);
  const auto points =
      bonds::make_nonlocal_points(mesh, order, 1.0, alpha::AlphaField::constant(0.0), partial_volume);

  peridynamics::Micromodulus kernel;
  kernel.shape = shape;
  kernel.horizon = delta;
  kernel.length = l_over_delta * delta;
  const double E = 1.0;
  kernel.scale = peridynamics::calibrate_isotropic(kernel, dim, PlaneMode::strain, E).scale;
  const Eigen::MatrixXd C0 =
      fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{E, 0.25}), dim, PlaneMode::strain);
  const double c0 = C0.cwiseAbs().maxCoeff();

  std::vector<Index> cells(static_cast<std::size_t>(mesh.num_cells()));
  std::iota(cells.begin(), cells.end(), Index{0});
  Index centre = m;
  if (dim > 1) centre += m * n;
  if (dim > 2) centre += m * n * n;

  QuadratureError err;
  Eigen::MatrixXd average = Eigen::MatrixXd::Zero(C0.rows(), C0.cols());
  double volume = 0.0;
  for (int g = 0; g < points.per_cell; ++g) {
    const std::size_t k = points.index(centre, g);
    const Eigen::MatrixXd D =
        2.0 * assembly::horizon_integral(points.x[k], 1.0, cells, points, kernel, mesh,
                                         partial_volume ? points.half[k] : Vec3::Zero());
    err.point = std::max(err.point, (D - C0).cwiseAbs().maxCoeff() / c0);
    average += points.weight[k] * D;
    volume += points.weight[k];
  }
  average /= volume;
  err.cell = (average - C0).cwiseAbs().maxCoeff() / c0;
  const Eigen::Index s = C0.rows() - 1;
  err.normal = average(0, 0) / C0(0, 0) - 1.0;
  err.cross = average(0, 1) / C0(0, 1) - 1.0;
  err.shear = average(s, s) / C0(s, s) - 1.0;
  err.uniaxial = C0.inverse()(0, 0) / average.inverse()(0, 0) - 1.0;
  return err;
}

struct KernelCase {
  KernelShape shape;
  double l_over_delta;
  const char* name;
};

const KernelCase kernels[] = {{KernelShape::exponential, 0.2, "exponential l=δ/5"},
                              {KernelShape::gaussian, 1.0 / 3.0, "gaussian l=δ/3"},
                              {KernelShape::constant, 1.0, "constant"}};

TEST(PeridynamicsQuadratureEnergy, HorizonIntegralMatchesIndependentSum) {
  // The measurement goes through assembly::horizon_integral; check it once
  // against a sum written here (2D, δ/h = 3, exponential, 3 points per direction).
  const double delta = 3.0;
  mesh::BoxSpec spec;
  spec.dim = 2;
  spec.upper = Vec3(7.0, 7.0, 1.0);
  spec.cells = {7, 7, 1};
  const mesh::Mesh mesh = mesh::make_box(spec);
  const auto points = bonds::make_nonlocal_points(mesh, 3, 1.0, alpha::AlphaField::constant(0.0));
  peridynamics::Micromodulus kernel;
  kernel.shape = KernelShape::exponential;
  kernel.horizon = delta;
  kernel.length = delta / 5.0;
  kernel.scale = 2.5;
  std::vector<Index> cells(49);
  std::iota(cells.begin(), cells.end(), Index{0});
  const Vec3 x = points.x[points.index(24, 1)];
  const Eigen::MatrixXd D = 2.0 * assembly::horizon_integral(x, 1.0, cells, points, kernel, mesh);
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < points.x.size(); ++k) {
    const Vec3 xi = points.x[k] - x;
    const double r = xi.norm();
    if (r == 0.0 || r * r >= delta * delta * (1.0 - 1e-10)) continue;  // open horizon, ties left out
    const double s = points.weight[k] * 2.5 * r * r * std::exp(-r / (delta / 5.0)) / (2.0 * r * r);
    const Eigen::Vector3d v(xi.x() * xi.x(), xi.y() * xi.y(), xi.x() * xi.y());  // xx, yy, xy
    S += s * v * v.transpose();
  }
  EXPECT_LT((D - S).cwiseAbs().maxCoeff(), 1e-13 * S.cwiseAbs().maxCoeff());
}

TEST(PeridynamicsQuadratureEnergy, BulkTensorErrorTable) {
  struct Row {
    int dim;
    double ratio;
  };
  const Row rows[] = {{2, 2.0}, {2, 3.0}, {2, 3.5}, {3, 3.0}};
  constexpr int max_order = 5;
  // The cut-off table first (its rows are kept to compare), then partial volumes.
  std::map<std::tuple<int, double, int>, std::vector<double>> cutoff_cell;
  for (const bool partial : {false, true}) {
    // Markdown, copied into docs/verification/quadrature-energy.md by scripts/make_doc_tables.py.
    std::printf("\n**%s**: max|D̄ − C₀| / max|C₀| of the cell-averaged D̄ (worst single point in brackets)\n\n",
                partial ? "Partial-volume edge" : "Cut-off edge (bonds at exactly |ξ| = δ left out)");
    std::printf("| dim | δ/h | kernel |");
    for (int q = 1; q <= max_order; ++q) std::printf(" %d pt/dir |", q);
    std::printf("\n|---|---|---|");
    for (int q = 1; q <= max_order; ++q) std::printf("---|");
    std::printf("\n");
    for (const Row& row : rows)
      for (std::size_t ki = 0; ki < std::size(kernels); ++ki) {
        const KernelCase& k = kernels[ki];
        std::vector<QuadratureError> e;
        std::printf("| %d | %.1f | %s |", row.dim, row.ratio, k.name);
        for (int q = 1; q <= max_order; ++q) {
          e.push_back(measure(row.dim, row.ratio, k.shape, k.l_over_delta, q, partial));
          std::printf(" %.2e (%.2e) |", e.back().cell, e.back().point);
        }
        std::printf("\n");
        SCOPED_TRACE(::testing::Message() << row.dim << "D δ/h " << row.ratio << " " << k.name
                                          << (partial ? " partial volume" : ""));
        auto& cut = cutoff_cell[{row.dim, row.ratio, static_cast<int>(ki)}];
        if (partial) {
          if (k.shape == KernelShape::gaussian) {
            // Nearly smooth at δ: the edge barely matters, and the partial-volume
            // rule's own O(h²) error (from boxes that are not centred on Gauss
            // points) dominates; within 0.5% from 3 points per direction on.
            for (int q = 3; q <= max_order && row.ratio >= 3.0; ++q)
              EXPECT_LT(e[static_cast<std::size_t>(q - 1)].cell, 5e-3) << q << " pt/dir";
            continue;
          }
          // Kernels that jump at δ: the error falls steadily with the points per
          // direction (the cut-off's does not: it cancels by luck at some orders),
          // its worst case from 2 points on is below the cut-off's, and for the
          // exponential kernel at δ/h ≥ 3 it is within 0.5% from 3 points on.
          double worst_pv = 0.0, worst_cut = 0.0;
          for (int q = 2; q <= max_order; ++q) {
            const auto i = static_cast<std::size_t>(q - 1);
            worst_pv = std::max(worst_pv, e[i].cell);
            worst_cut = std::max(worst_cut, cut[i]);
            if (q > 2) {
              EXPECT_LT(e[i].cell, e[i - 1].cell) << q << " pt/dir";
            }
            if (k.shape == KernelShape::exponential && row.ratio >= 3.0 && q >= 3) {
              EXPECT_LT(e[i].cell, 5e-3) << q << " pt/dir";
            }
          }
          EXPECT_LT(worst_pv, worst_cut);
          continue;
        }
        for (const auto& x : e) cut.push_back(x.cell);
        if (k.shape == KernelShape::gaussian) {
          // Smooth at δ (c(δ)δ² ∝ e^{−9}): from 2 points per direction on, and
          // δ/h ≥ 3, within 0.5% of C0 (the B2 bar) in the cell and at every point.
          // (Its one-point error can be accidentally small, so no ordering is asserted.)
          for (int q = 2; q <= max_order && row.ratio >= 3.0; ++q) {
            EXPECT_LT(e[static_cast<std::size_t>(q - 1)].cell, 5e-3) << q << " pt/dir";
            EXPECT_LT(e[static_cast<std::size_t>(q - 1)].point, 5e-3) << q << " pt/dir";
          }
        } else {
          // Kernels that jump at δ: Gauss points resolve the horizon's edge better
          // than the one-point (meshfree) rule ...
          EXPECT_LT(e[3].cell, e[0].cell);
          EXPECT_LT(e[3].point, e[0].point);
          // ... but only to first order in the point spacing: ~1% at the benchmark
          // settings. Regression bound for the exponential kernel at δ/h ≥ 3.5 (2D)
          // and δ/h = 3 (3D), 3 points per direction or more (observed ≤ 1.8%).
          if (k.shape == KernelShape::exponential && (row.ratio >= 3.5 || row.dim == 3)) {
            for (int q = 3; q <= max_order; ++q)
              EXPECT_LT(e[static_cast<std::size_t>(q - 1)].cell, 3e-2) << q << " pt/dir";
          }
        }
      }
  }
}

TEST(PeridynamicsQuadratureEnergy, BenchmarkSettingsComponentErrors) {
  // B2: 2D, δ/h = 3.5, exponential l = δ/5, 4×4 points. B4: 3D, δ/h = 3, the
  // same kernel, 3×3×3 (and 4×4×4) points. The fully non-local zone behaves
  // as a homogeneous material of stiffness D̄ (the cell average) inside a
  // local one of stiffness C0: an inclusion whose contrast is these numbers.
  struct Setting {
    const char* name;
    int dim;
    double ratio;
    int order;
    KernelShape shape;
    double l_over_delta;
  };
  // The revised BENCHMARKS.md: B2/B3 use the thesis' l = 0.1 µm = δ/26.25 with
  // 6×6 points (4×4 reported); B4 l = δ/5 and δ/10; B5 l = δ/10; B6 the
  // gaussian l = δ/3 with 2×2×2 points at δ/h = 1 … 2.5.
  const Setting settings[] = {
      {"B2 6x6 exponential l=δ/26", 2, 3.5, 6, KernelShape::exponential, 0.1 / 2.625},
      {"B2 4x4 exponential l=δ/26", 2, 3.5, 4, KernelShape::exponential, 0.1 / 2.625},
      {"B2 4x4 exponential l=δ/5", 2, 3.5, 4, KernelShape::exponential, 0.2},
      {"B4 3x3x3 exponential l=δ/5", 3, 3.0, 3, KernelShape::exponential, 0.2},
      {"B4 4x4x4 exponential l=δ/5", 3, 3.0, 4, KernelShape::exponential, 0.2},
      {"B4/B5 3x3x3 exponential l=δ/10", 3, 3.0, 3, KernelShape::exponential, 0.1},
      {"B6 2x2x2 gaussian l=δ/3 h=δ/2", 3, 2.0, 2, KernelShape::gaussian, 1.0 / 3.0},
      {"B6 2x2x2 gaussian l=δ/3 h=0.4δ", 3, 2.5, 2, KernelShape::gaussian, 1.0 / 3.0}};
  std::printf("\n| setting | edge | xxxx | xxyy | shear xyxy | E_uniax |\n|---|---|---|---|---|---|\n");
  for (const Setting& s : settings)
    for (const bool partial : {false, true}) {
      const auto e = measure(s.dim, s.ratio, s.shape, s.l_over_delta, s.order, partial);
      std::printf("| %s | %s | %+.2e | %+.2e | %+.2e | %+.2e |\n", s.name,
                  partial ? "partial volume" : "cut-off", e.normal, e.cross, e.shear, e.uniaxial);
      // Central forces on a lattice of cubic symmetry: D̄ keeps the Cauchy relation
      // D̄_xxyy = D̄_xyxy exactly (up to round-off), so the cross and shear errors coincide.
      EXPECT_NEAR(e.cross, e.shear, 1e-12) << s.name;
    }
}

}  // namespace
}  // namespace perimorph
