#pragma once
// Test support: assemble and solve a local-elasticity problem through the
// library's own path (sparsity → PETSc matrix → Dirichlet elimination → KSP),
// without a case file, for patch tests and manufactured solutions.

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <functional>
#include <vector>

namespace perimorph::testing {

/// Solves K u = F with u = g(x) prescribed (all components) on the nodes of
/// `fixed_nodes` (mesh nodes). Returns the dof vector.
inline std::vector<double> solve_local(const assembly::LocalSpace& space, const fem::ConstitutiveField& C,
                                       const std::vector<Index>& fixed_nodes,
                                       const std::function<Vec3(const Vec3&)>& g,
                                       const std::vector<double>& F, double rtol = 1e-13) {
  const int dim = space.mesh.dim();
  const Index n = space.dofmap.num_dofs();
  la::Matrix K(assembly::build_sparsity(space.dofmap));
  assembly::assemble_elasticity(space, C, K);
  K.finalize();
  std::vector<Index> dofs;
  std::vector<double> gv(static_cast<std::size_t>(n), 0.0);
  for (Index node : space.dofmap.dof_nodes_of_mesh_nodes(fixed_nodes)) {
    const Vec3 v = g(space.dofmap.node_coordinate(space.mesh, node));
    for (int d = 0; d < dim; ++d) {
      dofs.push_back(node * dim + d);
      gv[static_cast<std::size_t>(node * dim + d)] = v[d];
    }
  }
  std::sort(dofs.begin(), dofs.end());
  la::Vector x(n, dim), b(n, dim);
  x.assign(gv);
  b.assign(F);
  K.eliminate_dirichlet(dofs, x, b);
  la::LinearSolver solver(rtol, 20000);
  solver.set_operator(K, space.dofmap.node_coordinate_on(space.mesh), dim);
  la::Vector u(n, dim);
  solver.solve(b, u);
  return u.to_std();
}

}  // namespace perimorph::testing
