#include "perimorph/fem/quadrature.hpp"

#include "perimorph/core/error.hpp"

#include <cmath>
#include <numbers>

namespace perimorph::fem {

std::vector<QuadraturePoint> gauss_legendre_1d(int n) {
  PERIMORPH_ASSERT(n >= 1 && n <= 64, "Gauss-Legendre order must be in [1, 64]");
  std::vector<QuadraturePoint> rule(static_cast<std::size_t>(n));
  // Newton iteration on P_n from Chebyshev-like initial guesses; symmetric pairs.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // Recompute the derivative at the converged root for the weight.
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n == 1 ? 1.0 : n * (x * p1 - p0) / (x * x - 1.0);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    const auto lo = static_cast<std::size_t>(i);
    const auto hi = static_cast<std::size_t>(n - 1 - i);
    rule[lo].xi.x() = -x;
    rule[lo].weight = w;
    rule[hi].xi.x() = x;
    rule[hi].weight = w;
  }
  if (n % 2 == 1) rule[static_cast<std::size_t>(n / 2)].xi.x() = 0.0;
  return rule;
}

std::vector<QuadraturePoint> gauss_legendre(int dim, int n) {
  const auto line = gauss_legendre_1d(n);
  std::vector<QuadraturePoint> rule;
  const int nz = dim > 2 ? n : 1;
  const int ny = dim > 1 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n; ++i) {
        QuadraturePoint q;
        q.xi.x() = line[static_cast<std::size_t>(i)].xi.x();
        q.weight = line[static_cast<std::size_t>(i)].weight;
        if (dim > 1) {
          q.xi.y() = line[static_cast<std::size_t>(j)].xi.x();
          q.weight *= line[static_cast<std::size_t>(j)].weight;
        }
        if (dim > 2) {
          q.xi.z() = line[static_cast<std::size_t>(k)].xi.x();
          q.weight *= line[static_cast<std::size_t>(k)].weight;
        }
        rule.push_back(q);
      }
  return rule;
}

std::vector<Vec3> gauss_legendre_line_weights(int dim, int n) {
  const auto line = gauss_legendre_1d(n);
  std::vector<Vec3> out;
  const int nz = dim > 2 ? n : 1;
  const int ny = dim > 1 ? n : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n; ++i) {
        Vec3 w = Vec3::Zero();
        w.x() = line[static_cast<std::size_t>(i)].weight;
        if (dim > 1) w.y() = line[static_cast<std::size_t>(j)].weight;
        if (dim > 2) w.z() = line[static_cast<std::size_t>(k)].weight;
        out.push_back(w);
      }
  return out;
}

}  // namespace perimorph::fem
