#include "perimorph/setup/boundary_conditions.hpp"

#include "perimorph/casefile/suggest.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

namespace perimorph::setup {

namespace {

/// " (did you mean 'ymax'?)" or "".
std::string did_you_mean(const std::string& name, const std::vector<std::string>& names) {
  const std::string near = casefile::closest_match(name, names);
  return near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near);
}

template <class Map>
std::vector<std::string> keys(const Map& map) {
  std::vector<std::string> out;
  for (const auto& [k, v] : map) out.push_back(k);
  return out;
}

}  // namespace

std::vector<Index> set_dof_nodes(const Discretization& model, const std::string& set,
                                 const casefile::SourceLocation& where) {
  const auto& mesh = model.mesh;
  const auto& dm = model.dofmap;
  std::vector<Index> out;
  if (auto it = mesh.cell_sets.find(set); it != mesh.cell_sets.end()) {
    out = dm.dof_nodes_of_cells(it->second);
  } else if (mesh.node_sets.contains(set) || mesh.face_sets.contains(set)) {
    const std::vector<Index> nodes = mesh.nodes_of_set(set);
    out = dm.dof_nodes_of_mesh_nodes(nodes);
    // DG degree 0 cells have one node, at the centroid, copying no mesh node:
    // the set reaches them through their vertices.
    std::vector<char> in_set(static_cast<std::size_t>(mesh.num_nodes()), 0);
    for (Index n : nodes) in_set[static_cast<std::size_t>(n)] = 1;
    for (Index c = 0; c < mesh.num_cells(); ++c) {
      if (dm.continuity(c) != dofs::Continuity::discontinuous_constant) continue;
      const auto vertices = mesh.cell(c);
      if (std::any_of(vertices.begin(), vertices.end(),
                      [&](Index n) { return in_set[static_cast<std::size_t>(n)] != 0; }))
        out.push_back(dm.cell_nodes(c)[0]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  } else {
    const auto names = mesh.set_names();
    throw InputError(fmt::format(
        "{}: the mesh has no set named '{}'{}; its sets are {} (those of the box or of the Gmsh file's "
        "physical groups, cell set \"all\", one cell set per [[region]], one node set per [[node_set]])",
        where.describe(), set, did_you_mean(set, names), fmt::join(names, ", ")));
  }
  // On a piece (collective): a set may miss it and reach another process's.
  const bool reached = model.any_over_processes ? model.any_over_processes(!out.empty()) : !out.empty();
  if (!reached)
    throw InputError(fmt::format(
        "{}: set '{}' reaches no degree of freedom of the discretization, so a boundary condition on it "
        "would act on nothing; choose a set whose cells or nodes carry degrees of freedom",
        where.describe(), set));
  return out;
}

DirichletData build_dirichlet(const Discretization& model) {
  const int dim = model.dim();
  std::map<Index, double> prescribed;
  for (const auto& bc : model.config.dirichlet) {
    for (Index n : set_dof_nodes(model, bc.set, bc.where)) {
      const Vec3 x = model.dofmap.node_coordinate(model.mesh, n);
      for (int c = 0; c < dim; ++c)
        if (bc.constrained[static_cast<std::size_t>(c)])
          prescribed[n * dim + c] = bc.value[c] + bc.gradient.row(c).dot(x);
    }
  }
  DirichletData data;
  for (const auto& [dof, value] : prescribed) {
    data.dofs.push_back(dof);
    data.values.push_back(value);
  }
  return data;
}

std::vector<double> build_external_force(const Discretization& model) {
  std::vector<double> F(static_cast<std::size_t>(model.dofmap.num_dofs()), 0.0);
  const auto space = model.local_space();
  const Vec3 b = model.config.loading.body_force;
  if (b.squaredNorm() > 0)
    assembly::assemble_body_force(
        space, [&](const Vec3&) { return b; }, F);
  for (const auto& t : model.config.tractions) {
    auto it = model.mesh.face_sets.find(t.set);
    if (it == model.mesh.face_sets.end()) {
      const auto faces = keys(model.mesh.face_sets);
      const bool other = model.mesh.node_sets.contains(t.set) || model.mesh.cell_sets.contains(t.set);
      throw InputError(fmt::format("{}: tractions need a face set; {}{}. The face sets are {}",
                                   t.where.describe(),
                                   other ? fmt::format("'{}' is a node or cell set", t.set)
                                         : fmt::format("the mesh has no set named '{}'", t.set),
                                   did_you_mean(t.set, faces), fmt::join(faces, ", ")));
    }
    assembly::assemble_traction(space, it->second, t.value, F);
  }
  return F;
}

std::vector<ReactionSet> reaction_sets(const Discretization& model) {
  std::vector<ReactionSet> sets;
  for (const auto& bc : model.config.dirichlet) {
    if (std::any_of(sets.begin(), sets.end(), [&](const ReactionSet& s) { return s.name == bc.set; }))
      continue;
    sets.push_back({bc.set, set_dof_nodes(model, bc.set, bc.where)});
  }
  return sets;
}

}  // namespace perimorph::setup
