#include "perimorph/driver/constrained_system.hpp"

#include "perimorph/core/error.hpp"

namespace perimorph::driver {

ConstrainedSystem::ConstrainedSystem(const Model& model, la::Matrix K, DirichletData bc,
                                     std::span<const double> F)
    : model_(model),
      K_(std::move(K)),
      A_(K_.duplicate()),
      bc_(std::move(bc)),
      rhs_unit_(model.dofmap.num_dofs(), model.dim()),
      rhs_(model.dofmap.num_dofs(), model.dim()) {
  const Index n = model.dofmap.num_dofs();
  la::Vector g(n, model.dim());
  std::vector<double> gv(static_cast<std::size_t>(n), 0.0);
  for (std::size_t k = 0; k < bc_.dofs.size(); ++k) gv[static_cast<std::size_t>(bc_.dofs[k])] = bc_.values[k];
  g.assign(gv);
  rhs_unit_.assign(F);
  A_.eliminate_dirichlet(bc_.dofs, g, rhs_unit_);
  A_.set_spd();
}

void ConstrainedSystem::attach_solver() {
  const auto& spec = model_.config.solver;
  solver_ = std::make_unique<la::LinearSolver>(spec.rtol, spec.max_iterations);
  operator_changed();
}

void ConstrainedSystem::operator_changed() {
  if (solver_) solver_->set_operator(A_, model_.dofmap.node_coordinates(), model_.dim());
}

la::SolveReport ConstrainedSystem::solve(double lambda, la::Vector& u) {
  PERIMORPH_ASSERT(solver_ != nullptr, "ConstrainedSystem::solve before attach_solver");
  rhs_.set_all(0.0);
  rhs_.axpy(lambda, rhs_unit_);
  return solver_->solve(rhs_, u);
}

}  // namespace perimorph::driver
