#include "perimorph/bonds/nonlocal_points.hpp"

#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/shape.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <algorithm>
#include <array>

namespace perimorph::bonds {

namespace {

/// Largest rule: 6 points per direction in 3D.
constexpr std::size_t max_points = 216;

template <int D>
void cell_points(const mesh::Mesh& mesh, Index c, std::span<const fem::QuadraturePoint> rule,
                 std::span<const Vec3> line_weights, double scale, const alpha::AlphaField& alpha, Vec3* x,
                 double* weight, double* alpha_out, Vec3* half) {
  constexpr int nn = fem::q1_nodes<D>;
  fem::NodeCoords<D> X;
  const auto nodes = mesh.cell(c);
  for (int a = 0; a < nn; ++a) X.col(a) = mesh.node(nodes[static_cast<std::size_t>(a)]).template head<D>();
  fem::ShapeGradients<D> g;
  for (std::size_t q = 0; q < rule.size(); ++q) {
    Vec3 xq = Vec3::Zero();
    xq.template head<D>() = X * fem::q1_values<D>(rule[q].xi);
    if (x) x[q] = xq;
    if (weight) weight[q] = rule[q].weight * fem::q1_physical_gradients<D>(X, rule[q].xi, g) * scale;
    if (alpha_out) alpha_out[q] = alpha(xq);
    if (half && !line_weights.empty())
      half[q] = fem::q1_point_box_half_widths<D>(X, rule[q].xi, line_weights[q]);
  }
}

/// Everything but the stored points: per_cell, rule, shape values.
NonlocalPoints point_rule(const mesh::Mesh& mesh, int n_per_direction, double scale, bool partial_volume) {
  NonlocalPoints p;
  p.dim = mesh.dim();
  p.rule = fem::gauss_legendre(p.dim, n_per_direction);
  p.per_cell = static_cast<int>(p.rule.size());
  if (partial_volume) p.line_weights = fem::gauss_legendre_line_weights(p.dim, n_per_direction);
  p.scale = scale;
  dispatch_dim(p.dim, [&](auto D) {
    constexpr int nn = fem::q1_nodes<D()>;
    p.shape.resize(p.rule.size() * nn);
    for (std::size_t q = 0; q < p.rule.size(); ++q) {
      const auto N = fem::q1_values<D()>(p.rule[q].xi);
      for (int a = 0; a < nn; ++a) p.shape[q * nn + static_cast<std::size_t>(a)] = N[a];
    }
  });
  const auto ncells = static_cast<std::size_t>(mesh.num_cells());
  p.cell_alpha_max.assign(ncells, 0.0);
  p.cell_alpha_min.assign(ncells, 1.0);
  return p;
}

void resize_stored(NonlocalPoints& p, std::size_t cells) {
  const std::size_t total = cells * static_cast<std::size_t>(p.per_cell);
  p.x.resize(total);
  p.weight.resize(total);
  p.alpha.resize(total);
  if (!p.line_weights.empty()) p.half.resize(total);
}

/// The stored points of cell c (its slot must be set) and its α bounds.
void fill_cell(const mesh::Mesh& mesh, const alpha::AlphaField& alpha, NonlocalPoints& p, Index c) {
  const std::size_t k = p.index(c, 0);
  compute_cell_points(mesh, c, p.rule, p.line_weights, p.scale, alpha, &p.x[k], &p.weight[k], &p.alpha[k],
                      p.half.empty() ? nullptr : &p.half[k]);
  const auto a = std::minmax_element(p.alpha.begin() + static_cast<std::ptrdiff_t>(k),
                                     p.alpha.begin() + static_cast<std::ptrdiff_t>(k) + p.per_cell);
  p.cell_alpha_min[static_cast<std::size_t>(c)] = std::min(1.0, *a.first);
  p.cell_alpha_max[static_cast<std::size_t>(c)] = std::max(0.0, *a.second);
}

}  // namespace

void compute_cell_points(const mesh::Mesh& mesh, Index c, std::span<const fem::QuadraturePoint> rule,
                         std::span<const Vec3> line_weights, double scale, const alpha::AlphaField& alpha,
                         Vec3* x, double* weight, double* alpha_out, Vec3* half) {
  dispatch_dim(mesh.dim(), [&](auto D) {
    cell_points<D()>(mesh, c, rule, line_weights, scale, alpha, x, weight, alpha_out, half);
  });
}

NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume) {
  NonlocalPoints p = point_rule(mesh, n_per_direction, scale, partial_volume);
  resize_stored(p, static_cast<std::size_t>(mesh.num_cells()));
  const Index ncells = mesh.num_cells();
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < ncells; ++c) fill_cell(mesh, alpha, p, c);
  for (const Vec3& b : p.half) p.half_bound = std::max(p.half_bound, b.norm());
  return p;
}

