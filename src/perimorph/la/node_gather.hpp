#pragma once
// The entries of a distributed vector at the dof nodes one process reads
// (issue 17): those nodes' values brought from their owners, and only those,
// into an array in the assembly's numbering. What a process reads of the
// solution (the run, after each solve) and of x (ShellMatrix, before each
// product) is its halo; gathering the whole vector instead would send every
// process the whole model each time.

#include "perimorph/core/types.hpp"
#include "perimorph/la/distribution.hpp"
#include "perimorph/la/petsc_fwd.hpp"

#include <memory>
#include <span>
#include <vector>

namespace perimorph::la {

class Vector;

class NodeGather {
 public:
  /// Gathers from vectors laid out by `distribution` (not null) in dof nodes
  /// of `block_size` entries the nodes `reads` (assembly numbering, each
  /// once); `reads` empty: every node.
  NodeGather(std::shared_ptr<const Distribution> distribution, int block_size, std::vector<Index> reads);
  ~NodeGather();
  NodeGather(NodeGather&& other) noexcept;
  NodeGather& operator=(NodeGather&& other) noexcept;
  NodeGather(const NodeGather&) = delete;
  NodeGather& operator=(const NodeGather&) = delete;

  /// Writes x's entries at the nodes read into `out` (the whole vector in the
  /// assembly's numbering: num_nodes × block_size entries) and leaves the
  /// others as they are. Collective; every call with vectors of one layout.
  void gather(PetscVecHandle x, std::span<double> out);
  void gather(const Vector& x, std::span<double> out);
  /// The whole vector in the assembly's numbering: x's entries at the nodes
  /// read, `elsewhere` at the others (NaN: a read outside the halo shows).
  std::vector<double> gathered(const Vector& x, double elsewhere);

  const Distribution& distribution() const { return *distribution_; }
  int block_size() const { return block_size_; }
  /// Entries of x this process receives from others per gather.
  Index received() const;

 private:
  std::shared_ptr<const Distribution> distribution_;
  int block_size_ = 1;
  std::vector<Index> reads_;
  /// x → this process's entries at reads_ (all of x if empty), distributed
  /// numbering; made at the first gather, from that vector's layout.
  struct Scatter;
  std::unique_ptr<Scatter> scatter_;
};

}  // namespace perimorph::la
