#pragma once
// A PETSc AIJ matrix (RAII, move-only) created with exact preallocation from a
// SparsityPattern; inserting outside the pattern is an error. It implements
// assembly::MatrixInserter, so assembly code never sees PETSc.
//
// Insertion: on one process (MATSEQAIJ, the structure fixed at creation) add()
// writes into PETSc's own CSR arrays (MatGetRowIJ / MatSeqAIJGetArray), one
// search per run of consecutive columns instead of MatSetValues' per-value
// path; the values are summed in the same order, so the matrix is bit-identical
// to MatSetValues(ADD_VALUES). Any other operation releases the arrays first;
// elsewhere add() is MatSetValues.
//
// Distributed (issue 17): made with a la::Distribution, the matrix is spread
// over the processes of PETSC_COMM_WORLD by it, and add(), eliminate_dirichlet
// and to_dense take and give the assembly's numbering. add() keeps the rows
// this process owns and skips the others: their owners compute them ("owner
// computes", partition/dof_layout.hpp), so nothing is sent. The other
// operations that take row numbers are for one process.

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/la/distribution.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_fwd.hpp"
#include "perimorph/la/vector.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace perimorph::la {

class Matrix final : public assembly::MatrixInserter {
 public:
  explicit Matrix(const assembly::SparsityPattern& pattern);
  /// The same spread over the processes by `distribution` (of the pattern's
  /// block rows; the same on every process): each process stores the rows it
  /// owns, preallocated exactly from the pattern.
  Matrix(const assembly::SparsityPattern& pattern, std::shared_ptr<const Distribution> distribution);
  ~Matrix() override;
  Matrix(Matrix&& other) noexcept;
  Matrix& operator=(Matrix&& other) noexcept;
  Matrix(const Matrix&) = delete;
  Matrix& operator=(const Matrix&) = delete;

  /// ADD_VALUES of a dense row-major block.
  void add(std::span<const Index> rows, std::span<const Index> cols, std::span<const double> values) override;
  void zero_entries();
  /// Ends an insertion phase (MatAssemblyBegin/End, final).
  void finalize();
  /// A copy with the same pattern and values.
  Matrix duplicate() const;
  /// A copy without the node blocks (block size × block size, the pattern's)
  /// whose entries are all zero: the stored pattern of an assembly is that of
  /// the cell graph (every pair of cells that may share a bond), wider than
  /// the bonds themselves for a short horizon; a preconditioner built on the
  /// matrix (GAMG) pays for every stored entry. Finalized; values bitwise equal.
  Matrix without_zero_blocks() const;

  /// y ← A x
  void mult(const Vector& x, Vector& y) const;
  /// Exact elimination of Dirichlet rows and columns (THEORY §4): with x
  /// holding the prescribed values on `rows`, sets rhs ← rhs − A[:, rows] x[rows],
  /// zeroes those rows and columns, puts `diagonal` on the diagonal and sets
  /// rhs[rows] = diagonal · x[rows]. The matrix stays symmetric.
  void eliminate_dirichlet(std::span<const Index> rows, const Vector& x, Vector& rhs, double diagonal = 1.0);

