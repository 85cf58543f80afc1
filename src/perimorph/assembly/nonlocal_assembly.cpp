#include "perimorph/assembly/nonlocal_assembly.hpp"

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/fem/shape.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <vector>

namespace perimorph::assembly {

namespace {

constexpr Index chunk_cells = 16;

struct PairTask {
  Index e, f;
  long cached = -1;  ///< index into the translation cache, or -1
};

/// Key of a translation-invariant pair: the offset of F from E in cells and
/// the node counts of both (CG/DG vs DG degree 0).
using OffsetKey = std::array<long, 5>;

constexpr int max_points = 216;

/// NonlocalOptions::min_over_processes: each key's representative (a pair of
/// box cells, StructuredLayout::box_cell) becomes the first pair (e, f),
/// e ≤ f, in the whole graph's order, the smallest e·N + f over the processes
/// (N the box's cells). A slot per key (offset and node counts) in a box of
/// offsets every process agrees on, so the reduction's size does not grow with
/// the processes.
void first_pairs_over_processes(const std::map<OffsetKey, long>& cache_index,
                                std::vector<std::pair<Index, Index>>& representatives,
                                const mesh::StructuredLayout& layout, int dim,
                                const NonlocalOptions& options) {
  long reach = 0;
  for (const auto& entry : cache_index)
    for (int a = 0; a < 3; ++a) reach = std::max(reach, std::abs(entry.first[static_cast<std::size_t>(a)]));
  reach = -options.min_over_processes({-static_cast<long long>(reach)}).front();
  const long width = 2 * reach + 1, nodes = peridynamics::max_cell_nodes;
  auto slot = [&](const OffsetKey& k) {
    long s = 0;
    for (int a = 0; a < dim; ++a) s = s * width + k[static_cast<std::size_t>(a)] + reach;
    for (int a = dim; a < 3; ++a)
      PERIMORPH_ASSERT(k[static_cast<std::size_t>(a)] == 0, "an offset off the grid");
    PERIMORPH_ASSERT(k[3] >= 1 && k[3] <= nodes && k[4] >= 1 && k[4] <= nodes, "a cell with too many nodes");
    return static_cast<std::size_t>((s * nodes + k[3] - 1) * nodes + k[4] - 1);
  };
  long slots = nodes * nodes;
  for (int a = 0; a < dim; ++a) slots *= width;
  const auto none = std::numeric_limits<long long>::max();
  const auto n = static_cast<long long>(layout.num_box_cells());
  std::vector<long long> first(static_cast<std::size_t>(slots), none);
  for (const auto& [key, r] : cache_index) {
    const auto& [e, f] = representatives[static_cast<std::size_t>(r)];
    first[slot(key)] = static_cast<long long>(e) * n + f;
  }
  first = options.min_over_processes(std::move(first));
  for (const auto& [key, r] : cache_index) {
    const long long pair = first[slot(key)];
    representatives[static_cast<std::size_t>(r)] = {static_cast<Index>(pair / n),
                                                    static_cast<Index>(pair % n)};
  }
}

/// One cell's quadrature points, recomputed (the plain version, or a cell
/// whose points this process does not store); lives on the stack of the
/// thread that computes the pair.
struct PointBuffer {
  std::array<Vec3, max_points> x, half;
  std::array<double, max_points> weight, alpha;
};

/// The points of cell c, with the formulas of make_nonlocal_points (bit-identical to the stored ones).
void recompute_points(const mesh::Mesh& mesh, Index c, const std::vector<fem::QuadraturePoint>& rule,
                      double scale, const alpha::AlphaField& alpha, PointBuffer& out) {
  bonds::compute_cell_points(mesh, c, rule, {}, scale, alpha, out.x.data(), out.weight.data(),
                             out.alpha.data(), nullptr);
}

/// Points per direction of a tensor rule with `per_cell` points in D dimensions.
int points_per_direction(int per_cell, int dim) {
  const int n = static_cast<int>(std::lround(std::pow(static_cast<double>(per_cell), 1.0 / dim)));
  int total = 1;
  for (int d = 0; d < dim; ++d) total *= n;
  PERIMORPH_ASSERT(total == per_cell, "non-local points are not a tensor Gauss-Legendre rule");
  return n;
}

template <int D>
NonlocalStats assemble_dim(const NonlocalSpace& s, MatrixInserter& K, const NonlocalOptions& options) {
  const auto& pts = s.points;
  PERIMORPH_ASSERT(pts.per_cell <= max_points, "at most 6 non-local quadrature points per direction");
  const Index ncells = s.mesh.num_cells();
  const std::optional<bonds::CutNeighborhood> own_cuts =
      s.cuts != nullptr
          ? std::nullopt
          : std::optional<bonds::CutNeighborhood>(std::in_place, s.mesh, pts.bond_reach(s.kernel.horizon));
  const bonds::CutNeighborhood& near_cut = s.cuts != nullptr ? *s.cuts : *own_cuts;
  const std::vector<double> ones(static_cast<std::size_t>(pts.per_cell), 1.0);
  auto cell_shape = [&](Index c) {
    peridynamics::CellPoints p;
    p.count = pts.per_cell;
    p.nodes = static_cast<int>(s.dofmap.cell_nodes(c).size());
    p.shape = p.nodes == 1 ? ones.data() : pts.shape.data();
    p.half_bound = pts.half_bound;
    return p;
  };
  auto cell_points = [&](Index c) {
    peridynamics::CellPoints p = cell_shape(c);
    const std::size_t k = pts.first(c);
    p.half = pts.partial_volume() ? pts.half.data() + k : nullptr;
    p.x = pts.x.data() + k;
    p.weight = pts.weight.data() + k;
    p.alpha = pts.alpha.data() + k;
    return p;
  };
  auto unit_pair = [&](Index e, Index f) {
    return pts.cell_alpha_min[static_cast<std::size_t>(e)] >= 1.0 &&
           pts.cell_alpha_min[static_cast<std::size_t>(f)] >= 1.0;
  };
  auto near = [&](Index e, Index f) { return !near_cut.near(e).empty() && !near_cut.near(f).empty(); };
  // The plain version: points recomputed per pair from the mesh, the rule and α.
  const bool plain = !options.precomputed_points;
  std::vector<fem::QuadraturePoint> rule;
  if (plain) {
    PERIMORPH_ASSERT(s.alpha != nullptr, "precomputed_points = false needs NonlocalSpace::alpha");
    rule = fem::gauss_legendre(D, points_per_direction(pts.per_cell, D));
    // The space must describe the stored points (same α field, same scale):
    // check the first stored cell against them where they exist.
    if (ncells > 0 && !pts.weight.empty()) {
      const Index first = pts.holds_every_cell() ? 0 : pts.stored.front();
      PointBuffer b;
      recompute_points(s.mesh, first, rule, s.scale, *s.alpha, b);
      for (int q = 0; q < pts.per_cell; ++q) {
        const std::size_t k = pts.index(first, q);
        PERIMORPH_ASSERT(
            b.x[static_cast<std::size_t>(q)] == pts.x[k] &&
                b.weight[static_cast<std::size_t>(q)] == pts.weight[k] &&
                b.alpha[static_cast<std::size_t>(q)] == pts.alpha[k],
            "precomputed_points = false: NonlocalSpace::alpha or scale differ from those of the points");
      }
    }
  }
  auto broken_in = [&](Index e, Index f) {
    return s.broken != nullptr ? s.broken->pair(e, f) : std::span<const std::uint32_t>{};
  };
  auto compute = [&](Index e, Index f, double* block) {
    const bool unit = options.unit_alpha_shortcut && unit_pair(e, f);
    // The pieces a bond between e and f can cross (bonds::CutNeighborhood).
    thread_local std::vector<Cut> cut_buffer;
    const auto cuts = near(e, f) ? near_cut.near_pair(e, f, cut_buffer) : std::span<const Cut>{};
    if (!plain)
      return peridynamics::pair_stiffness<D>(cell_points(e), cell_points(f), e == f, s.kernel, cuts, unit,
                                             block, broken_in(e, f));
    // The plain version: both cells' points made again from the mesh.
    auto points_of = [&](Index c, PointBuffer& b) {
      recompute_points(s.mesh, c, rule, s.scale, *s.alpha, b);
      peridynamics::CellPoints p = cell_shape(c);
      p.half = pts.partial_volume() ? pts.half.data() + pts.first(c) : nullptr;
      p.x = b.x.data();
      p.weight = b.weight.data();
      p.alpha = b.alpha.data();
      return p;
    };
    PointBuffer be, bf;
    const peridynamics::CellPoints pe = points_of(e, be);
    const peridynamics::CellPoints pf = e == f ? pe : points_of(f, bf);
    return peridynamics::pair_stiffness<D>(pe, pf, e == f, s.kernel, cuts, unit, block, broken_in(e, f));
  };
  const std::size_t max_block = static_cast<std::size_t>(2 * peridynamics::max_cell_nodes * D) *
                                static_cast<std::size_t>(2 * peridynamics::max_cell_nodes * D);

  auto included = [&](Index e, Index f) { return !options.include_pair || options.include_pair(e, f); };
  // Translation cache: one representative pair per distinct key, a pair of
  // box cells (StructuredLayout::box_cell), with a pair of this mesh's cells
  // of the same key (their node counts).
  const bool use_cache = options.translation_cache && s.mesh.structure.has_value();
  std::map<OffsetKey, long> cache_index;
  std::vector<std::pair<Index, Index>> representatives, local_pairs;
  auto key_of = [&](Index e, Index f) {
    const auto a = s.mesh.structure->cell_ijk(e), b = s.mesh.structure->cell_ijk(f);
    return OffsetKey{b[0] - a[0], b[1] - a[1], b[2] - a[2], static_cast<long>(s.dofmap.cell_nodes(e).size()),
                     static_cast<long>(s.dofmap.cell_nodes(f).size())};
  };
  auto cacheable = [&](Index e, Index f) {
    return use_cache && unit_pair(e, f) && !near(e, f) && broken_in(e, f).empty();
  };
  // The pairs (e, f), e ≤ f, of the rows e in [first, last), in order: from
  // those rows, or (options.rows) from the list found in the flagged rows.
  std::vector<std::pair<Index, Index>> listed;
  if (!options.rows.empty()) {
    PERIMORPH_ASSERT(static_cast<Index>(options.rows.size()) == ncells, "one row flag per cell");
    for (Index c = 0; c < ncells; ++c)
      if (options.rows[static_cast<std::size_t>(c)] != 0)
        for (Index f : s.graph.row(c)) listed.push_back(std::minmax(c, f));
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
  }
  auto for_each_pair = [&](Index first, Index last, auto&& visit) {
    if (options.rows.empty()) {
      for (Index e = first; e < last; ++e)
        for (Index f : s.graph.row(e))
          if (f >= e) visit(e, f);
      return;
    }
    auto it = std::lower_bound(listed.begin(), listed.end(), std::pair<Index, Index>{first, Index{0}});
    for (; it != listed.end() && it->first < last; ++it) visit(it->first, it->second);
  };
  if (use_cache) {
    for_each_pair(0, ncells, [&](Index e, Index f) {
      if (!cacheable(e, f) || !included(e, f)) return;
      auto [it, added] = cache_index.emplace(key_of(e, f), static_cast<long>(representatives.size()));
      if (!added) return;
      local_pairs.emplace_back(e, f);
      representatives.emplace_back(s.mesh.structure->box_cell(e), s.mesh.structure->box_cell(f));
    });
    if (options.min_over_processes)
      first_pairs_over_processes(cache_index, representatives, *s.mesh.structure, D, options);
  }
  // A representative's block from its two box cells alone
  // (mesh::box_cell_mesh: the box's corners, bit for bit), their points made
  // as make_nonlocal_points makes them, α = 1 at every one (a cacheable pair's
  // α bounds are 1): the same bits whichever process computes it, whether or
  // not its piece holds the cells.
  auto compute_representative = [&](std::size_t r, double* block) {
    const auto [be, bf] = representatives[r];
    const auto [e, f] = local_pairs[r];  // the same key: the same node counts
    static const alpha::AlphaField unit_alpha = alpha::AlphaField::constant(1.0);
    auto points_of = [&](Index box_cell, Index c, PointBuffer& b) {
      const mesh::Mesh one = mesh::box_cell_mesh(*s.mesh.structure, D, box_cell);
      bonds::compute_cell_points(one, 0, pts.rule, pts.line_weights, pts.scale, unit_alpha, b.x.data(),
                                 b.weight.data(), b.alpha.data(), b.half.data());
      peridynamics::CellPoints p = cell_shape(c);
      p.half = pts.partial_volume() ? b.half.data() : nullptr;
      p.x = b.x.data();
      p.weight = b.weight.data();
      p.alpha = b.alpha.data();
      return p;
    };
    PointBuffer bufe, buff;
    const peridynamics::CellPoints pe = points_of(be, e, bufe);
    const peridynamics::CellPoints pf = be == bf ? pe : points_of(bf, f, buff);
    return peridynamics::pair_stiffness<D>(pe, pf, be == bf, s.kernel, {}, options.unit_alpha_shortcut, block,
                                           {});
  };
  std::vector<double> cache_blocks(representatives.size() * max_block);
  std::vector<std::size_t> cache_bonds(representatives.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t r = 0; r < representatives.size(); ++r)
    cache_bonds[r] = compute_representative(r, cache_blocks.data() + r * max_block);

  NonlocalStats stats;
  stats.distinct_blocks = representatives.size();
  std::vector<PairTask> tasks;
  std::vector<double> blocks;
  std::vector<std::size_t> bonds;
  std::vector<Index> dofs;
  for (Index first = 0; first < ncells; first += chunk_cells) {
    const Index last = std::min(ncells, first + chunk_cells);
    tasks.clear();
    for_each_pair(first, last, [&](Index e, Index f) {
      if (pts.cell_alpha_max[static_cast<std::size_t>(e)] + pts.cell_alpha_max[static_cast<std::size_t>(f)] <=
              0.0 ||
          !included(e, f))
        return;
      tasks.push_back({e, f, cacheable(e, f) ? cache_index.at(key_of(e, f)) : -1});
    });
    blocks.resize(tasks.size() * max_block);
    bonds.assign(tasks.size(), 0);
    // No parallel region for a chunk served entirely by the cache: its barrier
    // costs more than the loop when a core is busy elsewhere.
    const auto to_compute =
        std::count_if(tasks.begin(), tasks.end(), [](const PairTask& t) { return t.cached < 0; });
#pragma omp parallel for schedule(dynamic, 4) if (to_compute > 1)
    for (std::size_t t = 0; t < tasks.size(); ++t)
      if (tasks[t].cached < 0) bonds[t] = compute(tasks[t].e, tasks[t].f, blocks.data() + t * max_block);
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      const auto [e, f, cached] = tasks[t];
      const std::size_t nb = cached >= 0 ? cache_bonds[static_cast<std::size_t>(cached)] : bonds[t];
      if (nb == 0) continue;
      dofs.clear();
      for (Index n : s.dofmap.cell_nodes(e))
        for (int d = 0; d < D; ++d) dofs.push_back(n * D + d);
      if (f != e)
        for (Index n : s.dofmap.cell_nodes(f))
          for (int d = 0; d < D; ++d) dofs.push_back(n * D + d);
      const double* block = cached >= 0 ? cache_blocks.data() + static_cast<std::size_t>(cached) * max_block
                                        : blocks.data() + t * max_block;
      K.add(dofs, dofs, std::span<const double>(block, dofs.size() * dofs.size()));
      ++stats.cell_pairs;
      stats.bonds += nb;
      stats.reused_pairs += cached >= 0 ? 1 : 0;
    }
  }
  return stats;
}

}  // namespace

NonlocalStats assemble_nonlocal(const NonlocalSpace& space, MatrixInserter& K,
                                const NonlocalOptions& options) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return assemble_dim<D()>(space, K, options); });
}

}  // namespace perimorph::assembly
