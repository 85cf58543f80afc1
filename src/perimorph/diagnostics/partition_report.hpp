#pragma once
// `perimorph info --partition P` (issue 17, item 1): how the case's cells
// would be distributed over P ranks by each partitioner, and the halo each
// rank would hold (partition/partition.hpp).

#include "perimorph/setup/discretization.hpp"

#include <string>

namespace perimorph::diagnostics {

/// A table, one row per partitioner (coordinate bisection; PT-Scotch through
/// PETSc), of the largest part, the largest halo, the halo's share of the
/// cells a rank holds, the most neighbouring parts and the share of cell-graph
/// pairs cut. Throws InputError if parts < 1 or > cells.
std::string partition_report(const setup::Discretization& disc, int parts);

}  // namespace perimorph::diagnostics
