#include "perimorph/driver/boundary_conditions.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace perimorph::driver {

namespace {

std::vector<Index> dof_nodes_of_set(const Model& model, const std::string& set,
                                    const casefile::SourceLocation& where) {
  try {
    // A cell set names every dof node of its cells (the only way to reach the
    // centroid nodes of DG degree 0 cells); other sets name mesh nodes.
    if (auto it = model.mesh.cell_sets.find(set); it != model.mesh.cell_sets.end())
      return model.dofmap.dof_nodes_of_cells(it->second);
    return model.dofmap.dof_nodes_of_mesh_nodes(model.mesh.nodes_of_set(set));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", where.describe(), e.what()));
  }
}

}  // namespace

DirichletData build_dirichlet(const Model& model) {
  const int dim = model.dim();
  std::map<Index, double> prescribed;
  for (const auto& bc : model.config.dirichlet) {
    for (Index n : dof_nodes_of_set(model, bc.set, bc.where)) {
      const Vec3& x = model.dofmap.node_coordinate(n);
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

std::vector<double> build_external_force(const Model& model) {
  std::vector<double> F(static_cast<std::size_t>(model.dofmap.num_dofs()), 0.0);
  const auto space = model.local_space();
  const Vec3 b = model.config.loading.body_force;
  if (b.squaredNorm() > 0)
    assembly::assemble_body_force(
        space, [&](const Vec3&) { return b; }, F);
  for (const auto& t : model.config.tractions) {
    auto it = model.mesh.face_sets.find(t.set);
    if (it == model.mesh.face_sets.end())
      throw InputError(
          fmt::format("{}: tractions need a face set; '{}' is not one (face sets: xmin, xmax, ... and "
                      "\"boundary\")",
                      t.where.describe(), t.set));
    assembly::assemble_traction(space, it->second, t.value, F);
  }
  return F;
}

std::vector<ReactionSet> reaction_sets(const Model& model) {
  std::vector<ReactionSet> sets;
  for (const auto& bc : model.config.dirichlet) {
    if (std::any_of(sets.begin(), sets.end(), [&](const ReactionSet& s) { return s.name == bc.set; }))
      continue;
    sets.push_back({bc.set, dof_nodes_of_set(model, bc.set, bc.where)});
  }
  return sets;
}

}  // namespace perimorph::driver
