#include "perimorph/assembly/discrete_calibration.hpp"

#include "perimorph/fem/material.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"

#include <array>
#include <cmath>

namespace perimorph::assembly {

Eigen::MatrixXd lattice_bulk_tensor(const mesh::StructuredLayout& layout, int dim, int n,
                                    const peridynamics::Micromodulus& kernel, bool partial_volume) {
  const auto rule = fem::gauss_legendre(dim, n);
  const auto line = fem::gauss_legendre_line_weights(dim, n);
  const std::vector<std::array<int, 2>> pairs =
      dim == 1   ? std::vector<std::array<int, 2>>{{0, 0}}
      : dim == 2 ? std::vector<std::array<int, 2>>{{0, 0}, {1, 1}, {0, 1}}
                 : std::vector<std::array<int, 2>>{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  const int nv = fem::voigt_size(dim);
  double jac = 1.0, half_sum = 0.0;
  for (int d = 0; d < dim; ++d) {
    jac *= 0.5 * layout.spacing[d];
    half_sum += 0.5 * layout.spacing[d];
  }
  // Point boxes (fem::q1_point_box_half_widths on the lattice's cells).
  auto half = [&](std::size_t q) {
    Vec3 b = Vec3::Zero();
    for (int d = 0; d < dim; ++d) b[d] = 0.25 * layout.spacing[d] * line[q][d];
    return b;
  };
  const double outer = kernel.horizon + (partial_volume ? half_sum : 0.0);
  std::array<long, 3> reach{0, 0, 0};
  for (int d = 0; d < dim; ++d)
    reach[static_cast<std::size_t>(d)] = static_cast<long>(std::ceil(outer / layout.spacing[d])) + 1;
  auto point = [&](const Vec3& xi, const std::array<long, 3>& cell) {
    Vec3 x = Vec3::Zero();
    for (int d = 0; d < dim; ++d)
      x[d] =
          (static_cast<double>(cell[static_cast<std::size_t>(d)]) + 0.5 * (xi[d] + 1.0)) * layout.spacing[d];
    return x;
  };
  auto bond_c = [&](const Vec3& xi, double r2, std::size_t g, std::size_t h) {
    if (!partial_volume) return peridynamics::bond_micromodulus<3>(kernel, xi, r2, nullptr, nullptr);
    const Vec3 bg = half(g), bh = half(h);
    if (dim == 1) return peridynamics::bond_micromodulus<1>(kernel, xi, r2, &bg, &bh);
    if (dim == 2) return peridynamics::bond_micromodulus<2>(kernel, xi, r2, &bg, &bh);
    return peridynamics::bond_micromodulus<3>(kernel, xi, r2, &bg, &bh);
  };
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(nv, nv);
  double wsum = 0.0;
  for (std::size_t ig = 0; ig < rule.size(); ++ig) {
    const auto& g = rule[ig];
    const Vec3 xg = point(g.xi, {0, 0, 0});
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(nv, nv);
    for (long k = -reach[2]; k <= reach[2]; ++k)
      for (long j = -reach[1]; j <= reach[1]; ++j)
        for (long i = -reach[0]; i <= reach[0]; ++i)
          for (std::size_t ih = 0; ih < rule.size(); ++ih) {
            const Vec3 xi = point(rule[ih].xi, {i, j, k}) - xg;
            const double r2 = xi.squaredNorm();
            if (r2 == 0.0) continue;
            const double cb = bond_c(xi, r2, ig, ih);
            if (cb == 0.0) continue;
            const double s = rule[ih].weight * jac * cb / (2.0 * r2);
            for (int a = 0; a < nv; ++a)
              for (int b = 0; b < nv; ++b) {
                const auto [p, q] = pairs[static_cast<std::size_t>(a)];
                const auto [r, t] = pairs[static_cast<std::size_t>(b)];
                D(a, b) += s * xi[p] * xi[q] * xi[r] * xi[t];
              }
          }
    mean += g.weight * D;
    wsum += g.weight;
  }
  return mean / wsum;
}

double discrete_calibration_factor(const mesh::StructuredLayout& layout, int dim, int n,
                                   const peridynamics::Micromodulus& kernel, const Eigen::MatrixXd& C0,
                                   bool partial_volume) {
  const Eigen::MatrixXd D = lattice_bulk_tensor(layout, dim, n, kernel, partial_volume);
  return (C0.array() * D.array()).sum() / (D.array() * D.array()).sum();
}

}  // namespace perimorph::assembly
