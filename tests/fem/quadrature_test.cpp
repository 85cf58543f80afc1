// Gauss–Legendre rules: weights, exactness degree, symmetry, tensor products.
#include "perimorph/fem/quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace perimorph::fem {
namespace {

/// ∫_{-1}^{1} x^k dx.
double exact_monomial(int k) {
  return k % 2 == 1 ? 0.0 : 2.0 / (k + 1);
}

double integrate_1d(const std::vector<QuadraturePoint>& rule, int k) {
  double s = 0.0;
  for (const auto& q : rule) s += q.weight * std::pow(q.xi.x(), k);
  return s;
}

TEST(FemQuadrature, WeightsSumToReferenceMeasure) {
  for (int n = 1; n <= 64; ++n) {
    double s = 0.0;
    for (const auto& q : gauss_legendre_1d(n)) {
      EXPECT_GT(q.weight, 0.0) << "n = " << n;
      s += q.weight;
    }
    EXPECT_NEAR(s, 2.0, 1e-13) << "n = " << n;
  }
  for (int dim = 1; dim <= 3; ++dim)
    for (int n = 1; n <= 6; ++n) {
      const auto rule = gauss_legendre(dim, n);
      EXPECT_EQ(rule.size(), static_cast<std::size_t>(std::pow(n, dim)));
      double s = 0.0;
      for (const auto& q : rule) s += q.weight;
      EXPECT_NEAR(s, std::pow(2.0, dim), 1e-13) << "dim " << dim << " n " << n;
    }
}

TEST(FemQuadrature, ExactUpToDegree2nMinus1) {
  for (int n = 1; n <= 10; ++n) {
    const auto rule = gauss_legendre_1d(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n));
    for (int k = 0; k <= 2 * n - 1; ++k)
      EXPECT_NEAR(integrate_1d(rule, k), exact_monomial(k), 1e-14) << "n = " << n << ", k = " << k;
    // Degree 2n is not integrated exactly (the error is 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) > 2e-6).
    EXPECT_GT(std::abs(integrate_1d(rule, 2 * n) - exact_monomial(2 * n)), 1e-7) << "n = " << n;
  }
}

TEST(FemQuadrature, KnownSmallRules) {
  const auto r1 = gauss_legendre_1d(1);
  EXPECT_EQ(r1[0].xi.x(), 0.0);
  EXPECT_NEAR(r1[0].weight, 2.0, 1e-15);
  const auto r2 = gauss_legendre_1d(2);
  EXPECT_NEAR(r2[0].xi.x(), -1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r2[1].xi.x(), 1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r2[0].weight, 1.0, 1e-15);
  const auto r3 = gauss_legendre_1d(3);
  EXPECT_NEAR(r3[0].xi.x(), -std::sqrt(0.6), 1e-15);
  EXPECT_EQ(r3[1].xi.x(), 0.0);
  EXPECT_NEAR(r3[0].weight, 5.0 / 9.0, 1e-15);
  EXPECT_NEAR(r3[1].weight, 8.0 / 9.0, 1e-15);
}

TEST(FemQuadrature, PointsSymmetricAscendingInside) {
  for (int n = 1; n <= 64; ++n) {
    const auto rule = gauss_legendre_1d(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < rule.size(); ++i) {
      const auto& q = rule[i];
      const auto& m = rule[rule.size() - 1 - i];
      EXPECT_EQ(q.xi.x(), -m.xi.x()) << "n = " << n << ", i = " << i;
      EXPECT_EQ(q.weight, m.weight) << "n = " << n << ", i = " << i;
      EXPECT_GT(q.xi.x(), -1.0);
      EXPECT_LT(q.xi.x(), 1.0);
      EXPECT_EQ(q.xi.y(), 0.0);
      EXPECT_EQ(q.xi.z(), 0.0);
      if (i > 0) {
        EXPECT_LT(rule[i - 1].xi.x(), q.xi.x()) << "n = " << n << ", i = " << i;
      }
    }
    if (n % 2 == 1) {
      EXPECT_EQ(rule[static_cast<std::size_t>(n / 2)].xi.x(), 0.0);
    }
  }
}

TEST(FemQuadrature, TensorRuleOrderingAndExactness) {
  const int n = 3;
  const auto line = gauss_legendre_1d(n);
  const auto rule = gauss_legendre(3, n);
  ASSERT_EQ(rule.size(), 27u);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto& q = rule[static_cast<std::size_t>(i + n * (j + n * k))];  // x fastest
        EXPECT_EQ(q.xi.x(), line[static_cast<std::size_t>(i)].xi.x());
        EXPECT_EQ(q.xi.y(), line[static_cast<std::size_t>(j)].xi.x());
        EXPECT_EQ(q.xi.z(), line[static_cast<std::size_t>(k)].xi.x());
        EXPECT_NEAR(q.weight,
                    line[static_cast<std::size_t>(i)].weight * line[static_cast<std::size_t>(j)].weight *
                        line[static_cast<std::size_t>(k)].weight,
                    1e-15);
      }
  // 2D rule: z stays 0.
  for (const auto& q : gauss_legendre(2, 4)) EXPECT_EQ(q.xi.z(), 0.0);
  // x^a y^b z^c exact for a, b, c <= 2n - 1.
  for (int a = 0; a <= 2 * n - 1; ++a)
    for (int b = 0; b <= 2 * n - 1; ++b)
      for (int c = 0; c <= 2 * n - 1; ++c) {
        double s = 0.0;
        for (const auto& q : rule)
          s += q.weight * std::pow(q.xi.x(), a) * std::pow(q.xi.y(), b) * std::pow(q.xi.z(), c);
        // Tolerance relative to the reference volume 8 (the products of 27 weights round).
        EXPECT_NEAR(s, exact_monomial(a) * exact_monomial(b) * exact_monomial(c), 8 * 1e-14)
            << a << " " << b << " " << c;
      }
}

}  // namespace
}  // namespace perimorph::fem
