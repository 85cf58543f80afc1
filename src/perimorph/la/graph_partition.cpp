#include "perimorph/la/graph_partition.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <fmt/format.h>
#include <petscmat.h>

namespace perimorph::la {

std::vector<int> partition_graph(std::span<const Index> offsets, std::span<const Index> neighbors, int parts,
                                 const std::string& type) {
  const auto n = static_cast<PetscInt>(offsets.size()) - 1;
  // MatCreateMPIAdj takes ownership of PetscMalloc'ed rows without the diagonal.
  PetscInt *ia = nullptr, *ja = nullptr;
  PM_PETSC(PetscMalloc1(n + 1, &ia));
  PetscInt nnz = 0;
  for (PetscInt r = 0; r < n; ++r)
    for (Index k = offsets[static_cast<std::size_t>(r)]; k < offsets[static_cast<std::size_t>(r) + 1]; ++k)
      if (neighbors[static_cast<std::size_t>(k)] != r) ++nnz;
  PM_PETSC(PetscMalloc1(nnz > 0 ? nnz : 1, &ja));
  ia[0] = 0;
  for (PetscInt r = 0; r < n; ++r) {
    ia[r + 1] = ia[r];
    for (Index k = offsets[static_cast<std::size_t>(r)]; k < offsets[static_cast<std::size_t>(r) + 1]; ++k)
      if (neighbors[static_cast<std::size_t>(k)] != r)
        ja[ia[r + 1]++] = neighbors[static_cast<std::size_t>(k)];
  }
  Mat adj = nullptr;
  PM_PETSC(MatCreateMPIAdj(PETSC_COMM_SELF, n, n, ia, ja, nullptr, &adj));
  MatPartitioning part = nullptr;
  PM_PETSC(MatPartitioningCreate(PETSC_COMM_SELF, &part));
  std::vector<int> owner;
  PM_PETSC(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));  // an unknown type: our message
  const PetscErrorCode set = MatPartitioningSetType(part, type.c_str());
  PM_PETSC(PetscPopErrorHandler());
  if (set == 0) {
    PM_PETSC(MatPartitioningSetAdjacency(part, adj));
    PM_PETSC(MatPartitioningSetNParts(part, parts));
    IS is = nullptr;
    PM_PETSC(MatPartitioningApply(part, &is));
    const PetscInt* idx = nullptr;
    PM_PETSC(ISGetIndices(is, &idx));
    owner.assign(idx, idx + n);
    PM_PETSC(ISRestoreIndices(is, &idx));
    PM_PETSC(ISDestroy(&is));
  }
  PM_PETSC(MatPartitioningDestroy(&part));
  PM_PETSC(MatDestroy(&adj));
  if (set != 0)
    throw InputError(
        fmt::format("the PETSc build has no graph partitioner '{}' (Debian's PETSc 3.18 has "
                    "'ptscotch'; perimorph's own: coordinate bisection)",
                    type));
  return owner;
}

}  // namespace perimorph::la
