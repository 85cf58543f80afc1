#pragma once
// Dirichlet constraints and external loads of a case, at load factor 1; the
// run scales them by the load factor of each increment (THEORY §4).
//
// What a set reaches: a boundary condition on a set acts on the degrees of
// freedom of its dof nodes (set_dof_nodes). A set that reaches none, or a name
// the mesh does not have, is an InputError naming the case-file entry.

#include "perimorph/setup/discretization.hpp"

#include <string>
#include <vector>

namespace perimorph::setup {

/// The dof nodes a boundary condition on `set` reaches, sorted and unique:
/// - a cell set (`all`, a [[region]]): every dof node of its cells;
/// - a node or face set: every dof node that copies one of its mesh nodes (the
///   shared node of CG cells, the private copies of DG cells), and the centroid
///   node of every DG degree 0 cell touching the set (a vertex in the set; for
///   a face set of the box, the cells with a face on it), which has no vertex
///   node of its own.
/// Throws InputError prefixed with `where` for a name the mesh does not have
/// (with the closest set name) or a set that reaches no dof node (on a piece
/// of the model, on no process: Discretization::any_over_processes; then
/// collective).
std::vector<Index> set_dof_nodes(const Discretization& model, const std::string& set,
                                 const casefile::SourceLocation& where);

struct DirichletData {
  std::vector<Index> dofs;     ///< sorted, unique
  std::vector<double> values;  ///< prescribed value at load factor 1
};

/// Constrained dofs and their values. A dof named by several entries takes the
/// value of the last one. Throws InputError (with the case-file location) for a
/// set the mesh does not have or one that reaches no dof (set_dof_nodes).
DirichletData build_dirichlet(const Discretization& model);

/// External force vector (body force + tractions) at load factor 1. A DG
/// degree 0 cell (one node, constant shape function) takes the whole load of
/// its volume and of its faces in the set. Throws InputError for a traction
/// whose set is not a face set of the mesh.
std::vector<double> build_external_force(const Discretization& model);

/// A named set whose reaction force is reported: the dofs of its nodes.
struct ReactionSet {
  std::string name;
  std::vector<Index> dof_nodes;
};
/// One reaction set per distinct Dirichlet set name, in order of appearance
/// (the nodes of set_dof_nodes).
std::vector<ReactionSet> reaction_sets(const Discretization& model);

}  // namespace perimorph::setup
