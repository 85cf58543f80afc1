#include "perimorph/assembly/bond_stretch.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

namespace perimorph::assembly {

namespace {

/// Lets every pair within reach through to the micromodulus.
struct AnyPair {
  bool operator()(int, int, const Vec3&, double) const { return true; }
};

/// Calls visit(g, h, xi, r2, W ᾱ c_bond, broken) for every bond between cells
/// e ≤ f (g in e, h in f; g < h when f = e), the same bonds as pair_stiffness
/// with the same c_bond, failed ones flagged. A visit returning bool stops the
/// pair at the first false. Returns false if a visit stopped it. `wanted(g, h,
/// xi, r2)` is asked first, before the micromodulus (an exp for the gaussian
/// and exponential kernels) is computed: a pair it refuses is not visited, so
/// a pass that needs only a few bonds (those over a stretch) pays the kernel
/// for those alone.
template <int D, class Visit, class Wanted = AnyPair>
bool for_each_bond_of_pair(const NonlocalSpace& s, Index e, Index f, Visit&& visit, Wanted&& wanted = {}) {
  const auto& pts = s.points;
  const int n = pts.per_cell;
  const bool partial = pts.partial_volume();
  const double reach2 = peridynamics::bond_reach_squared(s.kernel.horizon, partial, 2.0 * pts.half_bound);
  if (pts.cell_alpha_max[static_cast<std::size_t>(e)] + pts.cell_alpha_max[static_cast<std::size_t>(f)] <=
      0.0)
    return true;
  const std::size_t first_e = pts.first(e), first_f = pts.first(f);
  const auto broken = s.broken != nullptr ? s.broken->pair(e, f) : std::span<const std::uint32_t>{};
  thread_local std::vector<Cut> cut_buffer;
  const std::span<const Cut> cuts = s.cuts_near(e, f, cut_buffer);
  for (int g = 0; g < n; ++g) {
    const std::size_t kg = first_e + static_cast<std::size_t>(g);
    for (int h = f == e ? g + 1 : 0; h < n; ++h) {
      const std::size_t kh = first_f + static_cast<std::size_t>(h);
      const Vec3 xi = pts.x[kh] - pts.x[kg];
      const double r2 = xi.squaredNorm();
      if (!peridynamics::within_reach(r2, reach2)) continue;
      const double abar = 0.5 * (pts.alpha[kg] + pts.alpha[kh]);
      if (abar == 0.0) continue;
      if (!wanted(g, h, xi, r2)) continue;
      const double cb = peridynamics::uncut_bond_micromodulus<D>(s.kernel, pts.x[kg], pts.x[kh], xi, r2,
                                                                 partial ? &pts.half[kg] : nullptr,
                                                                 partial ? &pts.half[kh] : nullptr, cuts);
      if (cb == 0.0) continue;
      const bool failed = !broken.empty() && std::binary_search(broken.begin(), broken.end(),
                                                                static_cast<std::uint32_t>(g * n + h));
      if constexpr (std::is_same_v<decltype(visit(g, h, xi, r2, 0.0, false)), bool>) {
        if (!visit(g, h, xi, r2, pts.weight[kg] * pts.weight[kh] * abar * cb, failed)) return false;
      } else {
        visit(g, h, xi, r2, pts.weight[kg] * pts.weight[kh] * abar * cb, failed);
      }
    }
  }
  return true;
}

/// Calls visit(f, g, h, xi, r2, W ᾱ c_bond, broken) for every bond of cell e
/// with a cell f ≥ e that wanted(f, g, h, xi, r2) lets through (see
/// for_each_bond_of_pair).
template <int D, class Visit, class Wanted>
void for_each_bond_of(const NonlocalSpace& s, Index e, Visit&& visit, Wanted&& wanted) {
  for (Index f : s.graph.row(e)) {
    if (f < e) continue;
    for_each_bond_of_pair<D>(
        s, e, f,
        [&](int g, int h, const Vec3& xi, double r2, double Wc, bool failed) {
          visit(f, g, h, xi, r2, Wc, failed);
        },
        [&](int g, int h, const Vec3& xi, double r2) { return wanted(f, g, h, xi, r2); });
  }
}

template <int D, class Visit>
void for_each_bond_of(const NonlocalSpace& s, Index e, Visit&& visit) {
  for_each_bond_of<D>(s, e, std::forward<Visit>(visit),
                      [](Index, int, int, const Vec3&, double) { return true; });
}

template <int D>
bool has_intact_bond_dim(const NonlocalSpace& s, Index e, Index f) {
  if (f < e) std::swap(e, f);
  return !for_each_bond_of_pair<D>(s, e, f, [](int, int, const Vec3&, double, double, bool failed) {
    return failed;  // stop at the first intact bond
  });
}

template <int D>
std::vector<std::array<Index, 2>> bonded_pairs_dim(const NonlocalSpace& s, std::span<const char> cells) {
  const Index ncells = s.mesh.num_cells();
  std::vector<std::vector<std::array<Index, 2>>> per_cell(static_cast<std::size_t>(ncells));
#pragma omp parallel for schedule(dynamic, 8)
  for (Index e = 0; e < ncells; ++e) {
    if (!cells.empty() && cells[static_cast<std::size_t>(e)] == 0) continue;
    for (Index f : s.graph.row(e))
      if (f >= e && has_intact_bond_dim<D>(s, e, f)) per_cell[static_cast<std::size_t>(e)].push_back({e, f});
  }
  std::vector<std::array<Index, 2>> all;
  for (auto& v : per_cell) all.insert(all.end(), v.begin(), v.end());
  return all;
}

template <int D>
std::vector<StretchedBond> bonds_over_dim(const NonlocalSpace& s, std::span<const double> u, double threshold,
                                          std::span<const char> cells) {
  const std::vector<Vec3> up = point_displacements(s, u);
  const Index ncells = s.mesh.num_cells();
  std::vector<std::vector<StretchedBond>> per_cell(static_cast<std::size_t>(ncells));
#pragma omp parallel for schedule(dynamic, 8)
  for (Index e = 0; e < ncells; ++e) {
    if (!cells.empty() && cells[static_cast<std::size_t>(e)] == 0) continue;
    auto& out = per_cell[static_cast<std::size_t>(e)];
    // The stretch needs only the geometry: the micromodulus is computed for the bonds over the threshold.
    auto over = [&](Index f, int g, int h, const Vec3& xi, double r2) {
      const Vec3 du = up[s.points.index(f, h)] - up[s.points.index(e, g)];
      return du.dot(xi) / r2 > threshold;
    };
    auto keep = [&](Index f, int g, int h, const Vec3& xi, double r2, double Wc, bool failed) {
      if (failed) return;
      const Vec3 du = up[s.points.index(f, h)] - up[s.points.index(e, g)];
      const double eta_r = du.dot(xi);    // η |ξ|
      const double stretch = eta_r / r2;  // > threshold: `over` let it through
      StretchedBond b;
      b.id = {e, f, g, h};
      b.stretch = stretch;
      b.energy = 0.5 * Wc * eta_r * eta_r / r2;
      b.k = Wc / r2;
      b.xi = xi;
      out.push_back(b);
    };
    for_each_bond_of<D>(s, e, keep, over);
  }
  std::vector<StretchedBond> all;
  for (auto& v : per_cell) all.insert(all.end(), v.begin(), v.end());
  return all;
}

/// Σ W ᾱ c_bond |ξ|² over the bonds of each point of cell c, and the part of
/// failed bonds, added to total[q] and lost[q] (q: the point's number in c).
/// The cell visits its graph row in order (a bond between two cells is
/// visited from both), so each sum has a fixed order wherever it is called.
template <int D>
void add_cell_bond_weights(const NonlocalSpace& s, Index c, double* total, double* lost) {
  auto add = [&](int q, double v, bool failed) {
    total[q] += v;
    if (failed) lost[q] += v;
  };
  for (Index f : s.graph.row(c)) {
    if (f >= c)
      for_each_bond_of_pair<D>(s, c, f, [&](int g, int h, const Vec3&, double r2, double Wc, bool failed) {
        add(g, Wc * r2, failed);
        if (f == c) add(h, Wc * r2, failed);
      });
    else
      for_each_bond_of_pair<D>(s, f, c, [&](int, int h, const Vec3&, double r2, double Wc, bool failed) {
        add(h, Wc * r2, failed);
      });
  }
}

template <int D>
BondWeights point_bond_weights_dim(const NonlocalSpace& s, std::span<const char> cells) {
  const auto& pts = s.points;
  BondWeights w;
  w.total.assign(pts.x.size(), 0.0);
  w.lost.assign(pts.x.size(), 0.0);
  // Threads write disjoint points (each cell its own).
  const Index ncells = s.mesh.num_cells();
#pragma omp parallel for schedule(dynamic, 8)
  for (Index c = 0; c < ncells; ++c) {
    if (!cells.empty() && cells[static_cast<std::size_t>(c)] == 0) continue;
    const std::size_t first = pts.index(c, 0);
    add_cell_bond_weights<D>(s, c, &w.total[first], &w.lost[first]);
  }
  return w;
}

template <int D>
std::vector<double> cell_damage_dim(const NonlocalSpace& s, std::span<const Index> cells) {
  const int n = s.points.per_cell;
  std::vector<double> out(cells.size());
#pragma omp parallel
  {
    std::vector<double> total(static_cast<std::size_t>(n)), lost(total.size());
#pragma omp for schedule(dynamic, 8)
    for (std::size_t k = 0; k < cells.size(); ++k) {
      std::fill(total.begin(), total.end(), 0.0);
      std::fill(lost.begin(), lost.end(), 0.0);
      add_cell_bond_weights<D>(s, cells[k], total.data(), lost.data());
      double d = 0.0;
      for (int q = 0; q < n; ++q) {
        const auto i = static_cast<std::size_t>(q);
        d += total[i] > 0.0 ? lost[i] / total[i] : 0.0;
      }
      out[k] = d / n;
    }
  }
  return out;
}

template <int D>
std::vector<InterfaceBonds> interface_bonds_dim(const NonlocalSpace& s, std::span<const char> cells) {
  PERIMORPH_ASSERT(s.mesh.structure.has_value(), "interface_bonds needs a structured box mesh");
  const auto& layout = *s.mesh.structure;
  const Index ncells = s.mesh.num_cells();
  std::vector<std::vector<InterfaceBonds>> per_cell(static_cast<std::size_t>(ncells));
#pragma omp parallel for schedule(dynamic, 8)
  for (Index e = 0; e < ncells; ++e) {
    if (!cells.empty() && cells[static_cast<std::size_t>(e)] == 0) continue;
    const auto a = layout.cell_ijk(e);
    auto& out = per_cell[static_cast<std::size_t>(e)];
    for_each_bond_of<D>(s, e, [&](Index f, int, int, const Vec3&, double, double, bool failed) {
      if (f == e) return;
      const auto b = layout.cell_ijk(f);
      int axis = -1, differing = 0;
      for (int d = 0; d < 3; ++d)
        if (a[static_cast<std::size_t>(d)] != b[static_cast<std::size_t>(d)]) {
          ++differing;
          axis = std::abs(a[static_cast<std::size_t>(d)] - b[static_cast<std::size_t>(d)]) == 1 ? d : -1;
        }
      if (differing != 1 || axis < 0) return;
      if (out.empty() || out.back().f != f) out.push_back({e, f, axis, 0, 0});
      ++out.back().total;
      out.back().failed += failed ? 1 : 0;
    });
  }
  std::vector<InterfaceBonds> all;
  for (auto& v : per_cell) all.insert(all.end(), v.begin(), v.end());
  return all;
}

template <int D>
BondCount count_bonds_dim(const NonlocalSpace& s) {
  const Index ncells = s.mesh.num_cells();
  std::size_t bonds = 0, pairs = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : bonds, pairs)
  for (Index e = 0; e < ncells; ++e)
    for (Index f : s.graph.row(e)) {
      if (f < e) continue;
      std::size_t here = 0;
      for_each_bond_of_pair<D>(s, e, f, [&](int, int, const Vec3&, double, double, bool) { ++here; });
      bonds += here;
      pairs += here > 0 ? 1 : 0;
    }
  return {bonds, pairs};
}

}  // namespace

