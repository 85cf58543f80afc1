#include "perimorph/system/constrained_system.hpp"

#include "perimorph/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace perimorph::system {

ConstrainedSystem::ConstrainedSystem(const setup::Discretization& model, la::Matrix K,
                                     setup::DirichletData bc, std::span<const double> F)
    : model_(model),
      K_(std::move(K)),
      A_(K_.duplicate()),
      bc_(std::move(bc)),
      applied_force_(F.begin(), F.end()),
      rhs_unit_(model.dofmap.num_dofs(), model.dim()),
      rhs_(model.dofmap.num_dofs(), model.dim()) {
  const Index n = model.dofmap.num_dofs();
  la::Vector g(n, model.dim());
  std::vector<double> gv(static_cast<std::size_t>(n), 0.0);
  prescribed_.assign(static_cast<std::size_t>(n), std::nan(""));
  for (std::size_t k = 0; k < bc_.dofs.size(); ++k) {
    gv[static_cast<std::size_t>(bc_.dofs[k])] = bc_.values[k];
    prescribed_[static_cast<std::size_t>(bc_.dofs[k])] = bc_.values[k];
  }
  g.assign(gv);
  rhs_unit_.assign(F);
  A_.eliminate_dirichlet(bc_.dofs, g, rhs_unit_);
  A_.set_spd();
  initial_diagonal_ = A_.diagonal();
}

void ConstrainedSystem::attach_solver() {
  const auto& spec = model_.config.solver;
  solver_ = std::make_unique<la::LinearSolver>(spec.rtol, spec.max_iterations);
  operator_changed();
}

void ConstrainedSystem::operator_changed() {
  if (solver_) solver_->set_operator(A_, model_.dofmap.node_coordinates(), model_.dim());
}

void ConstrainedSystem::downdate(std::span<const Index> dofs, std::span<const double> block) {
  const std::size_t m = dofs.size();
  negative_.resize(m * m);
  for (std::size_t i = 0; i < m * m; ++i) negative_[i] = -block[i];
  K_.add(dofs, dofs, negative_);
  free_dofs_.assign(dofs.begin(), dofs.end());
  for (std::size_t i = 0; i < m; ++i)
    if (prescribed(dofs[i])) free_dofs_[i] = -1;  // skipped by add
  A_.add(free_dofs_, free_dofs_, negative_);
  for (std::size_t i = 0; i < m; ++i) {
    if (free_dofs_[i] < 0) continue;
    touched_.push_back(dofs[i]);
    double sum = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
      const double g = prescribed_[static_cast<std::size_t>(dofs[j])];
      if (!std::isnan(g)) sum += block[i * m + j] * g;
    }
    if (sum != 0.0) {
      rhs_at_.push_back(dofs[i]);
      rhs_add_.push_back(sum);
    }
  }
}

const std::vector<Index>& ConstrainedSystem::finish_downdate() {
  K_.finalize();
  A_.finalize();
  rhs_unit_.add_at(rhs_at_, rhs_add_);
  rhs_at_.clear();
  rhs_add_.clear();
  last_downdated_.swap(touched_);
  touched_.clear();
  std::sort(last_downdated_.begin(), last_downdated_.end());
  last_downdated_.erase(std::unique(last_downdated_.begin(), last_downdated_.end()), last_downdated_.end());
  return last_downdated_;
}

std::vector<Index> ConstrainedSystem::without_stiffness(std::span<const Index> dofs) const {
  const std::vector<double> diag = A_.diagonal_at(dofs);
  std::vector<Index> out;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const double d0 = initial_diagonal_[static_cast<std::size_t>(dofs[k])];
    if (std::abs(diag[k]) <= 1e-12 * std::abs(d0)) out.push_back(dofs[k]);
  }
  return out;
}

void ConstrainedSystem::hold(std::span<const Index> dofs, bool zero_rhs) {
  if (dofs.empty()) return;
  for (Index d : dofs) {
    const Index one[1] = {d};
    const double spring[1] = {initial_diagonal_[static_cast<std::size_t>(d)]};
    A_.add(one, one, spring);
  }
  A_.finalize();
  if (zero_rhs) rhs_unit_.set_at(dofs, 0.0);
}

la::SolveReport ConstrainedSystem::solve(double lambda, la::Vector& u) {
  PERIMORPH_ASSERT(solver_ != nullptr, "ConstrainedSystem::solve before attach_solver");
  rhs_.set_all(0.0);
  rhs_.axpy(lambda, rhs_unit_);
  return solver_->solve(rhs_, u);
}

}  // namespace perimorph::system
