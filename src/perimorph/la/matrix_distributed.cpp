// The distributed parts of la::Matrix (matrix.hpp, issue 17): the
// constructor from a Distribution, add() into the owned rows' arrays, and the
// dense copy gathered on every process, and reads of the owned rows.

#include "perimorph/core/error.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/matrix_distributed_view.hpp"
#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace perimorph::la {

Matrix::Matrix(const assembly::SparsityPattern& pattern, std::shared_ptr<const Distribution> distribution)
    : distribution_(std::move(distribution)) {
  const Distribution& d = *distribution_;
  const Index bs = pattern.block_size;
  const Index nb = pattern.num_block_rows();
  if (d.num_nodes() != nb)
    throw Error(fmt::format("matrix: the distribution has {} dof nodes, the pattern {} block rows",
                            d.num_nodes(), nb));
  PM_PETSC(MatCreate(PETSC_COMM_WORLD, &m_));
  PM_PETSC(MatSetSizes(m_, d.owned_nodes() * bs, d.owned_nodes() * bs, PETSC_DETERMINE, PETSC_DETERMINE));
  PM_PETSC(MatSetType(m_, MATAIJ));
  PM_PETSC(MatSetBlockSize(m_, bs));
  // Block-row counts of the owned rows: columns owned here (diagonal block) or elsewhere.
  std::vector<PetscInt> dnnz(static_cast<std::size_t>(d.owned_nodes()), 0), onnz(dnnz.size(), 0);
  std::vector<Index> owned_rows;
  for (Index r = 0; r < nb; ++r) {
    if (!d.owns(r)) continue;
    owned_rows.push_back(r);
    const auto k = static_cast<std::size_t>(d.to_distributed[static_cast<std::size_t>(r)] - d.begin);
    for (Index c : pattern.row(r)) ++(d.owns(c) ? dnnz : onnz)[k];
  }
  PM_PETSC(MatXAIJSetPreallocation(m_, bs, dnnz.data(), onnz.data(), nullptr, nullptr));
  // The whole pattern of the owned rows is stored (explicit zeros), as above;
  // the indices translated here (no local-to-global mapping held by PETSc).
  std::vector<PetscScalar> zeros;
  std::vector<PetscInt> cols;
  for (Index r : owned_rows) {
    const auto pattern_cols = pattern.row(r);
    cols.resize(pattern_cols.size());
    for (std::size_t j = 0; j < cols.size(); ++j)
      cols[j] = d.to_distributed[static_cast<std::size_t>(pattern_cols[j])];
    zeros.assign(cols.size() * static_cast<std::size_t>(bs * bs), 0.0);
    const PetscInt row = d.to_distributed[static_cast<std::size_t>(r)];
    PM_PETSC(MatSetValuesBlocked(m_, 1, &row, static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(),
                                 INSERT_VALUES));
  }
  PM_PETSC(MatSetOption(m_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PM_PETSC(MatSetOption(m_, MAT_IGNORE_ZERO_ENTRIES, PETSC_FALSE));
  finalize();
  direct_ = false;
}

bool Matrix::acquire_distributed_view() {
  if (dview_) return true;
  PetscBool mpiaij = PETSC_FALSE;
  PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m_), MATMPIAIJ, &mpiaij));
  auto v = std::make_unique<DistributedView>();
  if (!mpiaij) {
    // One process (SeqAIJ): the matrix is its own diagonal block, with no off block.
    PetscBool seqaij = PETSC_FALSE;
    PM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m_), MATSEQAIJ, &seqaij));
    if (!seqaij) return false;
    v->diag = m_;
    PM_PETSC(MatGetSize(m_, &v->rend, nullptr));
    PetscInt bs = 1;
    PM_PETSC(MatGetBlockSize(m_, &bs));
    v->bs = bs;
    if (!borrow_csr(m_, v->d)) return false;
    dview_ = std::move(v);
    return true;
  }
  PM_PETSC(MatMPIAIJGetSeqAIJ(m_, &v->diag, &v->off, &v->garray));
  PetscInt noff = 0;
  PM_PETSC(MatGetSize(v->off, nullptr, &noff));
  if (!std::is_sorted(v->garray, v->garray + noff)) return false;  // searched by global column below
  PM_PETSC(MatGetOwnershipRange(m_, &v->rstart, &v->rend));
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  v->bs = bs;
  if (!borrow_csr(v->diag, v->d)) return false;
  if (!borrow_csr(v->off, v->o)) {
    return_csr(v->diag, v->d);
    return false;
  }
  dview_ = std::move(v);
  return true;
}

