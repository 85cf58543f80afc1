#pragma once
// The dofs one process owns (issue 17), ascending in the assembly's
// numbering: what a process keeps of a vector it reads only where it owns
// it (K u, the last recorded state of a run), so that such a vector costs a
// process its part, not the whole model. On one process: every dof, and an
// array over them is the whole vector.

#include "perimorph/core/types.hpp"
#include "perimorph/la/distribution.hpp"

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace perimorph::la {

/// The values of a dof vector at the given dofs (assembly numbering). Where
/// the vector is spread over processes, a collective call: every process asks
/// for the same dofs and gets the same values. An empty function: no vector.
using DofValuesAt = std::function<std::vector<double>(std::span<const Index>)>;

class OwnedDofs {
 public:
  OwnedDofs() = default;
  /// The dofs of the dof nodes (of `block_size` dofs each) `distribution`
  /// gives this process; null: all `num_dofs`.
  OwnedDofs(const Distribution* distribution, int block_size, Index num_dofs);

  std::size_t size() const { return every_ ? static_cast<std::size_t>(num_dofs_) : dofs_.size(); }
  /// The dof (assembly numbering) of owned entry j.
  Index dof(std::size_t j) const { return every_ ? static_cast<Index>(j) : dofs_[j]; }
  /// The owned entry of `dof`, or -1 where another process owns it.
  std::ptrdiff_t position(Index dof) const;
  /// A whole-length array (assembly numbering) at the owned dofs.
  std::vector<double> of(std::span<const double> whole) const;
  /// The values at any `dofs` of the array `owned` (one value per owned
  /// entry, in this order), each from the process that owns it (collective:
  /// every process asks for the same dofs; la::from_owners, the values
  /// exact). On one process owned[dofs[k]].
  std::vector<double> at(std::span<const double> owned, std::span<const Index> dofs) const;
  /// The whole-length array of `owned` on every process (collective; O(dofs)
  /// on every process: for a checkpoint or a remodel, not for every solve).
  std::vector<double> whole(std::span<const double> owned) const;
  /// init + Σ term(j) over the owned entries j in dof order; spread over
  /// processes, each process's sum added in rank order (la::sum_over_processes:
  /// the same bits on every process; collective). On one process the plain
  /// loop: the sum of every dof in dof order.
  double sum(double init, const std::function<double(std::size_t)>& term) const;

 private:
  bool every_ = true;
  Index num_dofs_ = 0;
  std::vector<Index> dofs_;  ///< ascending; used when !every_
};

}  // namespace perimorph::la
