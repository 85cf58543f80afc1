#include "perimorph/la/owned_dofs.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <algorithm>

namespace perimorph::la {

OwnedDofs::OwnedDofs(const Distribution* distribution, int block_size, Index num_dofs)
    : every_(distribution == nullptr), num_dofs_(num_dofs) {
  if (every_) return;
  PERIMORPH_ASSERT(distribution->num_nodes() * block_size == num_dofs, "OwnedDofs: wrong number of dofs");
  dofs_.reserve(static_cast<std::size_t>(distribution->owned_nodes() * block_size));
  for (Index n = 0; n < distribution->num_nodes(); ++n)
    if (distribution->owns(n))
      for (Index k = 0; k < block_size; ++k) dofs_.push_back(n * block_size + k);
}

std::ptrdiff_t OwnedDofs::position(Index dof) const {
  if (every_) return dof;
  const auto at = std::lower_bound(dofs_.begin(), dofs_.end(), dof);
  return at != dofs_.end() && *at == dof ? at - dofs_.begin() : -1;
}

std::vector<double> OwnedDofs::of(std::span<const double> whole) const {
  PERIMORPH_ASSERT(static_cast<Index>(whole.size()) == num_dofs_, "OwnedDofs: not a whole-length array");
  if (every_) return {whole.begin(), whole.end()};
  std::vector<double> out(dofs_.size());
  for (std::size_t j = 0; j < dofs_.size(); ++j) out[j] = whole[static_cast<std::size_t>(dofs_[j])];
  return out;
}

std::vector<double> OwnedDofs::at(std::span<const double> owned, std::span<const Index> dofs) const {
  PERIMORPH_ASSERT(owned.size() == size(), "OwnedDofs::at: not an array at the owned dofs");
  std::vector<double> out(dofs.size(), -0.0);
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const std::ptrdiff_t j = position(dofs[k]);
    if (j >= 0) out[k] = owned[static_cast<std::size_t>(j)];
  }
  return every_ ? out : from_owners(std::move(out));
}

std::vector<double> OwnedDofs::whole(std::span<const double> owned) const {
  PERIMORPH_ASSERT(owned.size() == size(), "OwnedDofs::whole: not an array at the owned dofs");
  if (every_) return {owned.begin(), owned.end()};
  std::vector<double> out(static_cast<std::size_t>(num_dofs_), -0.0);
  for (std::size_t j = 0; j < dofs_.size(); ++j) out[static_cast<std::size_t>(dofs_[j])] = owned[j];
  return from_owners(std::move(out));
}

double OwnedDofs::sum(double init, const std::function<double(std::size_t)>& term) const {
  const std::size_t n = size();
  if (every_) {
    for (std::size_t j = 0; j < n; ++j) init += term(j);
    return init;
  }
  double mine = 0.0;
  for (std::size_t j = 0; j < n; ++j) mine += term(j);
  return init + sum_over_processes({mine})[0];
}

}  // namespace perimorph::la
