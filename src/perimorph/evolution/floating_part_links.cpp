#include "perimorph/evolution/floating_part_links.hpp"

#include "perimorph/core/union_find.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <functional>
#include <map>

namespace perimorph::evolution {

namespace {

/// A node this process counts: its key, its part (the smallest key of the
/// part, first of one process's links, then of the whole graph's) and its position.
struct CountedNode {
  Index key = 0;
  Index part = 0;
  Vec3 x = Vec3::Zero();
};

void pack(std::vector<double>& values, const CountedNode& n) {
  values.insert(values.end(),
                {static_cast<double>(n.key), static_cast<double>(n.part), n.x.x(), n.x.y(), n.x.z()});
}

void unpack(std::span<const double> values, std::vector<CountedNode>& out) {
  for (std::size_t k = 0; k + 4 < values.size(); k += 5)
    out.push_back({static_cast<Index>(values[k]), static_cast<Index>(values[k + 1]),
                   Vec3(values[k + 2], values[k + 3], values[k + 4])});
}

/// The nodes of this process's links that another process may reach too: the
/// nodes of a cell that is not this process's or that has a bond to one (a
/// cell with a node of one of its cells is in its piece, and the cell graph
/// is symmetric: a process reaches a node through its own cells' local
/// stiffness and through a cell bonded to one of its own).
std::vector<char> nodes_others_may_reach(const setup::Discretization& disc,
                                         const assembly::NonlocalSpace& space, std::span<const char> own) {
  std::vector<char> shared(static_cast<std::size_t>(disc.dofmap.num_nodes()), 0);
  auto is_own = [&](Index c) { return own[static_cast<std::size_t>(c)] != 0; };
  for (Index c = 0; c < disc.mesh.num_cells(); ++c) {
    bool reached = !is_own(c);
    if (!reached)
      for (Index f : space.graph.row(c)) reached = reached || !is_own(f);
    if (reached)
      for (Index a : disc.dofmap.cell_nodes(c)) shared[static_cast<std::size_t>(a)] = 1;
  }
  return shared;
}

/// The nodes this process counts, each with its part among the links of the
/// process reaching it, sorted by key then part: those of its links no other
/// process reaches, and those any process's links reach that others may reach
/// too whose keys hash to it, once for each process's part reaching it (collective).
std::vector<CountedNode> nodes_to_count(const setup::Discretization& disc,
                                        const assembly::NonlocalSpace& space) {
  const int processes = la::world_size(), rank = la::world_rank();
  const std::vector<char> own = setup::cells_of_process(disc, processes, rank);
  const std::vector<Index> mine = stiffness_links(disc, space, own);
  const std::vector<char> shared = nodes_others_may_reach(disc, space, own);
  // Keys ascend in local order, so a link's root (its part's smallest node) has the part's smallest key.
  const auto& keys = disc.piece->dofs.key;
  std::vector<std::vector<double>> to(static_cast<std::size_t>(processes));
  for (std::size_t k = 0; k < mine.size(); k += 2) {
    const Index key = keys[static_cast<std::size_t>(mine[k])];
    const int counter =
        shared[static_cast<std::size_t>(mine[k])] ? la::hashed_process({key}, processes) : rank;
    pack(to[static_cast<std::size_t>(counter)],
         {key, keys[static_cast<std::size_t>(mine[k + 1])], disc.dofmap.node_coordinate(disc.mesh, mine[k])});
  }
  std::vector<la::Parcel> out;
  for (int p = 0; p < processes; ++p)
    if (p != rank && !to[static_cast<std::size_t>(p)].empty())
      out.push_back({p, std::move(to[static_cast<std::size_t>(p)])});
  std::vector<CountedNode> nodes;
  unpack(to[static_cast<std::size_t>(rank)], nodes);
  for (const la::Parcel& in : la::exchange(out)) unpack(in.values, nodes);
  std::sort(nodes.begin(), nodes.end(), [](const CountedNode& a, const CountedNode& b) {
    return a.key != b.key ? a.key < b.key : a.part < b.part;
  });
  return nodes;
}

/// Joins the processes' parts that meet at a node (every process joins the
/// same pairs, gathered), keeps each node once and names its part by the
/// whole graph's part: its smallest key, as find_floating_parts' roots (collective).
void join_parts(std::vector<CountedNode>& nodes) {
  std::vector<std::pair<Index, Index>> meeting;  // parts meeting at a node, each pair once
  for (std::size_t k = 1, first = 0; k < nodes.size(); ++k) {
    if (nodes[k].key != nodes[k - 1].key)
      first = k;
    else if (nodes[k].part != nodes[k - 1].part)
      meeting.emplace_back(nodes[first].part, nodes[k].part);
  }
  std::sort(meeting.begin(), meeting.end());
  meeting.erase(std::unique(meeting.begin(), meeting.end()), meeting.end());
  std::vector<double> pairs;
  for (const auto& [a, b] : meeting)
    pairs.insert(pairs.end(), {static_cast<double>(a), static_cast<double>(b)});
  const std::vector<double> all = la::all_gather(pairs);
  std::vector<Index> labels(all.size());
  std::transform(all.begin(), all.end(), labels.begin(), [](double v) { return static_cast<Index>(v); });
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  auto slot = [&](Index label) {
    return static_cast<Index>(std::lower_bound(labels.begin(), labels.end(), label) - labels.begin());
  };
  UnionFind parts(labels.size());  // the smallest label of each set is its root
  for (std::size_t k = 0; k < all.size(); k += 2)
    parts.join(slot(static_cast<Index>(all[k])), slot(static_cast<Index>(all[k + 1])));
  nodes.erase(std::unique(nodes.begin(), nodes.end(),
                          [](const CountedNode& a, const CountedNode& b) { return a.key == b.key; }),
              nodes.end());
  for (CountedNode& n : nodes) {
    const auto s = slot(n.part);
    if (static_cast<std::size_t>(s) < labels.size() && labels[static_cast<std::size_t>(s)] == n.part)
      n.part = labels[static_cast<std::size_t>(parts.find(s))];
  }
}

using PartFigures = std::map<Index, std::vector<double>>;

/// Each part's figures combined over the processes by `combine`, value by
/// value (`width` values a part), in rank order: the same bits on every
/// process (collective).
PartFigures over_processes(const PartFigures& mine, std::size_t width,
                           const std::function<double(double, double)>& combine) {
  std::vector<double> packed;
  for (const auto& [part, values] : mine) {
    packed.push_back(static_cast<double>(part));
    packed.insert(packed.end(), values.begin(), values.end());
  }
  PartFigures out;
  const std::vector<double> all = la::all_gather(packed);
  for (std::size_t k = 0; k < all.size(); k += width + 1) {
    const auto [it, fresh] =
        out.try_emplace(static_cast<Index>(all[k]), all.begin() + static_cast<std::ptrdiff_t>(k + 1),
                        all.begin() + static_cast<std::ptrdiff_t>(k + 1 + width));
    if (!fresh)
      for (std::size_t j = 0; j < width; ++j) it->second[j] = combine(it->second[j], all[k + 1 + j]);
  }
  return out;
}

/// The parts (their names, ascending) that `held` might leave free, from the
/// nodes each process counts (collective; floating_part_links.hpp).
std::vector<Index> loosely_held_parts(const std::vector<CountedNode>& nodes, std::span<const Index> held,
                                      int dim) {
  const auto plus = [](double a, double b) { return a + b; };
  PartFigures sums;  // node count, Σ position
  for (const CountedNode& n : nodes) {
    auto& s = sums.try_emplace(n.part, 4, 0.0).first->second;
    s[0] += 1.0;
    for (int i = 0; i < 3; ++i) s[static_cast<std::size_t>(i + 1)] += n.x[i];
  }
  const PartFigures total = over_processes(sums, 4, plus);
  auto centre = [&](Index part) -> Vec3 {
    const auto& t = total.at(part);
    return Vec3(t[1], t[2], t[3]) / t[0];
  };
  PartFigures farthest;
  for (const CountedNode& n : nodes) {
    double& r = farthest.try_emplace(n.part, 1, 0.0).first->second[0];
    r = std::max(r, (n.x - centre(n.part)).norm());
  }
  const PartFigures size = over_processes(farthest, 1, [](double a, double b) { return std::max(a, b); });
  const int modes = rigid_modes(dim);
  const auto width = static_cast<std::size_t>(1 + modes * modes);  // held rows, Gram matrix
  PartFigures gram;
  for (const CountedNode& n : nodes)
    for (int d = 0; d < dim; ++d) {
      if (!std::binary_search(held.begin(), held.end(), n.key * dim + d)) continue;
      const double s = size.at(n.part)[0] > 0.0 ? size.at(n.part)[0] : 1.0;
      const Eigen::VectorXd r = rigid_mode_row(dim, (n.x - centre(n.part)) / s, d).normalized();
      auto& g = gram.try_emplace(n.part, width, 0.0).first->second;
      g[0] += 1.0;
      Eigen::Map<Eigen::MatrixXd>(g.data() + 1, modes, modes) += r * r.transpose();
    }
  const PartFigures held_rows = over_processes(gram, width, plus);
  std::vector<Index> loose;
  for (const auto& [part, t] : total) {
    const auto it = held_rows.find(part);
    if (it != held_rows.end()) {
      const Eigen::MatrixXd g = Eigen::Map<const Eigen::MatrixXd>(it->second.data() + 1, modes, modes);
      const double smallest =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(g, Eigen::EigenvaluesOnly).eigenvalues()[0];
      if (smallest > 1e-10 * it->second[0]) continue;
    }
    loose.push_back(part);
  }
  return loose;
}

}  // namespace

std::vector<Index> links_of_loosely_held_parts(const setup::Discretization& disc,
                                               const assembly::NonlocalSpace& space,
                                               std::span<const Index> held, std::vector<Vec3>* positions) {
  if (!disc.piece || la::world_size() == 1) return stiffness_links_over_processes(disc, space, positions);
  std::vector<CountedNode> nodes = nodes_to_count(disc, space);
  join_parts(nodes);
  const std::vector<Index> loose = loosely_held_parts(nodes, held, disc.dim());
  std::vector<double> mine;
  for (const CountedNode& n : nodes)
    if (std::binary_search(loose.begin(), loose.end(), n.part)) pack(mine, n);
  const std::vector<double> all = la::all_gather(mine);
  std::vector<CountedNode> gathered;
  unpack(all, gathered);
  std::vector<Index> links;
  links.reserve(gathered.size() * 2);
  positions->clear();
  for (const CountedNode& n : gathered) {
    links.insert(links.end(), {n.key, n.part});
    positions->push_back(n.x);
  }
  return links;
}

}  // namespace perimorph::evolution
