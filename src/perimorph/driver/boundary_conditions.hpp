#pragma once
// Dirichlet constraints and external loads of a case, at load factor 1; the
// run scales them by the load factor of each increment (THEORY §4).

#include "perimorph/driver/model.hpp"

#include <string>
#include <vector>

namespace perimorph::driver {

struct DirichletData {
  std::vector<Index> dofs;     ///< sorted, unique
  std::vector<double> values;  ///< prescribed value at load factor 1
};

/// Constrained dofs and their values. A dof named by several entries takes the
/// value of the last one. Throws InputError (with the case-file location) for a
/// set the mesh does not have.
DirichletData build_dirichlet(const Model& model);

/// External force vector (body force + tractions) at load factor 1.
std::vector<double> build_external_force(const Model& model);

/// A named set whose reaction force is reported: the dofs of its nodes.
struct ReactionSet {
  std::string name;
  std::vector<Index> dof_nodes;
};
/// One reaction set per distinct Dirichlet set name, in order of appearance.
std::vector<ReactionSet> reaction_sets(const Model& model);

}  // namespace perimorph::driver
