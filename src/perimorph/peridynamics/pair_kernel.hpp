#pragma once
// The non-local stiffness of one pair of cells (THEORY §4, eqs. 3.13, 3.18):
//
//   K_EF = Σ_{bonds (g ∈ E, h ∈ F), 0 < |ξ| < δ} W_gh ᾱ_gh c(ξ) b_ghᵀ b_gh,
//   W_gh = w_g w_h, ᾱ_gh = (α_g + α_h)/2, b_gh u = e·(u_F(x_h) − u_E(x_g)).
//
// For E = F every unordered pair of points counts once. A pure kernel: small
// arrays in, a dense block out; no allocation, no I/O. Cost per bond O(D²·n_F)
// by summing over h first:
//   K_EE += Σ_g N_g N_gᵀ ⊗ T_g,  T_g = Σ_h k G       (G = e eᵀ, k = W ᾱ c)
//   K_FF += Σ_h N_h N_hᵀ ⊗ S_h,  S_h = Σ_g k G
//   K_EF −= Σ_g N_g ⊗ U_g,       U_g = Σ_h k G N_hᵀ

#include "perimorph/core/types.hpp"
#include "perimorph/peridynamics/bond_filter.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

namespace perimorph::peridynamics {

/// The quadrature points of one cell, as the kernel sees them. A view: the
/// pointers are non-owning (into NonlocalPoints or a caller's buffer).
struct CellPoints {
  const Vec3* x = nullptr;
  const double* weight = nullptr;
  const double* alpha = nullptr;  ///< may be null when unit_alpha is set
  int count = 0;
  const double* shape = nullptr;  ///< count × nodes, row q = point q
  int nodes = 0;                  ///< 8, 4, 2 (Q1) or 1 (DG degree 0)
  /// Partial-volume option: the points' box half-widths (null: plain cut-off)
  /// and a bound on |half| over the points.
  const Vec3* half = nullptr;
  double half_bound = 0.0;
};

inline constexpr int max_cell_nodes = 8;

/// Writes the block of the pair (E, F) into `block`, row-major, dofs ordered
/// node-major: [E's nodes × D, F's nodes × D] (only E's when same_cell).
/// `unit_alpha`: every α is 1 (ᾱ = 1, α not read). `broken`: sorted codes
/// g · F.count + h of failed bonds, left out (bonds/broken_bonds.hpp; for
/// E = F both orders). Requires count ≤ 216 and nodes ≤ max_cell_nodes.
/// Returns the number of bonds.
template <int D>
std::size_t pair_stiffness(const CellPoints& E, const CellPoints& F, bool same_cell, const Micromodulus& c,
                           std::span<const Cut> cuts, bool unit_alpha, double* block,
                           std::span<const std::uint32_t> broken = {}) {
  const int nE = E.nodes, nF = F.nodes;
  const int n = same_cell ? nE * D : (nE + nF) * D;
  for (int i = 0; i < n * n; ++i) block[i] = 0.0;
  const bool partial = E.half != nullptr;
  const double reach2 = bond_reach_squared(c.horizon, partial, E.half_bound + F.half_bound);
  std::size_t bonds = 0;
  std::array<double, max_cell_nodes * D * D> U{};
  std::array<double, D * D> T{};
  auto at = [&](int row_node, int i, int col_node, int j) -> double& {
    return block[(row_node * D + i) * n + col_node * D + j];
  };
  // S_h depends on every g, so it is kept per point of F (at most 6³ points).
  constexpr int max_points = 216;
  std::array<double, max_points * D * D> S{};
  if (!same_cell)
    for (int i = 0; i < F.count * D * D; ++i) S[static_cast<std::size_t>(i)] = 0.0;

  for (int g = 0; g < E.count; ++g) {
    T.fill(0.0);
    for (int i = 0; i < nF * D * D; ++i) U[static_cast<std::size_t>(i)] = 0.0;
    const Vec3& xg = E.x[g];
    bool any = false;
    for (int h = 0; h < F.count; ++h) {
      if (same_cell && h == g) continue;
      const Vec3 xi = F.x[h] - xg;
      const double r2 = xi.squaredNorm();
      if (!within_reach(r2, reach2)) continue;
      if (!broken.empty() &&
          std::binary_search(broken.begin(), broken.end(), static_cast<std::uint32_t>(g * F.count + h)))
        continue;
      const double abar = unit_alpha ? 1.0 : 0.5 * (E.alpha[g] + F.alpha[h]);
      if (abar == 0.0) continue;
      const double cb = uncut_bond_micromodulus<D>(c, xg, F.x[h], xi, r2, partial ? E.half + g : nullptr,
                                                   partial ? F.half + h : nullptr, cuts);
      if (cb == 0.0) continue;
      const double k = E.weight[g] * F.weight[h] * abar * cb / r2;  // G = ξξᵀ/r²
      ++bonds;
      any = true;
      double kG[D * D];
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) kG[i * D + j] = k * xi[i] * xi[j];
      for (int i = 0; i < D * D; ++i) T[static_cast<std::size_t>(i)] += kG[i];
      if (!same_cell)
        for (int i = 0; i < D * D; ++i) S[static_cast<std::size_t>(h * D * D + i)] += kG[i];
      const double* Nh = F.shape + h * nF;
      for (int b = 0; b < nF; ++b)
        for (int i = 0; i < D * D; ++i) U[static_cast<std::size_t>(b * D * D + i)] += kG[i] * Nh[b];
    }
    if (!any) continue;
    const double* Ng = E.shape + g * nE;
    for (int a = 0; a < nE; ++a)
      for (int a2 = 0; a2 < nE; ++a2) {
        const double NN = Ng[a] * Ng[a2];
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) at(a, i, a2, j) += NN * T[static_cast<std::size_t>(i * D + j)];
      }
    const int offF = same_cell ? 0 : nE;
    for (int a = 0; a < nE; ++a)
      for (int b = 0; b < nF; ++b)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j)
            at(a, i, offF + b, j) -= Ng[a] * U[static_cast<std::size_t>(b * D * D + i * D + j)];
  }
  if (same_cell) {
    // Ordered pairs (g, h), h ≠ g, with the full k: for E = F the unordered sum
    // ½ Σ_{g≠h} k (N_h − N_g)(N_h − N_g)ᵀ ⊗ G equals Σ_g N_g N_gᵀ ⊗ T_g − Σ_g N_g ⊗ U_g,
    // by the symmetry of k and G in (g, h). Each unordered bond was visited twice.
    return bonds / 2;
  }
  for (int h = 0; h < F.count; ++h) {
    const double* Nh = F.shape + h * nF;
    const double* Sh = S.data() + h * D * D;
    for (int b = 0; b < nF; ++b)
      for (int b2 = 0; b2 < nF; ++b2) {
        const double NN = Nh[b] * Nh[b2];
        if (NN == 0.0) continue;
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) at(nE + b, i, nE + b2, j) += NN * Sh[i * D + j];
      }
  }
  // K_FE = K_EFᵀ.
  for (int a = 0; a < nE; ++a)
    for (int b = 0; b < nF; ++b)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) at(nE + b, j, a, i) = at(a, i, nE + b, j);
  return bonds;
}

