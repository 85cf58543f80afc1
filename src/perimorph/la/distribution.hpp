#pragma once
// How the rows of a matrix and the entries of a vector are spread over the
// processes of PETSC_COMM_WORLD (issue 17): the assembly's numbering of dof
// nodes (every process holds all of it, for now) mapped to a distributed one
// in which each process owns a contiguous range. Plain data: partition/
// computes it (partition::DofLayout), la/ translates the assembly's indices
// with it (global_dof) as they reach PETSc, so assembly keeps inserting in its
// own numbering. PETSc holds no copy of it (no local-to-global mapping: that
// was another whole-length array a matrix).

#include "perimorph/core/types.hpp"

#include <vector>

namespace perimorph::la {

struct Distribution {
  /// The distributed number of each dof node of the assembly's numbering (a
  /// permutation, the same on every process).
  std::vector<Index> to_distributed;
  /// This process owns the distributed dof nodes [begin, end).
  Index begin = 0, end = 0;

  Index num_nodes() const { return static_cast<Index>(to_distributed.size()); }
  Index owned_nodes() const { return end - begin; }
  /// The distributed number of `dof` (assembly numbering, `bs` components a node).
  Index global_dof(Index dof, Index bs) const {
    return to_distributed[static_cast<std::size_t>(dof / bs)] * bs + dof % bs;
  }
  /// True if this process owns dof node n (assembly numbering).
  bool owns(Index n) const {
    const Index d = to_distributed[static_cast<std::size_t>(n)];
    return d >= begin && d < end;
  }
};

}  // namespace perimorph::la
