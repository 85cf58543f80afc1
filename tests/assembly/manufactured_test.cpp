// Manufactured solutions with body force (issue 2, item 8): a smooth exact
// displacement u*, its body force b = −div(C : ε(u*)), u = u* on the
// boundary; the observed order of the L2 displacement error must be 2 ± 0.15
// and of the energy-norm error 1 ± 0.15, in 2D (plane strain) and 3D.

#include "perimorph/fem/elasticity_kernel.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/mesh/box.hpp"
#include "support/solve_local.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace perimorph {
namespace {

constexpr double pi = std::numbers::pi;

/// u_i(x) = a_i Π_d f_id(x_d), each factor sin(k π x) or cos(k π x).
struct Manufactured {
  int dim;
  std::array<double, 3> amplitude;
  std::array<std::array<int, 3>, 3> k;        // wave numbers
  std::array<std::array<bool, 3>, 3> is_cos;  // factor type

  // Derivative of order `order` of factor (i, d) at t.
  double factor(int i, int d, int order, double t) const {
    const double w = k[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)] * pi;
    const bool c = is_cos[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)];
    switch (order) {
      case 0:
        return c ? std::cos(w * t) : std::sin(w * t);
      case 1:
        return c ? -w * std::sin(w * t) : w * std::cos(w * t);
      default:
        return c ? -w * w * std::cos(w * t) : -w * w * std::sin(w * t);
    }
  }
  /// ∂^{orders} u_i with orders[d] derivatives along d.
  double derivative(int i, const Vec3& x, std::array<int, 3> orders) const {
    double v = amplitude[static_cast<std::size_t>(i)];
    for (int d = 0; d < dim; ++d) v *= factor(i, d, orders[static_cast<std::size_t>(d)], x[d]);
    return v;
  }
  Vec3 u(const Vec3& x) const {
    Vec3 v = Vec3::Zero();
    for (int i = 0; i < dim; ++i) v[i] = derivative(i, x, {0, 0, 0});
    return v;
  }
  Mat3 grad(const Vec3& x) const {  // G(i, j) = ∂_j u_i
    Mat3 G = Mat3::Zero();
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) {
        std::array<int, 3> o{0, 0, 0};
        o[static_cast<std::size_t>(j)] = 1;
        G(i, j) = derivative(i, x, o);
      }
    return G;
  }
  double second(int i, int j, int l, const Vec3& x) const {  // ∂_j ∂_l u_i
    std::array<int, 3> o{0, 0, 0};
    ++o[static_cast<std::size_t>(j)];
    ++o[static_cast<std::size_t>(l)];
    return derivative(i, x, o);
  }
  /// b = −[(λ+μ) ∇(div u) + μ Δu] for isotropic λ, μ.
  Vec3 body_force(const Vec3& x, double lambda, double mu) const {
    Vec3 b = Vec3::Zero();
    for (int i = 0; i < dim; ++i) {
      double grad_div = 0.0, lap = 0.0;
      for (int j = 0; j < dim; ++j) {
        grad_div += second(j, j, i, x);
        lap += second(i, j, j, x);
      }
      b[i] = -((lambda + mu) * grad_div + mu * lap);
    }
    return b;
  }
};

template <int D>
std::pair<double, double> errors(const assembly::LocalSpace& space, const Eigen::MatrixXd& Cv,
                                 const Manufactured& ex, std::span<const double> u) {
  const auto rule = fem::gauss_legendre(D, 5);
  double l2 = 0.0, energy = 0.0;
  for (Index c = 0; c < space.mesh.num_cells(); ++c) {
    fem::NodeCoords<D> X;
    fem::ElementVector<D> ue;
    const auto nodes = space.dofmap.cell_nodes(c);
    for (int a = 0; a < fem::q1_nodes<D>; ++a) {
      X.col(a) =
          space.dofmap.node_coordinate(space.mesh, nodes[static_cast<std::size_t>(a)]).template head<D>();
      for (int d = 0; d < D; ++d)
        ue[a * D + d] = u[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a)] * D + d)];
    }
    fem::ShapeGradients<D> g;
    for (const auto& q : rule) {
      const double dv = q.weight * fem::q1_physical_gradients<D>(X, q.xi, g);
      const auto N = fem::q1_values<D>(q.xi);
      Vec3 x = Vec3::Zero();
      x.template head<D>() = X * N;
      const Vec3 uex = ex.u(x);
      for (int d = 0; d < D; ++d) {
        double uh = 0.0;
        for (int a = 0; a < fem::q1_nodes<D>; ++a) uh += N[a] * ue[a * D + d];
        l2 += (uh - uex[d]) * (uh - uex[d]) * dv;
      }
      const fem::VoigtVector<D> eh = fem::strain_displacement<D>(g) * ue;
      const Mat3 G = ex.grad(x);
      fem::VoigtVector<D> eex;
      if constexpr (D == 2)
        eex << G(0, 0), G(1, 1), G(0, 1) + G(1, 0);
      else
        eex << G(0, 0), G(1, 1), G(2, 2), G(1, 2) + G(2, 1), G(0, 2) + G(2, 0), G(0, 1) + G(1, 0);
      const fem::VoigtVector<D> de = eh - eex;
      energy += de.dot(Cv * de) * dv;
    }
  }
  return {std::sqrt(l2), std::sqrt(energy)};
}

