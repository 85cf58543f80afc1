#include "perimorph/system/whole_numbering.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace perimorph::system {

WholeNumbering::WholeNumbering(const partition::PieceDofs& dofs, int block_size, la::Onto onto)
    : block_size_(block_size), onto_(onto), owned_(dofs.owned) {
  std::vector<double> mine;
  for (std::size_t n = 0; n < dofs.key.size(); ++n)
    if (dofs.owned[n]) mine.push_back(static_cast<double>(dofs.key[n]));  // exact below 2^53
  const std::vector<double> keys = la::gather_onto(mine, onto);           // in distributed order
  sorted_keys_.resize(keys.size());
  std::transform(keys.begin(), keys.end(), sorted_keys_.begin(),
                 [](double k) { return static_cast<Index>(k); });
  std::sort(sorted_keys_.begin(), sorted_keys_.end());
  PERIMORPH_ASSERT(std::adjacent_find(sorted_keys_.begin(), sorted_keys_.end()) == sorted_keys_.end(),
                   "a dof node owned twice");
  of_distributed_.resize(keys.size());
  for (std::size_t d = 0; d < keys.size(); ++d) of_distributed_[d] = rank_of(static_cast<Index>(keys[d]));
  if (onto != la::Onto::every_process) return;
  of_local_.resize(dofs.key.size());
  local_of_whole_.assign(sorted_keys_.size(), -1);
  for (std::size_t n = 0; n < dofs.key.size(); ++n) {
    of_local_[n] = rank_of(dofs.key[n]);
    local_of_whole_[static_cast<std::size_t>(of_local_[n])] = static_cast<Index>(n);
  }
}

Index WholeNumbering::rank_of(Index key) const {
  const auto it = std::lower_bound(sorted_keys_.begin(), sorted_keys_.end(), key);
  PERIMORPH_ASSERT(it != sorted_keys_.end() && *it == key, "a dof node no process owns");
  return static_cast<Index>(it - sorted_keys_.begin());
}

Index WholeNumbering::whole_of_name(Index name) const {
  return rank_of(name / block_size_) * block_size_ + name % block_size_;
}

Index WholeNumbering::name_of_whole(Index whole_dof) const {
  PERIMORPH_ASSERT(whole_dof >= 0 && whole_dof < whole_dofs(),
                   "WholeNumbering: a dof beyond the whole model");
  return sorted_keys_[static_cast<std::size_t>(whole_dof / block_size_)] * block_size_ +
         whole_dof % block_size_;
}

void WholeNumbering::check_piece_side() const {
  PERIMORPH_ASSERT(onto_ == la::Onto::every_process,
                   "WholeNumbering: the piece's side of a numbering held on process 0 alone");
}

std::vector<double> WholeNumbering::whole(std::span<const double> owned) const {
  // Every process's owned values, in its range: the distributed order.
  const std::vector<double> all = la::gather_onto(std::vector<double>(owned.begin(), owned.end()), onto_);
  if (!la::receives(onto_)) return {};
  PERIMORPH_ASSERT(static_cast<Index>(all.size()) == whole_dofs(), "WholeNumbering: not the owned values");
  std::vector<double> out(all.size());
  const auto bs = static_cast<std::size_t>(block_size_);
  for (std::size_t d = 0; d < of_distributed_.size(); ++d)
    for (std::size_t k = 0; k < bs; ++k)
      out[static_cast<std::size_t>(of_distributed_[d]) * bs + k] = all[d * bs + k];
  return out;
}

std::vector<double> WholeNumbering::piece_of(std::span<const double> whole) const {
  check_piece_side();
  PERIMORPH_ASSERT(static_cast<Index>(whole.size()) == whole_dofs(), "WholeNumbering: not a whole vector");
  const auto bs = static_cast<std::size_t>(block_size_);
  std::vector<double> out(of_local_.size() * bs);
  for (std::size_t n = 0; n < of_local_.size(); ++n)
    for (std::size_t k = 0; k < bs; ++k)
      out[n * bs + k] = whole[static_cast<std::size_t>(of_local_[n]) * bs + k];
  return out;
}

