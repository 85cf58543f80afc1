#include "perimorph/peridynamics/micromodulus.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/fem/quadrature.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace perimorph::peridynamics {

const char* to_string(KernelShape s) {
  switch (s) {
    case KernelShape::constant:
      return "constant";
    case KernelShape::conical:
      return "conical";
    case KernelShape::exponential:
      return "exponential";
    case KernelShape::gaussian:
      return "gaussian";
    case KernelShape::pmb:
      return "pmb";
  }
  return "?";
}

double Micromodulus::shape_value(double r) const {
  if (r >= horizon) return 0.0;
  switch (shape) {
    case KernelShape::constant:
      return 1.0;
    case KernelShape::conical:
      return 1.0 - r / horizon;
    case KernelShape::exponential:
      return r * r * std::exp(-r / length);
    case KernelShape::gaussian:
      return r * r * std::exp(-r * r / (length * length));
    case KernelShape::pmb:
      return 1.0 / r;  // bonds join distinct points: r > 0
  }
  return 0.0;
}

double Micromodulus::shape_moment(int k) const {
  // Composite Gauss–Legendre, 32 panels of 20 points: the integrands are
  // smooth on [0, δ] (for pmb, r^(k−1) with k ≥ 2), so this is exact to
  // round-off.
  static const auto rule = fem::gauss_legendre_1d(20);
  constexpr int panels = 32;
  const double h = horizon / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p)
    for (const auto& q : rule) {
      const double r = (p + 0.5 * (q.xi.x() + 1.0)) * h;
      sum += q.weight * 0.5 * h * shape_value(r) * std::pow(r, k);
    }
  return sum;
}

double cauchy_poisson_ratio(int dim, PlaneMode mode) {
  if (dim == 1) return std::numeric_limits<double>::quiet_NaN();
  if (dim == 2 && mode == PlaneMode::stress) return 1.0 / 3.0;
  return 0.25;
}

std::string cauchy_problem(int dim, PlaneMode mode, double nu) {
  if (dim == 1) return {};
  const double expected = cauchy_poisson_ratio(dim, mode);
  if (std::abs(nu - expected) <= 1e-9) return {};
  const char* setting = dim == 3                    ? "in 3D"
                        : mode == PlaneMode::strain ? "in plane strain"
                                                    : "in plane stress";
  return fmt::format(
      "nu = {} cannot be represented by a bond-based (central-force) peridynamic material: its pair forces "
      "impose "
      "the Cauchy relation lambda = mu, hence nu = {} {} (THEORY §2). Use nu = {}, or leave nu out to have "
      "it set",
      nu, dim == 2 && mode == PlaneMode::stress ? "1/3" : "1/4", setting,
      dim == 2 && mode == PlaneMode::stress ? "0.3333333333333333" : "0.25");
}

Calibration calibrate_isotropic(const Micromodulus& kernel, int dim, PlaneMode mode, double E) {
  PERIMORPH_ASSERT(E > 0, "calibration needs E > 0");
  Calibration cal;
  cal.E = E;
  const double pi = std::numbers::pi;
  if (dim == 1) {
    cal.scale = E / kernel.shape_moment(2);  // E = ∫ c r² dr
    cal.nu = std::numeric_limits<double>::quiet_NaN();
    cal.gc_factor = 0.5 * cal.scale * kernel.shape_moment(3);
  } else if (dim == 2) {
    // λ = μ = (π/8) ∫ c r³ dr; E = 5μ/2 (plane strain) or 8μ/3 (plane stress).
    const double mu = mode == PlaneMode::strain ? 2.0 * E / 5.0 : 3.0 * E / 8.0;
    cal.scale = mu / (pi / 8.0 * kernel.shape_moment(3));
    cal.lame = mu;
    cal.nu = cauchy_poisson_ratio(2, mode);
    cal.gc_factor = cal.scale * kernel.shape_moment(4);
  } else {
    // λ = μ = (2π/15) ∫ c r⁴ dr; E = 5μ/2.
    const double mu = 2.0 * E / 5.0;
    cal.scale = mu / (2.0 * pi / 15.0 * kernel.shape_moment(4));
    cal.lame = mu;
    cal.nu = 0.25;
    cal.gc_factor = pi / 2.0 * cal.scale * kernel.shape_moment(5);
  }
  return cal;
}

AngularPart calibrate_angular(const Micromodulus& kernel, int dim, const Eigen::MatrixXd& C, const Mat3& axes,
                              AngularKind kind) {
  PERIMORPH_ASSERT(dim == 2 || dim == 3, "anisotropic micromoduli exist in 2D and 3D");
  if (dim == 2) {
    PERIMORPH_ASSERT(C.rows() == 3 && C.cols() == 3, "calibrate_angular: 2D needs a 3x3 tensor");
    return planar_angular(C, kernel.shape_moment(3));
  }
  PERIMORPH_ASSERT(C.rows() == 6 && C.cols() == 6, "calibrate_angular: 3D needs a 6x6 tensor");
  const Voigt6 C6 = C;
  if (kind == AngularKind::transversely_isotropic)
    return transversely_isotropic_angular(C6, kernel.shape_moment(4), axes);
  return orthotropic_angular(C6, kernel.shape_moment(4), axes);
}

}  // namespace perimorph::peridynamics