/// The block of one bond, in the layout of pair_stiffness: with v the values
/// of (−N_g on E's nodes, N_h on F's) (for E = F: N_h − N_g on E's nodes),
/// block(a i, b j) = k ξ_i ξ_j v_a v_b, k = W ᾱ c_bond / |ξ|². pair_stiffness
/// is the sum of these over its bonds; a failed bond is removed from an
/// assembled matrix by subtracting its block (THEORY §5).
template <int D>
void bond_block(const double* Ng, int nE, const double* Nh, int nF, bool same_cell, const Vec3& xi, double k,
                double* block) {
  std::array<double, 2 * max_cell_nodes> v{};
  const int nodes = same_cell ? nE : nE + nF;
  for (int a = 0; a < nE; ++a) v[static_cast<std::size_t>(a)] = -Ng[a];
  for (int b = 0; b < nF; ++b) v[static_cast<std::size_t>(same_cell ? b : nE + b)] += Nh[b];
  const int n = nodes * D;
  for (int a = 0; a < nodes; ++a)
    for (int i = 0; i < D; ++i)
      for (int b = 0; b < nodes; ++b)
        for (int j = 0; j < D; ++j)
          block[(a * D + i) * n + b * D + j] =
              k * xi[i] * xi[j] * v[static_cast<std::size_t>(a)] * v[static_cast<std::size_t>(b)];
}

}  // namespace perimorph::peridynamics