  /// The diagonal (MatGetDiagonal), a vector laid out as the rows (spread
  /// over the processes as they are: each holds its owned rows', nothing sent).
  Vector diagonal() const;
  /// The diagonal entries at `rows`, rows this process owns (any row on one
  /// process; MatGetValues, a finalized matrix). Nothing is sent.
  std::vector<double> owned_diagonal_at(std::span<const Index> rows) const;
  /// The diagonal entries at the given rows (MatGetValues; a finalized
  /// matrix). Distributed: collective, the same rows on every process, the
  /// values on every process.
  std::vector<double> diagonal_at(std::span<const Index> rows) const;
  /// The dense principal block A[dofs, dofs] (MatGetValues; a finalized
  /// matrix; entries outside the pattern are 0). Distributed: as blocks.
  Eigen::MatrixXd block(std::span<const Index> dofs) const;
  /// The principal blocks A[s, s] of each set s of dofs, as block does.
  /// Distributed: collective, the same sets on every process, each owner's
  /// rows summed over the processes once (one reduction for all the blocks),
  /// the blocks on every process bitwise as on one process. A dof may be -1
  /// where this process lacks it (a piece of the model: the sets are the
  /// same dofs, each process's numbers) when it owns no row of that set.
  std::vector<Eigen::MatrixXd> blocks(std::span<const std::vector<Index>> sets) const;
  Index rows() const;
  /// Number of stored non-zeros (allocated = used after finalize).
  double nonzeros() const;
  /// Calls visit(row, columns, values) for every row in order, with the
  /// stored entries of the row (columns ascending): a matrix without a
  /// distribution (visit_owned_rows for a distributed one). The spans are
  /// valid only during the call.
  void visit_rows(
      const std::function<void(Index, std::span<const Index>, std::span<const double>)>& visit) const;
  /// Calls visit(row, columns, values) for every row this process owns, in
  /// order, in the distributed numbering (the assembly's without a
  /// distribution), with its stored entries (columns ascending, distributed
  /// numbers). Nothing is sent: two matrices of the same rows on any pieces
  /// of the model compare row by row (the spans are valid during the call).
  void visit_owned_rows(
      const std::function<void(Index, std::span<const Index>, std::span<const double>)>& visit) const;
  /// The stored structure as a block pattern (the matrix's block size; every
  /// row of a block row has the same block columns, as Matrix(pattern) and
  /// without_zero_blocks make them): with Matrix(pattern) and set_values of
  /// the values visit_rows gives, an exact copy (a checkpoint, run/checkpoint.hpp).
  assembly::SparsityPattern block_pattern() const;
  /// Overwrites the stored values (in row order, as visit_rows gives them) of a
  /// finalized matrix; throws Error if their number differs.
  void set_values(std::span<const double> values);
  /// The stored entries in the assembly's numbering, on every process: the
  /// block pattern and the values row by row (a row's columns ascending), as
  /// block_pattern() and visit_rows give them on one process; distributed,
  /// every process's rows gathered (collective), so that the same matrix
  /// gives the same copy on any number of processes (a checkpoint,
  /// run/checkpoint.hpp).
  struct Replicated {
    assembly::SparsityPattern pattern;
    std::vector<double> values;
  };
  Replicated replicated() const;
  /// The same in another numbering of the dof nodes: `node_of_distributed`
  /// names the node of each distributed dof node (a permutation; on a piece
  /// of the model, whose assembly numbering covers the piece only, the whole
  /// model's: system::WholeNumbering), read only where the copy goes. With
  /// Onto::process_zero, the copy is process 0's alone (the others send their
  /// rows and return an empty copy, holding nothing whole). Collective.
  Replicated replicated(std::span<const Index> node_of_distributed, Onto onto = Onto::every_process) const;
  /// The matrix of `r`, an exact copy: Matrix(pattern) with its values, or,
  /// with a distribution, Matrix(pattern, distribution), each process setting
  /// the rows it owns (collective). Throws Error if the values do not fit.
  static Matrix from_replicated(const Replicated& r, std::shared_ptr<const Distribution> distribution);
  /// Dense copy, for tests on tiny matrices; distributed, the whole matrix in
  /// the assembly's numbering on every process (collective).
  Eigen::MatrixXd to_dense() const;
  /// A vector laid out as the matrix's rows (its distribution and block
  /// size), zero.
  Vector make_vector() const;
  /// Overwrites the values with those of `other`, a matrix of the same
  /// pattern and layout (a duplicate() of it, or its original).
  void copy_values_from(const Matrix& other);
  /// The distribution (null on one process without one).
  const std::shared_ptr<const Distribution>& distribution() const { return distribution_; }
  /// Marks the matrix symmetric positive definite (after finalize).
  void set_spd();

  /// The PETSc matrix, for PETSc calls that may change it (la/ only).
  PetscMatHandle handle() {
    release_view();
    return m_;
  }
  /// The PETSc matrix for read-only PETSc calls (PETSc takes Mat, not a
  /// const type, even where it only reads): nothing may change it through
  /// this handle.
  PetscMatHandle read_handle() const {
    release_view();
    return m_;
  }

 private:
  explicit Matrix(PetscMatHandle m);
  /// The CSR arrays held by add() between other operations (non-owning:
  /// PETSc's own arrays, borrowed until release_view).
  struct CsrView {
    const Index* ia = nullptr;
    const Index* ja = nullptr;
    double* values = nullptr;
    Index n = 0;
  };
  /// Borrows a SeqAIJ matrix's CSR arrays into `view` (false, nothing
  /// borrowed, if PETSc cannot give them); return_csr gives them back.
  static bool borrow_csr(PetscMatHandle a, CsrView& view);
  static void return_csr(PetscMatHandle a, const CsrView& view);
  bool acquire_view();
  void release_view() const;
  /// Distributed (matrix_distributed.cpp): add() writes the owned rows into
  /// the arrays of the two blocks PETSc keeps them in (the columns owned here,
  /// and the others), and keeps the entries of other processes' rows until
  /// release_view hands them to MatSetValues (sent at finalize).
  struct DistributedView;
  bool acquire_distributed_view();
  void add_distributed(std::span<const Index> rows, std::span<const Index> cols,
                       std::span<const double> values);
  void release_distributed_view() const;
  Eigen::MatrixXd distributed_to_dense() const;
  /// The assembly's number of each row in the distributed numbering (the
  /// inverse of the distribution's, scalar rows).
  std::vector<Index> assembly_rows() const;
  /// The principal blocks over consecutive runs of `dofs` (run k: sizes[k]
  /// dofs), gathered on every process (collective).
  std::vector<Eigen::MatrixXd> distributed_blocks(std::span<const Index> dofs,
                                                  std::span<const Index> sizes) const;

  PetscMatHandle m_ = nullptr;
  std::shared_ptr<const Distribution> distribution_;
  bool direct_ = false;  ///< MATSEQAIJ with a fixed structure: add() may write the arrays
  mutable CsrView view_;
  mutable bool view_held_ = false;
  mutable std::unique_ptr<DistributedView> dview_;
};

}  // namespace perimorph::la
