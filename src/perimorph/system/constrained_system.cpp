#include "perimorph/system/constrained_system.hpp"

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>

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
  ++downdates_;
  std::sort(last_downdated_.begin(), last_downdated_.end());
  last_downdated_.erase(std::unique(last_downdated_.begin(), last_downdated_.end()), last_downdated_.end());
  return last_downdated_;
}

void ConstrainedSystem::set_reference_diagonal(std::vector<double> diagonal) {
  PERIMORPH_ASSERT(diagonal.size() == initial_diagonal_.size(), "reference diagonal of the wrong size");
  initial_diagonal_ = std::move(diagonal);
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

namespace {

/// Hands each (square) block the assembly adds to ConstrainedSystem::downdate,
/// with its sign: +1 subtracts it, −1 adds it.
class DowndateInserter final : public assembly::MatrixInserter {
 public:
  DowndateInserter(ConstrainedSystem& system, double sign) : system_(system), sign_(sign) {}
  void add(std::span<const Index> rows, std::span<const Index> cols,
           std::span<const double> values) override {
    PERIMORPH_ASSERT(std::equal(rows.begin(), rows.end(), cols.begin(), cols.end()),
                     "reassemble takes square blocks over one set of dofs");
    block_.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) block_[k] = sign_ * values[k];
    system_.downdate(rows, block_);
  }

 private:
  ConstrainedSystem& system_;  ///< non-owning
  double sign_;
  std::vector<double> block_;
};

/// Adds (sign −1) or subtracts (sign +1) the stiffness `disc` assembles for
/// the cells flagged in `in`.
void downdate_cells(ConstrainedSystem& system, const setup::Discretization& disc, const std::vector<char>& in,
                    const bonds::BrokenBonds* failed, double sign) {
  DowndateInserter inserter(system, sign);
  auto flagged = [&](Index c) { return in[static_cast<std::size_t>(c)] != 0; };
  assembly::assemble_elasticity(disc.local_space(), disc.stiffness, inserter,
                                [&](Index c) { return flagged(c) && disc.has_local_stiffness(c); });
  if (!disc.nonlocal) return;
  const assembly::NonlocalSpace space = disc.nonlocal_space(failed);
  assembly::NonlocalOptions options;
  options.include_pair = [&](Index e, Index f) { return flagged(e) || flagged(f); };
  assembly::assemble_nonlocal(space, inserter, options);
}

}  // namespace

void ConstrainedSystem::reassemble(const setup::Discretization& before, const setup::Discretization& after,
                                   std::span<const Index> cells, const bonds::BrokenBonds* failed) {
  const Index ncells = before.mesh.num_cells();
  std::vector<char> in(static_cast<std::size_t>(ncells), 0);
  for (Index c : cells) in[static_cast<std::size_t>(c)] = 1;
  if (after.dofmap.num_dofs() != before.dofmap.num_dofs())
    throw Error(
        fmt::format("reassemble: the dof map changed ({} → {} dofs, cells switched between CG and "
                    "DG): build a new constrained system",
                    before.dofmap.num_dofs(), after.dofmap.num_dofs()));
  for (Index c : cells) {
    const auto a = before.dofmap.cell_nodes(c), b = after.dofmap.cell_nodes(c);
    if (!std::equal(a.begin(), a.end(), b.begin(), b.end()))
      throw Error(
          fmt::format("reassemble: cell {} has other dofs in the new discretization (CG ↔ DG): build "
                      "a new constrained system",
                      c));
  }
  if (after.nonlocal) {
    PERIMORPH_ASSERT(before.nonlocal.has_value(), "reassemble: a non-local model from a local one");
    const auto& old_graph = before.nonlocal->graph;
    const auto& new_graph = after.nonlocal->graph;
    const auto& amax = after.nonlocal->points.cell_alpha_max;
    for (Index e = 0; e < ncells; ++e)
      for (Index f : new_graph.row(e)) {
        if (f < e || !(in[static_cast<std::size_t>(e)] || in[static_cast<std::size_t>(f)])) continue;
        if (amax[static_cast<std::size_t>(e)] + amax[static_cast<std::size_t>(f)] <= 0.0) continue;
        const auto row = old_graph.row(e);
        if (std::find(row.begin(), row.end(), f) == row.end())
          throw Error(
              fmt::format("reassemble: cells {} and {} interact in the new discretization but not in "
                          "the matrix's pattern: build a new constrained system",
                          e, f));
      }
  }
  downdate_cells(*this, before, in, failed, 1.0);
  downdate_cells(*this, after, in, failed, -1.0);
  finish_downdate();
  operator_changed();
}

la::SolveReport ConstrainedSystem::solve(double lambda, la::Vector& u) {
  PERIMORPH_ASSERT(solver_ != nullptr, "ConstrainedSystem::solve before attach_solver");
  rhs_.set_all(0.0);
  rhs_.axpy(lambda, rhs_unit_);
  return solver_->solve(rhs_, u);
}

}  // namespace perimorph::system
