#include "perimorph/bonds/nonlocal_points.hpp"

#include "perimorph/fem/quadrature.hpp"
#include "perimorph/fem/shape.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <algorithm>

namespace perimorph::bonds {

namespace {

template <int D>
void fill(const mesh::Mesh& mesh, const std::vector<fem::QuadraturePoint>& rule,
          const std::vector<Vec3>& line_weights, double scale, const alpha::AlphaField& alpha,
          NonlocalPoints& p) {
  constexpr int nn = fem::q1_nodes<D>;
  p.shape.resize(rule.size() * nn);
  for (std::size_t q = 0; q < rule.size(); ++q) {
    const auto N = fem::q1_values<D>(rule[q].xi);
    for (int a = 0; a < nn; ++a) p.shape[q * nn + static_cast<std::size_t>(a)] = N[a];
  }
  const Index ncells = mesh.num_cells();
  const std::size_t total = static_cast<std::size_t>(ncells) * rule.size();
  p.x.resize(total);
  p.weight.resize(total);
  p.alpha.resize(total);
  p.cell_alpha_max.assign(static_cast<std::size_t>(ncells), 0.0);
  p.cell_alpha_min.assign(static_cast<std::size_t>(ncells), 1.0);
  const bool boxes = !line_weights.empty();
  if (boxes) p.half.resize(total);
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < ncells; ++c) {
    fem::NodeCoords<D> X;
    const auto nodes = mesh.cell(c);
    for (int a = 0; a < nn; ++a) X.col(a) = mesh.node(nodes[static_cast<std::size_t>(a)]).template head<D>();
    fem::ShapeGradients<D> g;
    double amax = 0.0, amin = 1.0;
    for (std::size_t q = 0; q < rule.size(); ++q) {
      const std::size_t k = p.index(c, static_cast<int>(q));
      const double detJ = fem::q1_physical_gradients<D>(X, rule[q].xi, g);
      Vec3 x = Vec3::Zero();
      x.template head<D>() = X * fem::q1_values<D>(rule[q].xi);
      p.x[k] = x;
      p.weight[k] = rule[q].weight * detJ * scale;
      p.alpha[k] = alpha(x);
      if (boxes) p.half[k] = fem::q1_point_box_half_widths<D>(X, rule[q].xi, line_weights[q]);
      amax = std::max(amax, p.alpha[k]);
      amin = std::min(amin, p.alpha[k]);
    }
    p.cell_alpha_max[static_cast<std::size_t>(c)] = amax;
    p.cell_alpha_min[static_cast<std::size_t>(c)] = amin;
  }
  for (const Vec3& b : p.half) p.half_bound = std::max(p.half_bound, b.norm());
}

}  // namespace

NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume) {
  NonlocalPoints p;
  p.dim = mesh.dim();
  const auto rule = fem::gauss_legendre(p.dim, n_per_direction);
  p.per_cell = static_cast<int>(rule.size());
  const std::vector<Vec3> line_weights =
      partial_volume ? fem::gauss_legendre_line_weights(p.dim, n_per_direction) : std::vector<Vec3>{};
  switch (p.dim) {
    case 1:
      fill<1>(mesh, rule, line_weights, scale, alpha, p);
      break;
    case 2:
      fill<2>(mesh, rule, line_weights, scale, alpha, p);
      break;
    default:
      fill<3>(mesh, rule, line_weights, scale, alpha, p);
      break;
  }
  return p;
}

}  // namespace perimorph::bonds
