#pragma once
// Gauss–Legendre rules on [-1, 1] and their tensor products on the reference
// cell [-1, 1]^d (THEORY §4). The number of points per direction is an input,
// separately for the local and non-local parts.

#include "perimorph/core/types.hpp"

#include <vector>

namespace perimorph::fem {

struct QuadraturePoint {
  Vec3 xi = Vec3::Zero();  ///< reference coordinates (unused components 0)
  double weight = 0.0;
};

/// n-point Gauss–Legendre rule on [-1, 1], exact for polynomials of degree
/// 2n − 1. Valid for 1 ≤ n ≤ 64; points ascending.
std::vector<QuadraturePoint> gauss_legendre_1d(int n);

/// Tensor-product rule with n points per direction on [-1, 1]^dim, x fastest.
std::vector<QuadraturePoint> gauss_legendre(int dim, int n);

/// For each point of gauss_legendre(dim, n) (same order), the 1D weights of
/// its coordinates per direction (unused components 0); their product is the
/// point's weight.
std::vector<Vec3> gauss_legendre_line_weights(int dim, int n);

}  // namespace perimorph::fem
