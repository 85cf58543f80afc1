// Matrix::replicated and Matrix::from_replicated (matrix.hpp): a matrix as
// every process sees it, in the assembly's numbering, and back.

#include "perimorph/core/error.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <petscmat.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <utility>

namespace perimorph::la {

Matrix::Replicated Matrix::replicated() const {
  return replicated({});
}

Matrix::Replicated Matrix::replicated(std::span<const Index> node_of_distributed, Onto onto) const {
  Replicated out;
  if (!distribution_) {
    out.pattern = block_pattern();
    visit_rows([&](Index, std::span<const Index>, std::span<const double> v) {
      out.values.insert(out.values.end(), v.begin(), v.end());
    });
    return out;
  }
  release_view();
  PetscInt bs = 1;
  PM_PETSC(MatGetBlockSize(m_, &bs));
  // This process's rows in the distributed numbering, each as [row, count,
  // columns..., values...] (the numbers exact in doubles below 2^53): the
  // receiver renumbers them, so that a sender needs no whole-length map.
  PetscInt rstart = 0, rend = 0;
  PM_PETSC(MatGetOwnershipRange(m_, &rstart, &rend));
  std::vector<double> mine;
  for (PetscInt r = rstart; r < rend; ++r) {
    PetscInt ncols = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    PM_PETSC(MatGetRow(m_, r, &ncols, &cols, &vals));
    mine.push_back(static_cast<double>(r));
    mine.push_back(static_cast<double>(ncols));
    for (PetscInt j = 0; j < ncols; ++j) mine.push_back(static_cast<double>(cols[j]));
    mine.insert(mine.end(), vals, vals + ncols);
    PM_PETSC(MatRestoreRow(m_, r, &ncols, &cols, &vals));
  }
  const std::vector<double> all = gather_onto(mine, onto);
  out.pattern.block_size = static_cast<int>(bs);
  out.pattern.row_offsets.assign(1, 0);
  if (!receives(onto)) return out;

  std::vector<Index> to_assembly;
  if (node_of_distributed.empty()) {
    to_assembly = assembly_rows();
  } else {
    to_assembly.resize(node_of_distributed.size() * static_cast<std::size_t>(bs));
    for (std::size_t d = 0; d < node_of_distributed.size(); ++d)
      for (PetscInt k = 0; k < bs; ++k)
        to_assembly[d * static_cast<std::size_t>(bs) + static_cast<std::size_t>(k)] =
            node_of_distributed[d] * bs + k;
  }
  const auto n = static_cast<Index>(to_assembly.size());
  std::vector<std::size_t> at(static_cast<std::size_t>(n), all.size());  // each row's record
  for (std::size_t k = 0; k < all.size(); k += 2 + 2 * static_cast<std::size_t>(all[k + 1]))
    at[static_cast<std::size_t>(to_assembly[static_cast<std::size_t>(all[k])])] = k;
  std::vector<std::pair<Index, double>> row;
  for (Index r = 0; r < n; ++r) {
    const std::size_t k = at[static_cast<std::size_t>(r)];
    PERIMORPH_ASSERT(k < all.size(), "a row of the distributed matrix no process holds");
    const auto ncols = static_cast<std::size_t>(all[k + 1]);
    row.clear();
    for (std::size_t j = 0; j < ncols; ++j)
      row.emplace_back(to_assembly[static_cast<std::size_t>(all[k + 2 + j])], all[k + 2 + ncols + j]);
    std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    if (r % bs == 0) {
      for (std::size_t j = 0; j < ncols; j += static_cast<std::size_t>(bs))
        out.pattern.columns.push_back(row[j].first / bs);
      out.pattern.row_offsets.push_back(static_cast<Index>(out.pattern.columns.size()));
    }
    for (const auto& e : row) out.values.push_back(e.second);
  }
  return out;
}

Matrix Matrix::from_replicated(const Replicated& r, std::shared_ptr<const Distribution> distribution) {
  const std::size_t bs = static_cast<std::size_t>(r.pattern.block_size);
  if (r.values.size() != r.pattern.columns.size() * bs * bs)
    throw Error(fmt::format("matrix: {} values for a pattern of {} stored entries", r.values.size(),
                            r.pattern.columns.size() * bs * bs));
  if (!distribution) {
    Matrix m(r.pattern);
    m.set_values(r.values);
    return m;
  }
  const Distribution& d = *distribution;
  Matrix m(r.pattern, distribution);
  std::vector<Index> cols;
  std::size_t at = 0;
  for (Index b = 0; b < r.pattern.num_block_rows(); ++b) {
    cols.clear();
    for (Index c : r.pattern.row(b))
      for (std::size_t k = 0; k < bs; ++k) cols.push_back(c * static_cast<Index>(bs) + static_cast<Index>(k));
    for (std::size_t k = 0; k < bs; ++k, at += cols.size()) {
      if (!d.owns(b)) continue;  // its owner sets it
      const Index row[1] = {b * static_cast<Index>(bs) + static_cast<Index>(k)};
      m.add(row, cols, std::span<const double>(r.values).subspan(at, cols.size()));
    }
  }
  m.finalize();
  return m;
}

}  // namespace perimorph::la
