#include "perimorph/evolution/floating_parts.hpp"

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/core/union_find.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace perimorph::evolution {

namespace {

/// An orthonormal basis grown one vector at a time (modified Gram–Schmidt).
struct Span {
  std::vector<Eigen::VectorXd> basis;
  /// Adds the part of `row` outside the span if it is at least `tol` × |row|.
  bool add(const Eigen::VectorXd& row, double tol) {
    const double norm = row.norm();
    if (norm == 0.0) return false;
    Eigen::VectorXd r = row;
    for (const auto& q : basis) r -= q.dot(r) * q;
    if (r.norm() <= tol * norm) return false;
    basis.push_back(r / r.norm());
    return true;
  }
};

}  // namespace

Eigen::VectorXd rigid_mode_row(int dim, const Vec3& p, int d) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(rigid_modes(dim));
  r[d] = 1.0;
  if (dim == 2) {
    r[2] = d == 0 ? -p.y() : p.x();  // u = (−y, x)
  } else if (dim == 3) {
    const double x = p.x(), y = p.y(), z = p.z();
    const double about_x[3] = {0.0, -z, y}, about_y[3] = {z, 0.0, -x}, about_z[3] = {-y, x, 0.0};
    r[3] = about_x[d];
    r[4] = about_y[d];
    r[5] = about_z[d];
  }
  return r;
}

std::vector<Index> stiffness_links(const setup::Discretization& model, const assembly::NonlocalSpace& space,
                                   std::span<const char> cells) {
  const auto& dm = model.dofmap;
  const Index nn = dm.num_nodes();
  UnionFind parts(static_cast<std::size_t>(nn));
  std::vector<char> reached(static_cast<std::size_t>(nn), 0);
  auto join_cell = [&](Index c, Index anchor) {
    for (Index a : dm.cell_nodes(c)) {
      parts.join(anchor, a);
      reached[static_cast<std::size_t>(a)] = 1;
    }
  };
  for (Index c = 0; c < model.mesh.num_cells(); ++c)
    if ((cells.empty() || cells[static_cast<std::size_t>(c)] != 0) && model.has_local_stiffness(c))
      join_cell(c, dm.cell_nodes(c).front());
  for (const auto& [e, f] : assembly::bonded_pairs(space, cells)) {
    const Index anchor = dm.cell_nodes(e).front();
    join_cell(e, anchor);
    join_cell(f, anchor);
  }
  std::vector<Index> links;
  for (Index a = 0; a < nn; ++a)
    if (reached[static_cast<std::size_t>(a)]) links.insert(links.end(), {a, parts.find(a)});
  return links;
}

std::vector<Index> stiffness_links_over_processes(const setup::Discretization& disc,
                                                  const assembly::NonlocalSpace& space,
                                                  std::vector<Vec3>* positions) {
  if (la::world_size() == 1) return stiffness_links(disc, space);
  const std::vector<Index> mine =
      stiffness_links(disc, space, setup::cells_of_process(disc, la::world_size(), la::world_rank()));
  if (!disc.piece) {
    const std::vector<double> all = la::all_gather(std::vector<double>(mine.begin(), mine.end()));
    std::vector<Index> links(all.size());
    std::transform(all.begin(), all.end(), links.begin(), [](double v) { return static_cast<Index>(v); });
    return links;
  }
  // On a piece: in the nodes' names (their keys), with the first node's position.
  PERIMORPH_ASSERT(positions != nullptr, "a piece's links need their positions");
  const auto& keys = disc.piece->dofs.key;
  std::vector<double> packed;
  packed.reserve(mine.size() / 2 * 5);
  for (std::size_t k = 0; k < mine.size(); k += 2) {
    const Vec3 x = disc.dofmap.node_coordinate(disc.mesh, mine[k]);
    packed.insert(packed.end(),
                  {static_cast<double>(keys[static_cast<std::size_t>(mine[k])]),
                   static_cast<double>(keys[static_cast<std::size_t>(mine[k + 1])]), x.x(), x.y(), x.z()});
  }
  const std::vector<double> all = la::all_gather(packed);
  std::vector<Index> links;
  links.reserve(all.size() / 5 * 2);
  positions->clear();
  for (std::size_t k = 0; k < all.size(); k += 5) {
    links.insert(links.end(), {static_cast<Index>(all[k]), static_cast<Index>(all[k + 1])});
    positions->emplace_back(all[k + 2], all[k + 3], all[k + 4]);
  }
  return links;
}