void Matrix::add_distributed(std::span<const Index> rows, std::span<const Index> cols,
                             std::span<const double> values) {
  // MatSetValues(ADD_VALUES)'s semantics, as the serial direct path: negative
  // indices skipped, values summed in row-major order, an entry outside the
  // pattern an error; rows of other processes skipped (their owners compute them).
  DistributedView& v = *dview_;
  const Distribution& dist = *distribution_;
  const std::size_t nc = cols.size();
  // The columns' distributed numbers, once for every row (a block's columns
  // fit the stack: 2 cells × 8 nodes × 3 components).
  constexpr std::size_t on_stack = 64;
  std::array<PetscInt, on_stack> stack_cols;  // written before read
  std::vector<PetscInt> heap_cols;
  PetscInt* gcols = stack_cols.data();
  if (nc > on_stack) {
    heap_cols.resize(nc);
    gcols = heap_cols.data();
  }
  for (std::size_t j = 0; j < nc; ++j) gcols[j] = cols[j] < 0 ? -1 : dist.global_dof(cols[j], v.bs);
  const bool same_rows = rows.data() == cols.data() && rows.size() == nc;  // a block's rows are its columns
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i] < 0) continue;
    const PetscInt gr = same_rows ? gcols[i] : dist.global_dof(rows[i], v.bs);
    const double* vrow = values.data() + i * nc;
    if (gr < v.rstart || gr >= v.rend) continue;
    const PetscInt lr = gr - v.rstart;
    const PetscInt *dfirst = v.d.ja + v.d.ia[lr], *dlast = v.d.ja + v.d.ia[lr + 1];
    const PetscInt* ofirst = v.off != nullptr ? v.o.ja + v.o.ia[lr] : nullptr;
    const PetscInt* olast = v.off != nullptr ? v.o.ja + v.o.ia[lr + 1] : nullptr;
    const PetscInt* at = nullptr;  // the last diagonal-block entry written (runs of columns)
    for (std::size_t j = 0; j < nc; ++j) {
      if (cols[j] < 0) continue;
      const PetscInt gc = gcols[j];
      if (gc >= v.rstart && gc < v.rend) {
        const PetscInt c = gc - v.rstart;
        if (at != nullptr && at + 1 < dlast && at[1] == c)
          ++at;
        else {
          at = std::lower_bound(dfirst, dlast, c);
          if (at == dlast || *at != c)
            throw Error(fmt::format("matrix entry ({}, {}) is outside the preallocated sparsity pattern",
                                    rows[i], cols[j]));
        }
        v.d.values[at - v.d.ja] += vrow[j];
      } else {
        const PetscInt* o =
            std::lower_bound(ofirst, olast, gc, [&](PetscInt k, PetscInt g) { return v.garray[k] < g; });
        if (o == olast || v.garray[*o] != gc)
          throw Error(fmt::format("matrix entry ({}, {}) is outside the preallocated sparsity pattern",
                                  rows[i], cols[j]));
        v.o.values[o - v.o.ja] += vrow[j];
      }
    }
  }
}

void Matrix::release_distributed_view() const {
  if (!dview_) return;
  const std::unique_ptr<DistributedView> v = std::move(dview_);
  return_csr(v->diag, v->d);
  if (v->off != nullptr) return_csr(v->off, v->o);
}

