#include "perimorph/assembly/morphed_stiffness.hpp"

#include "perimorph/bonds/cut_neighborhood.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/fem/shape.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"

#include <array>
#include <limits>

namespace perimorph::assembly {

namespace {

/// Voigt index pairs (i, j) in the model dimension: xx | xx yy xy | xx yy zz yz xz xy.
std::vector<std::array<int, 2>> voigt_pairs(int dim) {
  if (dim == 1) return {{0, 0}};
  if (dim == 2) return {{0, 0}, {1, 1}, {0, 1}};
  return {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
}

Vec3 box_half_widths(const mesh::Mesh& mesh, Index c, const Vec3& xi, const Vec3& line_weights) {
  return dispatch_dim(mesh.dim(), [&](auto dim) {
    constexpr int D = dim();
    fem::NodeCoords<D> X;
    const auto nodes = mesh.cell(c);
    for (int a = 0; a < fem::q1_nodes<D>; ++a)
      X.col(a) = mesh.node(nodes[static_cast<std::size_t>(a)]).template head<D>();
    return fem::q1_point_box_half_widths<D>(X, xi, line_weights);
  });
}

}  // namespace

Vec3 physical_point(const mesh::Mesh& mesh, Index c, const Vec3& xi) {
  Vec3 x = Vec3::Zero();
  const auto nodes = mesh.cell(c);
  for (int a = 0; a < mesh.nodes_per_cell(); ++a) {
    double N = 1.0;
    for (int d = 0; d < mesh.dim(); ++d) N *= 0.5 * (1.0 + mesh::reference_node_coordinate(a, d) * xi[d]);
    x += N * mesh.node(nodes[static_cast<std::size_t>(a)]);
  }
  return x;
}

double alpha_at_local_point(const mesh::Mesh& mesh, const alpha::AlphaField& alpha, Index c, const Vec3& xi) {
  return alpha(physical_point(mesh, c, xi));
}

Eigen::MatrixXd horizon_integral(const Vec3& xg, double alpha_g, std::span<const Index> cells,
                                 const bonds::NonlocalPoints& points,
                                 const peridynamics::Micromodulus& kernel, const mesh::Mesh& mesh,
                                 const Vec3& half_g) {
  const int dim = points.dim;
  const auto pairs = voigt_pairs(dim);
  const int nv = static_cast<int>(pairs.size());
  Eigen::MatrixXd I = Eigen::MatrixXd::Zero(nv, nv);
  const bool partial = points.partial_volume();
  const double reach2 = peridynamics::bond_reach_squared(kernel.horizon, partial, 2.0 * points.half_bound);
  // Only the cuts a bond from x_g can cross (a mesh file's pre-crack has hundreds of pieces).
  const std::vector<Cut> cuts = bonds::cuts_near_point(mesh.cuts, xg, std::sqrt(reach2));
  for (Index f : cells) {
    const std::size_t first = points.first(f);
    for (int h = 0; h < points.per_cell; ++h) {
      const std::size_t k = first + static_cast<std::size_t>(h);
      const double da = alpha_g - points.alpha[k];
      if (da == 0.0) continue;
      const Vec3 xi = points.x[k] - xg;
      const double r2 = xi.squaredNorm();
      if (!peridynamics::within_reach(r2, reach2)) continue;
      const Vec3* hg = partial ? &half_g : nullptr;
      const Vec3* hh = partial ? &points.half[k] : nullptr;
      const double cb = dispatch_dim(dim, [&](auto D) {
        return peridynamics::uncut_bond_micromodulus<D()>(kernel, xg, points.x[k], xi, r2, hg, hh, cuts);
      });
      if (cb == 0.0) continue;
      const double s = points.weight[k] * cb * 0.5 * da / (2.0 * r2);
      for (int a = 0; a < nv; ++a)
        for (int b = a; b < nv; ++b) {
          const auto [i, j] = pairs[static_cast<std::size_t>(a)];
          const auto [l, m] = pairs[static_cast<std::size_t>(b)];
          I(a, b) += s * xi[i] * xi[j] * xi[l] * xi[m];
        }
    }
  }
  I.triangularView<Eigen::StrictlyLower>() = I.transpose().triangularView<Eigen::StrictlyLower>();
  return I;
}

MorphedStiffness morph_stiffness(const mesh::Mesh& mesh, std::span<const fem::QuadraturePoint> rule,
                                 const bonds::NonlocalPoints& points, const bonds::CellGraph& graph,
                                 const peridynamics::Micromodulus& kernel, const alpha::AlphaField& alpha,
                                 const Eigen::MatrixXd& C0, CouplingRule rule_kind,
                                 fem::ConstitutiveField& field, std::span<const char> computed,
                                 const std::function<std::vector<char>(std::vector<char>)>& share_flags) {
  PERIMORPH_ASSERT(computed.empty() || share_flags, "a model part needs the other parts' flags");
  const Index ncells = mesh.num_cells();
  const int nq = static_cast<int>(rule.size());
  const int nv = fem::voigt_size(mesh.dim());
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(nv, nv);
  const int id_local = field.add_tensor(C0);
  const int id_zero = field.add_tensor(zero);
  const int id_absent =
      field.add_tensor(Eigen::MatrixXd::Constant(nv, nv, std::numeric_limits<double>::quiet_NaN()));

  MorphedStiffness out;
  out.purely_nonlocal.assign(static_cast<std::size_t>(ncells), 0);
  std::vector<std::vector<Eigen::MatrixXd>> per_point(static_cast<std::size_t>(ncells));
  std::vector<char> absent(static_cast<std::size_t>(ncells), 0);  // not computed here: NaN
  // Partial volumes: the local points' own boxes (the local rule is a tensor
  // Gauss–Legendre rule), so that where the local and non-local rules coincide
  // the horizon integral uses exactly the bond weights of the stiffness.
  std::vector<Vec3> line_weights;
  if (points.partial_volume()) {
    int n = 1;
    while (fem::gauss_legendre(mesh.dim(), n).size() < rule.size()) ++n;
    line_weights = fem::gauss_legendre_line_weights(mesh.dim(), n);
    PERIMORPH_ASSERT(line_weights.size() == rule.size(),
                     "the local rule is not a tensor Gauss-Legendre rule");
  }

#pragma omp parallel for schedule(dynamic, 16)
  for (Index c = 0; c < ncells; ++c) {
    if (!computed.empty() && computed[static_cast<std::size_t>(c)] == 0) {
      absent[static_cast<std::size_t>(c)] = 1;  // its flag comes from share_flags
      continue;
    }
    // α at the local points: a purely non-local cell has α = 1 at all of them (and C = 0).
    bool all_one = true;
    std::vector<double> alpha_q(static_cast<std::size_t>(nq));
    for (int q = 0; q < nq; ++q) {
      const double a = alpha_at_local_point(mesh, alpha, c, rule[static_cast<std::size_t>(q)].xi);
      alpha_q[static_cast<std::size_t>(q)] = a;
      all_one = all_one && a == 1.0;
    }
    // Range of α over the horizon (neighbour cells' points).
    double amin = 1.0, amax = 0.0;
    for (Index f : graph.row(c)) {
      amin = std::min(amin, points.cell_alpha_min[static_cast<std::size_t>(f)]);
      amax = std::max(amax, points.cell_alpha_max[static_cast<std::size_t>(f)]);
    }
    std::vector<Eigen::MatrixXd> C(static_cast<std::size_t>(nq));
    bool uniform = true, all_zero = true;
    for (int q = 0; q < nq; ++q) {
      const Vec3 x = physical_point(mesh, c, rule[static_cast<std::size_t>(q)].xi);
      const double a = alpha_q[static_cast<std::size_t>(q)];
      Eigen::MatrixXd Cq = (1.0 - a) * C0;
      if (rule_kind == CouplingRule::morphing && !(amin == a && amax == a))
        Cq += horizon_integral(x, a, graph.row(c), points, kernel, mesh,
                               line_weights.empty()
                                   ? Vec3::Zero()
                                   : box_half_widths(mesh, c, rule[static_cast<std::size_t>(q)].xi,
                                                     line_weights[static_cast<std::size_t>(q)]));
      all_zero = all_zero && (Cq.array() == 0.0).all();
      uniform = uniform && a == 0.0 && (Cq.array() == C0.array()).all();
      C[static_cast<std::size_t>(q)] = std::move(Cq);
    }
    if (all_zero && all_one)
      out.purely_nonlocal[static_cast<std::size_t>(c)] = 1;
    else if (!uniform)
      per_point[static_cast<std::size_t>(c)] = std::move(C);
  }
  if (!computed.empty()) out.purely_nonlocal = share_flags(std::move(out.purely_nonlocal));
  for (Index c = 0; c < ncells; ++c) {
    auto& C = per_point[static_cast<std::size_t>(c)];
    if (out.purely_nonlocal[static_cast<std::size_t>(c)])
      field.set_cell(c, id_zero);
    else if (absent[static_cast<std::size_t>(c)])
      field.set_cell(c, id_absent);
    else if (C.empty())
      field.set_cell(c, id_local);
    else {
      field.set_cell_points(c, C);
      ++out.morphing_cells;
    }
  }
  return out;
}

}  // namespace perimorph::assembly
