#pragma once
// Values looked up by key across the processes (issue 17, item 1): each
// process holds some keys with a value each, and asks for the values of other
// keys, without knowing which process holds them. PETSc's rendezvous
// (PetscSFCreateByMatchingIndices): the key space is cut into one range per
// process, each key's holder and askers meet at its range's process, and the
// values then travel holder → asker directly. No process handles more than its
// own keys, what it asks and its range's share: nothing of the whole.

#include "perimorph/core/types.hpp"

#include <span>
#include <vector>

namespace perimorph::la {

/// The value of each key of `wanted`, from the process whose `keys` hold it
/// (`values[k]` ≥ 0 is `keys[k]`'s). Keys lie in [0, key_space), the same
/// key_space on every process; a key is held by one process at most, and a
/// process asks for none of its own. Collective over PETSC_COMM_WORLD. Throws
/// Error naming a wanted key no process holds.
std::vector<Index> values_of_keys(std::span<const Index> keys, std::span<const Index> values,
                                  std::span<const Index> wanted, Index key_space);

/// The sum of `count` over the processes of lower rank (0 on process 0):
/// where this process's range of a numbering in rank order begins. Collective.
Index offset_over_processes(Index count);

}  // namespace perimorph::la