NonlocalPoints make_nonlocal_points(const mesh::Mesh& mesh, int n_per_direction, double scale,
                                    const alpha::AlphaField& alpha, bool partial_volume,
                                    std::span<const char> stored_cells) {
  NonlocalPoints p = point_rule(mesh, n_per_direction, scale, partial_volume);
  const Index ncells = mesh.num_cells();
  p.slot.assign(static_cast<std::size_t>(ncells), -1);
  // Every cell's α bounds and boxes, from points not kept.
  const bool boxes = partial_volume;
  double half_bound = 0.0;
#pragma omp parallel for schedule(static) reduction(max : half_bound)
  for (Index c = 0; c < ncells; ++c) {
    std::array<double, max_points> a;
    std::array<Vec3, max_points> h;
    compute_cell_points(mesh, c, p.rule, p.line_weights, p.scale, alpha, nullptr, nullptr, a.data(),
                        boxes ? h.data() : nullptr);
    double amin = 1.0, amax = 0.0;
    for (int q = 0; q < p.per_cell; ++q) {
      amin = std::min(amin, a[static_cast<std::size_t>(q)]);
      amax = std::max(amax, a[static_cast<std::size_t>(q)]);
      if (boxes) half_bound = std::max(half_bound, h[static_cast<std::size_t>(q)].norm());
    }
    p.cell_alpha_min[static_cast<std::size_t>(c)] = amin;
    p.cell_alpha_max[static_cast<std::size_t>(c)] = amax;
  }
  p.half_bound = half_bound;
  store_points(p, mesh, alpha, stored_cells);
  return p;
}

void store_points(NonlocalPoints& p, const mesh::Mesh& mesh, const alpha::AlphaField& alpha,
                  std::span<const char> cells) {
  const Index ncells = mesh.num_cells();
  assert(cells.size() == static_cast<std::size_t>(ncells));
  p.stored.clear();
  p.slot.assign(static_cast<std::size_t>(ncells), -1);
  for (Index c = 0; c < ncells; ++c)
    if (cells[static_cast<std::size_t>(c)]) {
      p.slot[static_cast<std::size_t>(c)] = static_cast<Index>(p.stored.size());
      p.stored.push_back(c);
    }
  resize_stored(p, p.stored.size());
  const auto n = static_cast<Index>(p.stored.size());
#pragma omp parallel for schedule(static)
  for (Index s = 0; s < n; ++s) fill_cell(mesh, alpha, p, p.stored[static_cast<std::size_t>(s)]);
}

std::size_t NonlocalPoints::first(Index c) const {
  PERIMORPH_ASSERT(c >= 0 && c < num_cells() && holds(c),
                   "a pass read the non-local points of a cell this process does not store");
  return index(c, 0);
}

void point_positions(const mesh::Mesh& mesh, const NonlocalPoints& points, Index c, Vec3* out) {
  if (points.holds(c)) {
    std::copy_n(points.x.begin() + static_cast<std::ptrdiff_t>(points.index(c, 0)), points.per_cell, out);
    return;
  }
  compute_cell_points(mesh, c, points.rule, {}, points.scale, alpha::AlphaField::constant(0.0), out, nullptr,
                      nullptr, nullptr);
}

NonlocalPoints points_of_cells(const NonlocalPoints& p, std::span<const Index> cells) {
  PERIMORPH_ASSERT(std::is_sorted(cells.begin(), cells.end()), "points_of_cells: cells in ascending order");
  NonlocalPoints out;
  out.dim = p.dim;
  out.per_cell = p.per_cell;
  out.shape = p.shape;
  out.half_bound = p.half_bound;
  out.rule = p.rule;
  out.line_weights = p.line_weights;
  out.scale = p.scale;
  out.slot.assign(cells.size(), -1);
  const auto per = static_cast<std::size_t>(p.per_cell);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const Index c = cells[k];
    PERIMORPH_ASSERT(c >= 0 && c < p.num_cells(), "points_of_cells: a cell of the points");
    out.cell_alpha_max.push_back(p.cell_alpha_max[static_cast<std::size_t>(c)]);
    out.cell_alpha_min.push_back(p.cell_alpha_min[static_cast<std::size_t>(c)]);
    if (!p.holds(c)) continue;
    out.slot[k] = static_cast<Index>(out.stored.size());
    out.stored.push_back(static_cast<Index>(k));
    const std::size_t from = p.index(c, 0);
    out.x.insert(out.x.end(), p.x.begin() + static_cast<std::ptrdiff_t>(from),
                 p.x.begin() + static_cast<std::ptrdiff_t>(from + per));
    out.weight.insert(out.weight.end(), p.weight.begin() + static_cast<std::ptrdiff_t>(from),
                      p.weight.begin() + static_cast<std::ptrdiff_t>(from + per));
    out.alpha.insert(out.alpha.end(), p.alpha.begin() + static_cast<std::ptrdiff_t>(from),
                     p.alpha.begin() + static_cast<std::ptrdiff_t>(from + per));
    if (!p.half.empty())
      out.half.insert(out.half.end(), p.half.begin() + static_cast<std::ptrdiff_t>(from),
                      p.half.begin() + static_cast<std::ptrdiff_t>(from + per));
  }
  if (out.stored.size() == cells.size()) {  // every cell's: the plain layout
    out.stored.clear();
    out.slot.clear();
  }
  return out;
}

Vec3 point_position(const mesh::Mesh& mesh, const NonlocalPoints& points, Index c, int q) {
  if (points.holds(c)) return points.x[points.index(c, q)];
  std::array<Vec3, max_points> x;
  point_positions(mesh, points, c, x.data());
  return x[static_cast<std::size_t>(q)];
}

}  // namespace perimorph::bonds
