#include "perimorph/system/constrained_system.hpp"

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/shell_matrix.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace perimorph::system {

/// The matrix-free operators and what they read (a stable address for the
/// shells' callbacks).
struct ConstrainedSystem::MatrixFree {
  MatrixFree(MatrixFreeStiffness s, std::vector<char> prescribed, int dim)
      : stiffness(std::move(s)),
        fixed(std::move(prescribed)),
        masked(fixed.size()),
        K(shell(dim, [this](std::span<const double> x,
                            std::span<double> y) { stiffness.K.apply(x, y, stiffness.owned_cells); })),
        A(shell(dim, [this](std::span<const double> x, std::span<double> y) {
          for (std::size_t k = 0; k < masked.size(); ++k) masked[k] = fixed[k] ? 0.0 : x[k];
          stiffness.K.apply(masked, y, stiffness.owned_cells);
          for (std::size_t k = 0; k < masked.size(); ++k)
            if (fixed[k]) y[k] = x[k];
        })) {}
  /// A shell laid out as the preconditioner (spread over the processes with it, or serial).
  la::ShellMatrix shell(int dim, la::ShellMatrix::Apply apply) const {
    // Each process receives the bond reach of its cells (the halo), not all of x.
    if (const auto& d = stiffness.preconditioner.distribution())
      return la::ShellMatrix(d, dim, std::move(apply), stiffness.K.nodes_read(stiffness.owned_cells));
    return la::ShellMatrix(static_cast<Index>(fixed.size()), dim, std::move(apply));
  }
  MatrixFreeStiffness stiffness;  ///< its preconditioner constrained in place
  std::vector<char> fixed;        ///< 1 on the prescribed dofs
  std::vector<double> masked;     ///< scratch of A's product
  la::ShellMatrix K, A;
};

namespace {

/// A matrix of no rows: the K and A of a matrix-free system.
la::Matrix no_matrix(int dim) {
  assembly::SparsityPattern p;
  p.block_size = dim;
  p.row_offsets = {0};
  return la::Matrix(p);
}

}  // namespace

ConstrainedSystem::ConstrainedSystem(const setup::Discretization& model, la::Matrix K,
                                     setup::DirichletData bc, std::span<const double> F)
    : model_(model),
      K_(std::move(K)),
      A_(K_.duplicate()),
      bc_(std::move(bc)),
      rhs_unit_(K_.make_vector()),
      rhs_(K_.make_vector()) {
  owned_ = la::OwnedDofs(rhs_unit_.distribution(), model.dim(), model.dofmap.num_dofs());
  applied_force_ = owned_.of(F);
  constrain_rhs();
  initial_diagonal_ = A_.diagonal().at_owned(owned_);
}

ConstrainedSystem::ConstrainedSystem(const setup::Discretization& model, MatrixFreeStiffness K,
                                     setup::DirichletData bc, std::span<const double> F)
    : model_(model),
      K_(no_matrix(model.dim())),
      A_(no_matrix(model.dim())),
      bc_(std::move(bc)),
      rhs_unit_(K.preconditioner.make_vector()),
      rhs_(K.preconditioner.make_vector()) {
  const Index n = model.dofmap.num_dofs();
  owned_ = la::OwnedDofs(rhs_unit_.distribution(), model.dim(), n);
  applied_force_ = owned_.of(F);
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (Index d : bc_.dofs) fixed[static_cast<std::size_t>(d)] = 1;
  free_ = std::make_unique<MatrixFree>(std::move(K), std::move(fixed), model.dim());
  constrain_rhs();
  // The eliminated rows and columns of the preconditioner are zero blocks but
  // for their diagonal: dropped, so that its AMG sees only the coupling (on
  // one process: without_zero_blocks reads every row).
  la::Matrix& P = free_->stiffness.preconditioner;
  la::Vector g = make_vector(), scratch = make_vector();
  P.eliminate_dirichlet(bc_.dofs, g, scratch);
  if (!P.distribution()) P = P.without_zero_blocks();
  P.set_spd();
  initial_diagonal_ = P.diagonal().at_owned(owned_);
}

ConstrainedSystem::~ConstrainedSystem() = default;
ConstrainedSystem::ConstrainedSystem(ConstrainedSystem&&) noexcept = default;

la::Vector ConstrainedSystem::make_vector() const {
  return (free_ ? free_->stiffness.preconditioner : K_).make_vector();
}

void ConstrainedSystem::constrain_rhs() {
  la::Vector g = make_vector();
  PERIMORPH_ASSERT(bc_.dofs.size() == bc_.values.size() && std::is_sorted(bc_.dofs.begin(), bc_.dofs.end()) &&
                       std::adjacent_find(bc_.dofs.begin(), bc_.dofs.end()) == bc_.dofs.end(),
                   "the prescribed dofs must be sorted and unique");
  g.set_at(bc_.dofs, bc_.values);
  if (free_) {
    // b = F − K g on the free rows, g on the prescribed ones (as eliminate_dirichlet).
    la::Vector Kg = make_vector();
    free_->K.mult(g, Kg);
    std::vector<double> b = Kg.at_owned(owned_);
    for (std::size_t j = 0; j < b.size(); ++j) {
      const Index dof = owned_.dof(j);
      b[j] = free_->fixed[static_cast<std::size_t>(dof)] ? prescribed_value(dof) : applied_force_[j] - b[j];
    }
    rhs_unit_.assign_owned(owned_, b);
    return;
  }
  rhs_unit_.assign_owned(owned_, applied_force_);
  A_.eliminate_dirichlet(bc_.dofs, g, rhs_unit_);
  A_.set_spd();
}

double ConstrainedSystem::prescribed_value(Index dof) const {
  const auto at = std::lower_bound(bc_.dofs.begin(), bc_.dofs.end(), dof);
  if (at == bc_.dofs.end() || *at != dof) return std::numeric_limits<double>::quiet_NaN();
  return bc_.values[static_cast<std::size_t>(at - bc_.dofs.begin())];
}

void ConstrainedSystem::apply_K(const la::Vector& x, la::Vector& y) const {
  if (free_)
    free_->K.mult(x, y);
  else
    K_.mult(x, y);
}

void ConstrainedSystem::attach_solver() {
  const auto& spec = model_.config.solver;
  solver_ = std::make_unique<la::LinearSolver>(spec.rtol, spec.max_iterations);
  operator_changed();
}

void ConstrainedSystem::operator_changed() {
  if (!solver_) return;
  const la::NodeCoordinate at = model_.dofmap.node_coordinate_on(model_.mesh);
  if (free_)
    solver_->set_operators(free_->A, free_->stiffness.preconditioner, at, model_.dim());
  else
    solver_->set_operator(A_, at, model_.dim());
}

void ConstrainedSystem::downdate(std::span<const Index> dofs, std::span<const double> block) {
  PERIMORPH_ASSERT(!free_, "a matrix-free system cannot change (setup::check_matrix_free)");
  const std::size_t m = dofs.size();
  negative_.resize(m * m);
  for (std::size_t i = 0; i < m * m; ++i) negative_[i] = -block[i];
  K_.add(dofs, dofs, negative_);
  free_dofs_.assign(dofs.begin(), dofs.end());
  given_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    given_[i] = prescribed_value(dofs[i]);
    if (!std::isnan(given_[i])) free_dofs_[i] = -1;  // skipped by add
  }
  A_.add(free_dofs_, free_dofs_, negative_);
  for (std::size_t i = 0; i < m; ++i) {
    if (free_dofs_[i] < 0) continue;
    touched_.push_back(dofs[i]);
    double sum = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
      const double g = given_[j];
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

namespace {

/// Every process's `mine` (sorted) on every process, sorted (collective).
std::vector<Index> gathered_sorted(const std::vector<Index>& mine) {
  if (la::world_size() == 1) return mine;
  const std::vector<double> all = la::all_gather(std::vector<double>(mine.begin(), mine.end()));
  std::vector<Index> out(all.size());
  std::transform(all.begin(), all.end(), out.begin(), [](double v) { return static_cast<Index>(v); });
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<Index> ConstrainedSystem::without_stiffness(std::span<const Index> dofs) const {
  PERIMORPH_ASSERT(!free_, "a matrix-free system cannot change (setup::check_matrix_free)");
  PERIMORPH_ASSERT(std::is_sorted(dofs.begin(), dofs.end()), "without_stiffness takes sorted dofs");
  std::vector<Index> mine;
  std::vector<std::size_t> at;
  for (Index d : dofs)
    if (const std::ptrdiff_t j = owned_.position(d); j >= 0) {
      mine.push_back(d);
      at.push_back(static_cast<std::size_t>(j));
    }
  const std::vector<double> diag = A_.owned_diagonal_at(mine);
  std::vector<Index> out;
  for (std::size_t k = 0; k < mine.size(); ++k)
    if (std::abs(diag[k]) <= 1e-12 * std::abs(initial_diagonal_[at[k]]))
      out.push_back(setup::dof_name(model_, mine[k]));
  return gathered_sorted(out);
}

std::vector<Index> ConstrainedSystem::free_dofs_without_stiffness() const {
  std::vector<Index> free;
  for (std::size_t j = 0; j < owned_.size(); ++j)
    if (!prescribed(owned_.dof(j))) free.push_back(owned_.dof(j));
  return without_stiffness(free);
}

void ConstrainedSystem::hold(std::span<const Index> dofs, bool zero_rhs) {
  PERIMORPH_ASSERT(!free_, "a matrix-free system cannot change (setup::check_matrix_free)");
  if (dofs.empty()) return;
  for (Index d : dofs) {
    // A spread over processes keeps its owned rows only (Matrix::add).
    const std::ptrdiff_t j = owned_.position(d);
    if (j < 0) continue;
    const Index one[1] = {d};
    const double spring[1] = {initial_diagonal_[static_cast<std::size_t>(j)]};
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
  PERIMORPH_ASSERT(!free_, "a matrix-free system cannot change (setup::check_matrix_free)");
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
  if (free_) {
    // A's prescribed rows are the identity: started at their values, the
    // solution keeps them to round-off (started elsewhere, a residual relative
    // to ||b|| would let them err by the stiffness' scale).
    // Each process sets the rows it owns (no gather of u).
    std::vector<double> start(bc_.values.size());
    for (std::size_t k = 0; k < start.size(); ++k) start[k] = lambda * bc_.values[k];
    u.set_at(bc_.dofs, start);
  }
  return solver_->solve(rhs_, u);
}

}  // namespace perimorph::system