FloatingParts find_floating_parts(const setup::Discretization& model, std::span<const Index> links,
                                  std::span<const Index> held, const la::DofValuesAt& force,
                                  std::span<const Vec3> positions) {
  const int dim = model.dim();
  const int nr = rigid_modes(dim);
  PERIMORPH_ASSERT(links.size() % 2 == 0, "stiffness links come in pairs");
  PERIMORPH_ASSERT(positions.empty() || positions.size() * 2 == links.size(), "a position for each link");
  // The nodes the links reach, numbered 0, 1, … in the order of their names
  // (every node reached is the first of a link: stiffness_links).
  std::vector<Index> name;
  name.reserve(links.size() / 2);
  for (std::size_t k = 0; k < links.size(); k += 2) name.push_back(links[k]);
  std::sort(name.begin(), name.end());
  name.erase(std::unique(name.begin(), name.end()), name.end());
  const auto nn = static_cast<Index>(name.size());
  auto node_of = [&](Index n) {
    const auto it = std::lower_bound(name.begin(), name.end(), n);
    PERIMORPH_ASSERT(it != name.end() && *it == n, "a link to a node no link reaches");
    return static_cast<Index>(it - name.begin());
  };
  std::vector<Vec3> at(static_cast<std::size_t>(nn));
  UnionFind parts(static_cast<std::size_t>(nn));
  for (std::size_t k = 0; k < links.size(); k += 2) {
    const Index a = node_of(links[k]);
    parts.join(a, node_of(links[k + 1]));
    at[static_cast<std::size_t>(a)] =
        positions.empty() ? model.dofmap.node_coordinate(model.mesh, links[k]) : positions[k / 2];
  }
  auto coordinate = [&](Index a) -> const Vec3& { return at[static_cast<std::size_t>(a)]; };
  // Nodes of each part (roots are the smallest node, so parts come in order).
  std::vector<std::vector<Index>> members;
  std::vector<Index> part_of_root(static_cast<std::size_t>(nn), -1);
  for (Index a = 0; a < nn; ++a) {
    const Index r = parts.find(a);
    auto& slot = part_of_root[static_cast<std::size_t>(r)];
    if (slot < 0) {
      slot = static_cast<Index>(members.size());
      members.emplace_back();
    }
    members[static_cast<std::size_t>(slot)].push_back(a);
  }
  // Held, per reached node and component; a held dof of a node no link reaches changes nothing.
  std::vector<char> is_held(static_cast<std::size_t>(nn) * static_cast<std::size_t>(dim), 0);
  for (Index d : held) {
    const auto it = std::lower_bound(name.begin(), name.end(), d / dim);
    if (it != name.end() && *it == d / dim)
      is_held[static_cast<std::size_t>((it - name.begin()) * dim + d % dim)] = 1;
  }

  // The parts the held dofs do not fix (the parts share no node, so pinning
  // one changes no other's span), and the force at their dofs, read once.
  struct Floating {
    const std::vector<Index>* nodes;
    Vec3 centre;  ///< the nodes' positions are taken relative to it,
    double size;  ///< scaled by the part's size (1 if a single point)
    Span span;    ///< of the held dofs' rigid-body rows
  };
  std::vector<Floating> floating;
  std::vector<Index> floating_dofs;
  for (const auto& nodes : members) {
    Vec3 centre = Vec3::Zero();
    for (Index a : nodes) centre += coordinate(a);
    centre /= static_cast<double>(nodes.size());
    double size = 0.0;
    for (Index a : nodes) size = std::max(size, (coordinate(a) - centre).norm());
    if (size == 0.0) size = 1.0;
    Span span;
    for (Index a : nodes)
      for (int d = 0; d < dim; ++d)
        if (is_held[static_cast<std::size_t>(a * dim + d)])
          span.add(rigid_mode_row(dim, (coordinate(a) - centre) / size, d), kHeldSpanTolerance);
    if (static_cast<int>(span.basis.size()) == nr) continue;
    for (Index a : nodes)
      for (int d = 0; d < dim; ++d) floating_dofs.push_back(a * dim + d);
    floating.push_back({&nodes, centre, size, std::move(span)});
  }
  std::sort(floating_dofs.begin(), floating_dofs.end());
  std::vector<Index> floating_names(floating_dofs.size());
  for (std::size_t k = 0; k < floating_dofs.size(); ++k)
    floating_names[k] = name[static_cast<std::size_t>(floating_dofs[k] / dim)] * dim + floating_dofs[k] % dim;
  const std::vector<double> floating_force = force ? force(floating_names) : std::vector<double>{};
  auto force_at = [&](Index dof) {
    return floating_force[static_cast<std::size_t>(
        std::lower_bound(floating_dofs.begin(), floating_dofs.end(), dof) - floating_dofs.begin())];
  };

  FloatingParts out;
  for (Floating& part : floating) {
    const std::vector<Index>& nodes = *part.nodes;
    Span& span = part.span;
    auto rel = [&](Index a) -> Vec3 { return (coordinate(a) - part.centre) / part.size; };
    ++out.parts;
    // The free modes: the complement of the held rows' span.
    Span all = span;
    std::vector<Eigen::VectorXd> free_modes;
    for (int k = 0; k < nr; ++k)
      if (all.add(Eigen::VectorXd::Unit(nr, k), 1e-8)) free_modes.push_back(all.basis.back());
    if (force) {
      for (const auto& m : free_modes) {
        double work = 0.0, scale = 0.0;
        for (Index a : nodes)
          for (int d = 0; d < dim; ++d) {
            const double F = force_at(a * dim + d);
            const Eigen::VectorXd row = rigid_mode_row(dim, rel(a), d);
            work += F * row.dot(m);
            scale += std::abs(F) * row.norm();
          }
        if (scale > 0.0 && std::abs(work) > 1e-9 * scale) {
          Vec3 lo = coordinate(nodes.front()), hi = lo;
          for (Index a : nodes) {
            lo = lo.cwiseMin(coordinate(a));
            hi = hi.cwiseMax(coordinate(a));
          }
          throw Error(
              fmt::format("bond failures have cut free a part of {} nodes (between ({:g}, {:g}, {:g}) and "
                          "({:g}, {:g}, {:g})) "
                          "that no support holds in every direction, and the applied forces on it do not "
                          "balance: there is "
                          "no quasi-static equilibrium (the part would fly off)",
                          nodes.size(), lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()));
        }
      }
    }
    // Pins: the part's nodes from the farthest from its centre inwards (long
    // lever arms), a dof kept when it removes a mode well (then any mode).
    std::vector<Index> order(nodes);
    std::stable_sort(order.begin(), order.end(),
                     [&](Index a, Index b) { return rel(a).squaredNorm() > rel(b).squaredNorm(); });
    for (double tol : {0.3, kHeldSpanTolerance})
      for (Index a : order)
        for (int d = 0; d < dim && static_cast<int>(span.basis.size()) < nr; ++d) {
          const Index dof = a * dim + d;
          if (is_held[static_cast<std::size_t>(dof)]) continue;
          if (span.add(rigid_mode_row(dim, rel(a), d), tol)) {
            out.pins.push_back(name[static_cast<std::size_t>(a)] * dim + d);
            is_held[static_cast<std::size_t>(dof)] = 1;
          }
        }
    PERIMORPH_ASSERT(static_cast<int>(span.basis.size()) == nr, "a floating part could not be pinned");
  }
  std::sort(out.pins.begin(), out.pins.end());
  return out;
}

}  // namespace perimorph::evolution
