#pragma once
// Graph partitioning through PETSc's MatPartitioning (issue 17, item 1): the
// partitioners of the PETSc build (Debian's 3.18: PT-Scotch; ParMETIS is not
// in it) on a symmetric graph held by one process.

#include "perimorph/core/types.hpp"

#include <span>
#include <string>
#include <vector>

namespace perimorph::la {

/// An owner (0 … parts − 1) per vertex of the symmetric graph in compressed
/// rows (`offsets`: size n + 1; `neighbors`: each row's vertices; a vertex in
/// its own row is ignored), from MatPartitioning of type `type` ("ptscotch",
/// "parmetis", ... as the PETSc build has them), unit vertex and edge weights.
/// Throws InputError naming the type if PETSc does not have it.
std::vector<int> partition_graph(std::span<const Index> offsets, std::span<const Index> neighbors, int parts,
                                 const std::string& type);

}  // namespace perimorph::la
