#include "perimorph/fem/material.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <array>

namespace perimorph::fem {

namespace {
// Voigt index of the symmetric pair (i, j).
constexpr std::array<std::array<int, 3>, 3> voigt_index{{{0, 5, 4}, {5, 1, 3}, {4, 3, 2}}};
}  // namespace

Voigt6 stiffness_voigt(const IsotropicElasticity& m) {
  const double lambda = m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu));
  const double mu = m.E / (2 * (1 + m.nu));
  Voigt6 C = Voigt6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) C(i, j) = lambda;
    C(i, i) = lambda + 2 * mu;
    C(i + 3, i + 3) = mu;
  }
  return C;
}

Voigt6 stiffness_voigt(const OrthotropicElasticity& m) {
  Voigt6 S = Voigt6::Zero();
  S(0, 0) = 1 / m.E1;
  S(1, 1) = 1 / m.E2;
  S(2, 2) = 1 / m.E3;
  S(0, 1) = S(1, 0) = -m.nu12 / m.E1;
  S(0, 2) = S(2, 0) = -m.nu13 / m.E1;
  S(1, 2) = S(2, 1) = -m.nu23 / m.E2;
  S(3, 3) = 1 / m.G23;
  S(4, 4) = 1 / m.G13;
  S(5, 5) = 1 / m.G12;
  return rotate_stiffness(S.inverse(), m.axes);
}

Voigt6 rotate_stiffness(const Voigt6& C, const Mat3& R) {
  if (R.isIdentity(0.0)) return C;
  // Expand to the full tensor, rotate, contract back (done once per material).
  double c[3][3][3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) c[i][j][k][l] = C(voigt_index[i][j], voigt_index[k][l]);
  Voigt6 out = Voigt6::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = k; l < 3; ++l) {
          double v = 0.0;
          for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q)
              for (int r = 0; r < 3; ++r)
                for (int s = 0; s < 3; ++s) v += R(i, p) * R(j, q) * R(k, r) * R(l, s) * c[p][q][r][s];
          out(voigt_index[i][j], voigt_index[k][l]) = v;
        }
  return out;
}

Eigen::MatrixXd reduce_stiffness(const Voigt6& C, int dim, PlaneMode mode) {
  if (dim == 3) return C;
  if (dim == 1) {
    Eigen::MatrixXd E(1, 1);
    E(0, 0) = 1.0 / C.inverse()(0, 0);
    return E;
  }
  const std::array<int, 3> idx{0, 1, 5};
  Eigen::MatrixXd out(3, 3);
  if (mode == PlaneMode::strain) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        out(a, b) = C(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]);
    return out;
  }
  const Voigt6 S = C.inverse();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out(a, b) = S(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]);
  return out.inverse();
}

std::string admissibility_problem(const IsotropicElasticity& m) {
  if (!(m.E > 0)) return fmt::format("Young's modulus E = {} must be positive", m.E);
  if (!(m.nu > -1.0 && m.nu < 0.5))
    return fmt::format("Poisson ratio nu = {} must lie in (-1, 0.5) for a stable isotropic material", m.nu);
  return {};
}

std::string admissibility_problem(const OrthotropicElasticity& m) {
  for (auto [name, v] :
       {std::pair{"E1", m.E1}, {"E2", m.E2}, {"E3", m.E3}, {"G12", m.G12}, {"G13", m.G13}, {"G23", m.G23}})
    if (!(v > 0)) return fmt::format("{} = {} must be positive", name, v);
  Eigen::Matrix3d S;
  S << 1 / m.E1, -m.nu12 / m.E1, -m.nu13 / m.E1, -m.nu12 / m.E1, 1 / m.E2, -m.nu23 / m.E2, -m.nu13 / m.E1,
      -m.nu23 / m.E2, 1 / m.E3;
  const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues().minCoeff();
  if (!(min_eig > 0))
    return fmt::format(
        "the Poisson ratios nu12 = {}, nu13 = {}, nu23 = {} make the compliance indefinite "
        "(smallest eigenvalue {:.3g}); need 1 - nu12*nu21 - nu23*nu32 - nu13*nu31 - 2*nu21*nu32*nu13 > 0",
        m.nu12, m.nu13, m.nu23, min_eig);
  if ((m.axes.transpose() * m.axes - Mat3::Identity()).norm() > 1e-10 || m.axes.determinant() < 0)
    return "the material axes are not a proper rotation (orthonormal, right-handed)";
  return {};
}

}  // namespace perimorph::fem