template <int D>
void convergence_study(const Manufactured& ex, const std::vector<int>& sizes) {
  const fem::IsotropicElasticity iso{1.0, 0.3};
  const double lambda = iso.E * iso.nu / ((1 + iso.nu) * (1 - 2 * iso.nu)), mu = iso.E / (2 * (1 + iso.nu));
  const Eigen::MatrixXd Cv = fem::reduce_stiffness(fem::stiffness_voigt(iso), D, fem::PlaneMode::strain);
  std::vector<double> h, el2, een;
  for (int n : sizes) {
    const mesh::Mesh m = mesh::make_box({D, Vec3::Zero(), Vec3::Ones(), {n, n, n}});
    const dofs::DofMap dm(m, D);
    const auto rule = fem::gauss_legendre(D, 2);
    fem::ConstitutiveField C(D, m.num_cells(), static_cast<int>(rule.size()));
    const int id = C.add_tensor(Cv);
    for (Index c = 0; c < m.num_cells(); ++c) C.set_cell(c, id);
    const auto load_rule = fem::gauss_legendre(D, 3);
    const assembly::LocalSpace space{m, dm, load_rule, 1.0};
    // Body force integrated with 3 points per direction (smooth data), stiffness with 2.
    std::vector<double> F(static_cast<std::size_t>(dm.num_dofs()), 0.0);
    assembly::assemble_body_force(
        space, [&](const Vec3& x) { return ex.body_force(x, lambda, mu); }, F);
    const auto u = testing::solve_local(
        {m, dm, rule, 1.0}, C, m.node_sets.at("boundary"), [&](const Vec3& x) { return ex.u(x); }, F);
    const auto [l2, en] = errors<D>({m, dm, rule, 1.0}, Cv, ex, u);
    h.push_back(1.0 / n);
    el2.push_back(l2);
    een.push_back(en);
  }
  for (std::size_t i = 1; i < h.size(); ++i) {
    const double p_l2 = std::log(el2[i - 1] / el2[i]) / std::log(h[i - 1] / h[i]);
    const double p_en = std::log(een[i - 1] / een[i]) / std::log(h[i - 1] / h[i]);
    std::printf("%dD h=1/%d  L2 %.4e (order %.3f)  energy %.4e (order %.3f)\n", D, sizes[i], el2[i], p_l2,
                een[i], p_en);
    if (i + 1 == h.size()) {
      EXPECT_NEAR(p_l2, 2.0, 0.15);
      EXPECT_NEAR(p_en, 1.0, 0.15);
    }
  }
}

TEST(AssemblyManufactured, ConvergenceOrders2DPlaneStrain) {
  Manufactured ex{
      2, {1e-3, 2e-3, 0}, {{{1, 1, 0}, {2, 1, 0}, {0, 0, 0}}}, {{{false, false}, {true, false}, {}}}};
  convergence_study<2>(ex, {8, 16, 32, 64});
}

TEST(AssemblyManufactured, ConvergenceOrders3D) {
  Manufactured ex{3,
                  {1e-3, 2e-3, -1e-3},
                  {{{1, 1, 1}, {1, 2, 1}, {2, 1, 1}}},
                  {{{false, false, true}, {true, false, false}, {false, true, false}}}};
  convergence_study<3>(ex, {4, 8, 16});
}

}  // namespace
}  // namespace perimorph