std::vector<double> WholeNumbering::owned_of(std::span<const double> whole) const {
  check_piece_side();
  PERIMORPH_ASSERT(static_cast<Index>(whole.size()) == whole_dofs(), "WholeNumbering: not a whole vector");
  const auto bs = static_cast<std::size_t>(block_size_);
  std::vector<double> out;
  for (std::size_t n = 0; n < of_local_.size(); ++n)
    if (owned_[n])
      for (std::size_t k = 0; k < bs; ++k)
        out.push_back(whole[static_cast<std::size_t>(of_local_[n]) * bs + k]);
  return out;
}

la::Matrix::Replicated WholeNumbering::whole(const la::Matrix& M) const {
  return M.replicated(of_distributed_, onto_);
}

la::Matrix::Replicated WholeNumbering::piece_of(const StoredMatrix& whole) const {
  check_piece_side();
  PERIMORPH_ASSERT(whole.row_offsets.size() == local_of_whole_.size() + 1,
                   "WholeNumbering: not a matrix of the whole model");
  const std::size_t bb =
      static_cast<std::size_t>(whole.block_size) * static_cast<std::size_t>(whole.block_size);
  PERIMORPH_ASSERT(whole.values.size() == whole.columns.size() * bb,
                   "WholeNumbering: values off the pattern");
  la::Matrix::Replicated out;
  out.pattern.block_size = whole.block_size;
  out.pattern.row_offsets.assign(1, 0);
  for (std::size_t n = 0; n < of_local_.size(); ++n) {
    if (owned_[n]) {
      const auto w = static_cast<std::size_t>(of_local_[n]);
      const Index first = whole.row_offsets[w], last = whole.row_offsets[w + 1];
      if (first < 0 || last < first || static_cast<std::size_t>(last) > whole.columns.size())
        throw InputError(fmt::format("the matrix row of dof node {} does not add up", w));
      for (auto k = static_cast<std::size_t>(first); k < static_cast<std::size_t>(last); ++k) {
        const Index c = whole.columns[k];
        if (c < 0 || static_cast<std::size_t>(c) >= local_of_whole_.size())
          throw InputError(fmt::format("the matrix row of dof node {} has a column out of range", w));
        const Index local = local_of_whole_[static_cast<std::size_t>(c)];
        if (local < 0)
          throw InputError(
              fmt::format("the matrix couples dof node {} to node {}, which this process's piece of the "
                          "model does not hold",
                          w, c));
        out.pattern.columns.push_back(local);  // ascending: local order is the whole order
      }
      whole.values.append_to(out.values, static_cast<std::size_t>(first) * bb,
                             static_cast<std::size_t>(last - first) * bb);
    }
    out.pattern.row_offsets.push_back(static_cast<Index>(out.pattern.columns.size()));
  }
  return out;
}

std::vector<Index> WholeNumbering::whole_dofs_of(std::span<const Index> piece_dofs) const {
  check_piece_side();
  std::vector<Index> out(piece_dofs.size());
  for (std::size_t k = 0; k < piece_dofs.size(); ++k)
    out[k] = of_local_[static_cast<std::size_t>(piece_dofs[k] / block_size_)] * block_size_ +
             piece_dofs[k] % block_size_;
  return out;
}

std::vector<Index> WholeNumbering::piece_dofs_of(std::span<const Index> whole_dofs) const {
  check_piece_side();
  std::vector<Index> out(whole_dofs.size());
  for (std::size_t k = 0; k < whole_dofs.size(); ++k) {
    const Index n = local_of_whole_[static_cast<std::size_t>(whole_dofs[k] / block_size_)];
    out[k] = n < 0 ? -1 : n * block_size_ + whole_dofs[k] % block_size_;
  }
  return out;
}

}  // namespace perimorph::system
