#pragma once
// The whole model's numbering of a piece's dofs (issue 17): what a run on
// pieces of the model (setup::cut_to_piece) writes in, and reads from, a
// checkpoint, so that a checkpoint is the same whatever the number of
// processes and whether they ran on parts or pieces (run/checkpoint.hpp).
// The whole model numbers its dof nodes in key order (partition::PieceDofs),
// so a node's whole number is the rank of its key among every process's keys:
// each process sends the keys of the nodes it owns, in its distributed range's
// order, and the processes that are to hold whole vectors sort them: every
// process (a restart: O(whole model nodes) on each), or process 0 alone
// (la::Onto::process_zero: what a checkpoint writes, whole on process 0 only).

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/partition/piece_dofs.hpp"

#include <span>
#include <vector>

namespace perimorph::system {

/// A matrix in the whole numbering as a checkpoint stores it (block CSR:
/// la::Matrix::Replicated's arrays), left in the checkpoint's bytes.
struct StoredMatrix {
  int block_size = 1;
  core::StoredArray<Index> row_offsets, columns;
  core::StoredArray<double> values;
};

class WholeNumbering {
 public:
  /// Collective over PETSC_COMM_WORLD: every process passes its piece's dof
  /// nodes (`dofs`, whose owned nodes in local order are its distributed
  /// range: system::piece_distribution) and `block_size` dofs a node. With
  /// Onto::process_zero only process 0 holds the whole numbering and receives
  /// the whole vectors and matrices; the others hold nothing whole, and the
  /// piece's side (piece_of, owned_of, the dofs' numbers) is not there.
  WholeNumbering(const partition::PieceDofs& dofs, int block_size, la::Onto onto = la::Onto::every_process);

  /// Where the whole vectors and matrices go.
  la::Onto onto() const { return onto_; }
  /// The whole model's dof count (0 where the whole numbering is not held).
  Index whole_dofs() const { return static_cast<Index>(of_distributed_.size()) * block_size_; }
  /// The whole number of each dof node of the distributed numbering.
  std::span<const Index> of_distributed() const { return of_distributed_; }
  /// The whole dof of a dof name (setup::dof_name: key × block size +
  /// component), and back, where the whole numbering is held.
  Index whole_of_name(Index name) const;
  Index name_of_whole(Index whole_dof) const;

  /// The whole-length vector of `owned` (the values at this process's owned
  /// dofs, in their order: la::OwnedDofs), on the processes the numbering's
  /// Onto names; empty on the others (collective).
  std::vector<double> whole(std::span<const double> owned) const;
  /// The piece-length vector (the piece's assembly numbering) of a whole one.
  std::vector<double> piece_of(std::span<const double> whole) const;
  /// The owned entries (la::OwnedDofs order) of a whole vector.
  std::vector<double> owned_of(std::span<const double> whole) const;

  /// The matrix in the whole numbering, on the processes the numbering's Onto
  /// names; an empty pattern on the others (collective).
  la::Matrix::Replicated whole(const la::Matrix& M) const;
  /// The rows of the piece's owned dof nodes of a matrix in the whole
  /// numbering as a checkpoint stores it, in the piece's numbering (the other
  /// rows empty), for la::Matrix::from_replicated on the piece's
  /// distribution. Only those rows are read: a mapped checkpoint's other
  /// pages are never touched. Throws InputError where such a row does not
  /// add up, or reaches a node out of range or one the piece lacks (naming
  /// the whole row).
  la::Matrix::Replicated piece_of(const StoredMatrix& whole) const;

  /// The whole numbers of piece dofs, and back (−1 where the piece lacks it).
  std::vector<Index> whole_dofs_of(std::span<const Index> piece_dofs) const;
  std::vector<Index> piece_dofs_of(std::span<const Index> whole_dofs) const;

 private:
  Index rank_of(Index key) const;
  void check_piece_side() const;

  int block_size_ = 1;
  la::Onto onto_ = la::Onto::every_process;
  std::vector<Index> sorted_keys_;     ///< every owned node's key, ascending: its rank is its whole node
  std::vector<Index> of_distributed_;  ///< whole node of each distributed node
  std::vector<Index> of_local_;        ///< whole node of each local (piece) node
  std::vector<Index> local_of_whole_;  ///< local node of each whole node, −1 where the piece lacks it
  std::vector<char> owned_;            ///< per local node (PieceDofs::owned)
};

}  // namespace perimorph::system