std::vector<Index> Matrix::assembly_rows() const {
  const Distribution& d = *distribution_;
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  std::vector<Index> to_assembly(static_cast<std::size_t>(d.num_nodes() * bs));
  for (Index node = 0; node < d.num_nodes(); ++node)
    for (Index k = 0; k < bs; ++k)
      to_assembly[static_cast<std::size_t>(d.to_distributed[static_cast<std::size_t>(node)] * bs + k)] =
          node * bs + k;
  return to_assembly;
}

void Matrix::visit_owned_rows(
    const std::function<void(Index, std::span<const Index>, std::span<const double>)>& visit) const {
  release_view();
  PetscInt first = 0, last = 0;
  PM_PETSC(MatGetOwnershipRange(m_, &first, &last));
  for (PetscInt r = first; r < last; ++r) {
    PetscInt ncols = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    PM_PETSC(MatGetRow(m_, r, &ncols, &cols, &vals));
    visit(r, {cols, static_cast<std::size_t>(ncols)}, {vals, static_cast<std::size_t>(ncols)});
    PM_PETSC(MatRestoreRow(m_, r, &ncols, &cols, &vals));
  }
}

Eigen::MatrixXd Matrix::distributed_to_dense() const {
  release_view();
  // The owned rows, by assembly numbering, summed over the processes.
  const std::vector<Index> to_assembly = assembly_rows();
  const auto n = static_cast<Index>(to_assembly.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  visit_owned_rows([&](Index r, std::span<const Index> cols, std::span<const double> vals) {
    for (std::size_t k = 0; k < cols.size(); ++k)
      A(to_assembly[static_cast<std::size_t>(r)], to_assembly[static_cast<std::size_t>(cols[k])]) = vals[k];
  });
  MPI_Allreduce(MPI_IN_PLACE, A.data(), static_cast<int>(A.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return A;
}

std::vector<Eigen::MatrixXd> Matrix::distributed_blocks(std::span<const Index> dofs,
                                                        std::span<const Index> sizes) const {
  release_view();
  const Distribution& d = *distribution_;
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  auto global = [&](Index dof) { return d.global_dof(dof, bs); };
  // Every block's owned rows, row-major, one after the other; −0.0 elsewhere
  // (la::from_owners: each row from its one owner, exactly).
  std::size_t total = 0;
  for (Index n : sizes) total += static_cast<std::size_t>(n * n);
  std::vector<double> values(total, -0.0);
  std::vector<PetscInt> cols;
  std::size_t at = 0, first = 0;
  for (Index n : sizes) {
    const auto set = dofs.subspan(first, static_cast<std::size_t>(n));
    cols.resize(set.size());
    for (std::size_t j = 0; j < set.size(); ++j) cols[j] = set[j] < 0 ? -1 : global(set[j]);
    for (Index i = 0; i < n; ++i) {
      const Index dof = set[static_cast<std::size_t>(i)];
      if (dof < 0 || !d.owns(dof / bs)) continue;
      PERIMORPH_ASSERT(std::find(cols.begin(), cols.end(), PetscInt{-1}) == cols.end(),
                       "an owned row of a block whose dofs this process lacks");
      const PetscInt row = global(dof);
      PM_PETSC(MatGetValues(m_, 1, &row, static_cast<PetscInt>(n), cols.data(), values.data() + at + i * n));
    }
    at += static_cast<std::size_t>(n * n);
    first += set.size();
  }
  values = from_owners(std::move(values));
  std::vector<Eigen::MatrixXd> out;
  out.reserve(sizes.size());
  at = 0;
  for (Index n : sizes) {
    out.push_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        values.data() + at, n, n));
    at += static_cast<std::size_t>(n * n);
  }
  return out;
}

std::vector<double> Matrix::owned_diagonal_at(std::span<const Index> rows) const {
  release_view();
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  std::vector<double> out(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    PetscInt row = rows[k];
    if (distribution_) {
      PERIMORPH_ASSERT(distribution_->owns(row / bs), "owned_diagonal_at: a row another process owns");
      row = distribution_->global_dof(row, bs);
    }
    PM_PETSC(MatGetValues(m_, 1, &row, 1, &row, &out[k]));
  }
  return out;
}

}  // namespace perimorph::la
