#include "perimorph/peridynamics/anisotropy.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/fem/quadrature.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

namespace perimorph::peridynamics {

namespace {

constexpr double pi = std::numbers::pi;

/// Voigt index of the symmetric pair (i, j) in 3D and 2D.
constexpr int voigt3[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
constexpr int voigt2[2][2] = {{0, 2}, {2, 1}};

/// The Cauchy pairs in Voigt indices: (normal-type entry, shear-type entry),
/// each a pair of (Voigt row, Voigt column), with the tensor names.
struct CauchyPair {
  int nr, nc, sr, sc;
  const char* normal;
  const char* shear;
};
constexpr CauchyPair cauchy_pairs_3d[6] = {{0, 1, 5, 5, "C1122", "C1212"}, {0, 2, 4, 4, "C1133", "C1313"},
                                           {1, 2, 3, 3, "C2233", "C2323"}, {0, 3, 4, 5, "C1123", "C1312"},
                                           {1, 4, 3, 5, "C2213", "C2312"}, {2, 5, 3, 4, "C3312", "C2313"}};
constexpr CauchyPair cauchy_pairs_2d[1] = {{0, 1, 2, 2, "C1122", "C1212"}};

std::span<const CauchyPair> cauchy_pairs(int dim) {
  if (dim == 3) return cauchy_pairs_3d;
  return cauchy_pairs_2d;
}

}  // namespace

const char* to_string(AngularKind k) {
  switch (k) {
    case AngularKind::isotropic:
      return "isotropic";
    case AngularKind::orthotropic:
      return "orthotropic";
    case AngularKind::transversely_isotropic:
      return "transversely isotropic";
    case AngularKind::planar:
      return "planar anisotropic";
  }
  return "?";
}

double AngularPart::evaluate(const Vec3& e) const {
  if (kind == AngularKind::isotropic) return 1.0;
  if (kind == AngularKind::planar) {
    const double c = e.x(), s = e.y();
    const double c2 = c * c - s * s, s2 = 2.0 * c * s;
    const double c4 = c2 * c2 - s2 * s2, s4 = 2.0 * s2 * c2;
    return a[0] + a[1] * c2 + a[2] * s2 + a[3] * c4 + a[4] * s4;
  }
  // Components in material axes: m = axesᵀ e.
  double m[3];
  for (int k = 0; k < 3; ++k) m[k] = axes(0, k) * e.x() + axes(1, k) * e.y() + axes(2, k) * e.z();
  const double x2 = m[2] * m[2];
  const double P20 = 0.5 * (3.0 * x2 - 1.0);
  const double P40 = (35.0 * x2 * x2 - 30.0 * x2 + 3.0) / 8.0;
  double Y = a[0] + a[1] * P20 + a[3] * P40;
  if (kind == AngularKind::orthotropic) {
    const double p = m[0] * m[0] - m[1] * m[1];  // (1 − x²) cos 2φ
    const double q = m[0] * m[0] * m[1] * m[1];
    Y += a[2] * 3.0 * p + a[4] * 7.5 * (7.0 * x2 - 1.0) * p + a[5] * 105.0 * (p * p - 4.0 * q);
  }
  return Y;
}

AngularPart orthotropic_angular(const Voigt6& C, double R4, const Mat3& axes) {
  PERIMORPH_ASSERT(R4 > 0, "orthotropic_angular needs R4 > 0");
  const double C11 = C(0, 0), C22 = C(1, 1), C33 = C(2, 2), C12 = C(0, 1), C13 = C(0, 2), C23 = C(1, 2);
  AngularPart Y;
  Y.kind = AngularKind::orthotropic;
  Y.axes = axes;
  Y.a[0] = (C11 + C22 + C33 + 2 * C12 + 2 * C13 + 2 * C23) / (2 * pi * R4);
  Y.a[1] = -5 * (C11 + C22 + 2 * C12 - C13 - C23 - 2 * C33) / (4 * pi * R4);
  Y.a[2] = 5 * (C11 - C22 + C13 - C23) / (8 * pi * R4);
  Y.a[3] = 9 * (3 * C11 + 3 * C22 + 8 * C33 + 6 * C12 - 24 * C13 - 24 * C23) / (16 * pi * R4);
  Y.a[4] = -3 * (C11 - C22 - 6 * C13 + 6 * C23) / (16 * pi * R4);
  Y.a[5] = 3 * (C11 + C22 - 6 * C12) / (128 * pi * R4);
  return Y;
}

AngularPart transversely_isotropic_angular(const Voigt6& C, double R4, const Mat3& axes) {
  PERIMORPH_ASSERT(R4 > 0, "transversely_isotropic_angular needs R4 > 0");
  const double C11 = C(0, 0), C13 = C(0, 2), C33 = C(2, 2);
  const double d5 = 5.0 * R4;  // δ⁵ for the constant kernel
  AngularPart Y;
  Y.kind = AngularKind::transversely_isotropic;
  Y.axes = axes;
  Y.a[0] = 5 * (8 * C11 + 12 * C13 + 3 * C33) / (6 * pi * d5);
  Y.a[1] = -25 * (4 * C11 - 3 * C13 - 3 * C33) / (6 * pi * d5);
  Y.a[3] = 45 * (C11 - 6 * C13 + C33) / (2 * pi * d5);
  return Y;
}

AngularPart planar_angular(const Eigen::Matrix3d& C2, double R3) {
  PERIMORPH_ASSERT(R3 > 0, "planar_angular needs R3 > 0");
  const double K = pi * R3 / 2.0;
  const double C11 = C2(0, 0), C22 = C2(1, 1), C12 = C2(0, 1), C16 = C2(0, 2), C26 = C2(1, 2);
  AngularPart Y;
  Y.kind = AngularKind::planar;
  Y.a[0] = (C11 + C22 + 2 * C12) / (2 * K);
  Y.a[1] = (C11 - C22) / K;
  Y.a[2] = 2 * (C16 + C26) / K;
  Y.a[3] = (C11 + C22 - 6 * C12) / K;
  Y.a[4] = 4 * (C16 - C26) / K;
  return Y;
}

Eigen::MatrixXd angular_bulk_tensor(const AngularPart& Y, int dim, double radial_moment) {
  PERIMORPH_ASSERT(dim == 2 || dim == 3, "angular_bulk_tensor: dim must be 2 or 3");
  const int nv = dim == 2 ? 3 : 6;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(nv, nv);
  // Y e⊗e⊗e⊗e is a polynomial of degree 8 in e: 24 equal steps in the
  // azimuth and 10 Gauss points in cos θ integrate it exactly.
  constexpr int n_azimuth = 24;
  auto add = [&](const Vec3& e, double w) {
    const double s = w * Y.evaluate(e) * radial_moment / 2.0;
    // Each Voigt entry once: C(a, b) = s · e_i e_j e_k e_l for its (i, j), (k, l).
    for (int i = 0; i < dim; ++i)
      for (int j = i; j < dim; ++j)
        for (int k = 0; k < dim; ++k)
          for (int l = k; l < dim; ++l) {
            const int a = dim == 3 ? voigt3[i][j] : voigt2[i][j];
            const int b = dim == 3 ? voigt3[k][l] : voigt2[k][l];
            C(a, b) += s * e[i] * e[j] * e[k] * e[l];
          }
  };
  for (int p = 0; p < n_azimuth; ++p) {
    const double phi = 2.0 * pi * (p + 0.5) / n_azimuth;
    if (dim == 2) {
      add(Vec3(std::cos(phi), std::sin(phi), 0.0), 2.0 * pi / n_azimuth);
      continue;
    }
    for (const auto& q : fem::gauss_legendre_1d(10)) {
      const double x = q.xi.x(), sx = std::sqrt(1.0 - x * x);
      add(Vec3(sx * std::cos(phi), sx * std::sin(phi), x), q.weight * 2.0 * pi / n_azimuth);
    }
  }
  return C;
}

std::array<double, 2> angular_range(const AngularPart& Y, int dim) {
  if (Y.kind == AngularKind::isotropic) return {1.0, 1.0};
  double lo = 1e300, hi = -1e300;
  constexpr int n = 180;
  for (int p = 0; p < 2 * n; ++p) {
    const double phi = pi * p / n;
    if (dim == 2) {
      const double y = Y.evaluate(Vec3(std::cos(phi), std::sin(phi), 0.0));
      lo = std::min(lo, y);
      hi = std::max(hi, y);
      continue;
    }
    for (int t = 0; t <= n; ++t) {
      const double theta = pi * t / n;
      const Vec3 e(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const double y = Y.evaluate(e);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
  }
  return {lo, hi};
}

std::vector<CauchyViolation> cauchy_violations(const Eigen::MatrixXd& C, int dim, double rtol) {
  std::vector<CauchyViolation> out;
  if (dim == 1) return out;
  const double tol = rtol * C.cwiseAbs().maxCoeff();
  for (const CauchyPair& p : cauchy_pairs(dim)) {
    const double n = C(p.nr, p.nc), s = C(p.sr, p.sc);
    if (std::abs(n - s) > tol)
      out.push_back({fmt::format("{} = {}", p.shear, p.normal), p.shear, p.normal, s, n});
  }
  return out;
}

Eigen::MatrixXd nearest_central_force(const Eigen::MatrixXd& C, int dim) {
  Eigen::MatrixXd out = C;
  if (dim == 1) return out;
  for (const CauchyPair& p : cauchy_pairs(dim)) {
    // The normal-type entry stands for 2 of the tensor's entries with this
    // index multiset, the shear-type one for 4 (or 4 and 8): the mean over all
    // of them is (n + 2 s) / 3.
    const double v = (C(p.nr, p.nc) + 2.0 * C(p.sr, p.sc)) / 3.0;
    out(p.nr, p.nc) = out(p.nc, p.nr) = v;
    out(p.sr, p.sc) = out(p.sc, p.sr) = v;
  }
  return out;
}

}  // namespace perimorph::peridynamics