bool has_intact_bond(const NonlocalSpace& space, Index e, Index f) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return has_intact_bond_dim<D()>(space, e, f); });
}

BondCount count_bonds(const NonlocalSpace& space) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return count_bonds_dim<D()>(space); });
}

std::vector<std::array<Index, 2>> bonded_pairs(const NonlocalSpace& space, std::span<const char> cells) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return bonded_pairs_dim<D()>(space, cells); });
}

std::vector<InterfaceBonds> interface_bonds(const NonlocalSpace& space, std::span<const char> cells) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return interface_bonds_dim<D()>(space, cells); });
}

std::vector<Vec3> point_displacements(const NonlocalSpace& s, std::span<const double> u) {
  const auto& pts = s.points;
  const int dim = s.mesh.dim();
  std::vector<Vec3> out(pts.x.size(), Vec3::Zero());
  // The cells whose points are stored (on a process of a distributed run, those its part reads).
  const bool every = pts.holds_every_cell();
  const Index ncells = every ? s.mesh.num_cells() : static_cast<Index>(pts.stored.size());
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < ncells; ++k) {
    const Index c = every ? k : pts.stored[static_cast<std::size_t>(k)];
    const auto nodes = s.dofmap.cell_nodes(c);
    const int nn = static_cast<int>(nodes.size());
    for (int q = 0; q < pts.per_cell; ++q) {
      Vec3 v = Vec3::Zero();
      for (int a = 0; a < nn; ++a) {
        const double N = nn == 1 ? 1.0 : pts.shape[static_cast<std::size_t>(q * nn + a)];
        for (int d = 0; d < dim; ++d)
          v[d] += N * u[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a)] * dim + d)];
      }
      out[pts.index(c, q)] = v;
    }
  }
  return out;
}

std::vector<StretchedBond> bonds_over(const NonlocalSpace& space, std::span<const double> u, double threshold,
                                      std::span<const char> cells) {
  PERIMORPH_ASSERT(cells.empty() || cells.size() == static_cast<std::size_t>(space.mesh.num_cells()),
                   "bonds_over: one flag per cell");
  return dispatch_dim(space.mesh.dim(),
                      [&](auto D) { return bonds_over_dim<D()>(space, u, threshold, cells); });
}

BondWeights point_bond_weights(const NonlocalSpace& space, std::span<const char> cells) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return point_bond_weights_dim<D()>(space, cells); });
}

std::vector<double> cell_damage(const NonlocalSpace& space, std::span<const Index> cells) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return cell_damage_dim<D()>(space, cells); });
}

}  // namespace perimorph::assembly
