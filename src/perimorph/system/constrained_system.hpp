#pragma once
// The linear system of a run (THEORY §4–5): K, unconstrained (reactions,
// energies and work read it); A, K with the prescribed dofs eliminated
// (symmetric positive definite); rhs_unit, the right-hand side at load factor
// 1 (the applied forces, and the prescribed values moved over); the Dirichlet
// data; and the solver on A. The load enters linearly: the system at load
// factor λ is A u = λ rhs_unit. Bond failure changes it in place through
// downdate and hold (BondFailure::apply), then calls operator_changed().
// A matrix-free system (system/matrix_free_stiffness.hpp) has no K or A: it
// applies them (apply_K, the solve) and supports none of the changes.

#include "perimorph/core/error.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/matrix_free_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

namespace perimorph::bonds {
class BrokenBonds;
}
namespace perimorph::core {
class BinaryWriter;
class BinaryReader;
}  // namespace perimorph::core

namespace perimorph::system {

class WholeNumbering;

class ConstrainedSystem {
 public:
  /// Constrains `K` (assembled, finalized) by `bc`, with the external force
  /// `F` at load factor 1. No solver yet (attach_solver).
  ConstrainedSystem(const setup::Discretization& model, la::Matrix K, setup::DirichletData bc,
                    std::span<const double> F);
  /// The same with K applied without a matrix: A x is K x on the free rows and
  /// columns and x on the prescribed ones (eliminate_dirichlet's convention),
  /// solved by the case's Krylov method preconditioned from the short-horizon
  /// matrix, constrained likewise.
  ConstrainedSystem(const setup::Discretization& model, MatrixFreeStiffness K, setup::DirichletData bc,
                    std::span<const double> F);
  ~ConstrainedSystem();
  ConstrainedSystem(ConstrainedSystem&&) noexcept;
  ConstrainedSystem(const ConstrainedSystem&) = delete;
  ConstrainedSystem& operator=(const ConstrainedSystem&) = delete;

  /// A system as `save` wrote it (a checkpoint, run/checkpoint.hpp): K, A,
  /// rhs_unit, the reference diagonal and the downdate count exactly as they
  /// were (every downdate, spring and reassembly since the first assembly is
  /// in them), on `model` with its constraints `bc` and loads `F`. No solver
  /// yet. Throws Error (naming the checkpoint) if they do not fit `model`.
  /// On a piece of the model they are in the whole model's numbering: `whole`
  /// if given (the piece's), else built (collective).
  static std::unique_ptr<ConstrainedSystem> restored(const setup::Discretization& model,
                                                     setup::DirichletData bc, std::span<const double> F,
                                                     core::BinaryReader& in,
                                                     const WholeNumbering* whole = nullptr);
  void save(core::BinaryWriter& out, const WholeNumbering* whole = nullptr) const;

  /// A dof vector laid out as the system's (spread over the processes as K
  /// is, or serial), zero.
  la::Vector make_vector() const;
  /// The case's solver ([solver] rtol, max_iterations; PETSc options from the
  /// options database) on A, with the rigid-body near-null space of the nodes.
  void attach_solver();
  /// Solves A u = λ rhs_unit (u: the initial guess in, the solution out).
  /// Throws SolverError (la::LinearSolver). Requires attach_solver.
  la::SolveReport solve(double lambda, la::Vector& u);
  /// y ← K x (the unconstrained stiffness: internal forces, reactions, energies).
  void apply_K(const la::Vector& x, la::Vector& y) const;
  /// True for a matrix-free system (no K(), A(), downdate, hold or reassemble).
  bool matrix_free() const { return free_ != nullptr; }
  /// The attached solver (null before attach_solver).
  const la::LinearSolver* solver() const { return solver_.get(); }
  /// Lets the attached solver fall back to a direct solve that holds null
  /// pivots when a Krylov solve fails (la::LinearSolver::allow_direct_fallback):
  /// for a matrix that bond failures may have left singular.
  void allow_direct_fallback() {
    if (solver_) solver_->allow_direct_fallback(true);
  }
  /// A has changed (a downdate or held dofs): the solver takes it again.
  void operator_changed();

  /// Subtracts a bond's block (m × m, row-major, over `dofs`) from K, and from
  /// A on its free rows and columns; the block's prescribed columns move to
  /// the right-hand side, rhs_unit[i] += B_ij g_j (free i, prescribed j, g the
  /// prescribed values at load factor 1). Call finish_downdate after the last.
  void downdate(std::span<const Index> dofs, std::span<const double> block);
  /// Finalizes K and A after downdates; returns the free dofs they touched
  /// (sorted, unique), also kept as last_downdated().
  const std::vector<Index>& finish_downdate();
  /// The free dofs touched by the downdates that the last finish_downdate
  /// closed (sorted, unique).
  const std::vector<Index>& last_downdated() const { return last_downdated_; }
  /// How many finish_downdate calls there have been (a new last_downdated()).
  std::size_t downdate_count() const { return downdates_; }
  /// Of `dofs` (sorted), those whose diagonal of A has fallen to round-off
  /// (1e-12) of its value before any downdate: dofs left with no stiffness,
  /// sorted. Spread over processes, each looks at the dofs it owns and the
  /// answers are gathered (collective: the same `dofs` on every process, the
  /// same answer). On a piece of the model (setup::cut_to_piece) each process
  /// passes its own dofs (its owned ones among them are looked at) and the
  /// answer is in the dofs' names (setup::dof_name), sorted.
  std::vector<Index> without_stiffness(std::span<const Index> dofs) const;
  /// The same for every free dof, without listing them whole.
  std::vector<Index> free_dofs_without_stiffness() const;
  /// Holds each dof by a spring of its stiffness before any downdate on A's
  /// diagonal (K unchanged: the spring carries no force); with `zero_rhs` the
  /// right-hand side there is set to 0. A is finalized.
  void hold(std::span<const Index> dofs, bool zero_rhs);
  /// Replaces the stiffness of `cells` in place (α changed there, THEORY
  /// §3–§4): subtracts what `before` assembles for them (the local stiffness
  /// of each cell of `cells`, the bonds of every cell pair with a cell in
  /// `cells`) and adds what `after` assembles, on K and, as downdate does, on
  /// A's free rows and columns with the prescribed columns moved to the
  /// right-hand side; `failed` bonds are left out of both. `cells` must hold
  /// every cell whose points' α, morphed C or bonds differ between the two.
  /// Requires the same dof map (a CG ↔ DG switch changes the dofs: build a new
  /// system then) and every cell pair of `after` touching `cells` in
  /// `before`'s graph (the matrix pattern); throws Error otherwise. Finalizes
  /// K and A; the reference diagonal of without_stiffness and hold stays the
  /// first assembly's. Then operator_changed().
  void reassemble(const setup::Discretization& before, const setup::Discretization& after,
                  std::span<const Index> cells, const bonds::BrokenBonds* failed = nullptr);
  /// The dofs this process owns (every dof on one process): the arrays below
  /// named "at the owned dofs" hold one value per owned dof, in its order.
  const la::OwnedDofs& owned_dofs() const { return owned_; }
  /// The diagonal of A before any downdate (the reference of
  /// without_stiffness and the springs of hold), at the owned dofs.
  const std::vector<double>& reference_diagonal() const { return initial_diagonal_; }
  /// It at any `dofs` (collective where spread: la::OwnedDofs::at).
  std::vector<double> reference_diagonal_at(std::span<const Index> dofs) const {
    return owned_.at(initial_diagonal_, dofs);
  }
  /// Replaces it, at the owned dofs (a system remodelled from another carries
  /// the first one's reference over, system/remodel.hpp).
  void set_reference_diagonal(std::vector<double> diagonal);
  /// True if the dof is prescribed.
  bool prescribed(Index dof) const { return std::binary_search(bc_.dofs.begin(), bc_.dofs.end(), dof); }
  /// The dof's prescribed value at load factor 1, NaN if it is free.
  double prescribed_value(Index dof) const;

  la::Matrix& K() { return assembled(K_); }
  const la::Matrix& K() const { return assembled(K_); }
  la::Matrix& A() { return assembled(A_); }
  const la::Matrix& A() const { return assembled(A_); }
  la::Vector& rhs_unit() { return rhs_unit_; }
  const la::Vector& rhs_unit() const { return rhs_unit_; }
  const setup::DirichletData& bc() const { return bc_; }
  /// The external force at load factor 1 (before the constraints), at the
  /// owned dofs.
  const std::vector<double>& applied_force() const { return applied_force_; }
  /// It at any `dofs` (collective where spread: la::OwnedDofs::at).
  std::vector<double> applied_force_at(std::span<const Index> dofs) const {
    return owned_.at(applied_force_, dofs);
  }

 private:
  struct MatrixFree;
  template <class M>
  M& assembled(M& matrix) const {
    PERIMORPH_ASSERT(!free_, "a matrix-free system has no assembled matrix");
    return matrix;
  }
  /// rhs_unit from bc_ and applied_force_.
  void constrain_rhs();

  const setup::Discretization& model_;
  std::unique_ptr<MatrixFree> free_;  ///< matrix-free only
  la::Matrix K_, A_;
  setup::DirichletData bc_;  ///< the prescribed dofs (sorted, unique) and values at load factor 1
  la::OwnedDofs owned_;
  std::vector<double> applied_force_;  ///< at the owned dofs
  la::Vector rhs_unit_, rhs_;
  std::unique_ptr<la::LinearSolver> solver_;
  std::vector<double> initial_diagonal_;  ///< of A, before any downdate, at the owned dofs
  // Collected by downdate, applied by finish_downdate.
  std::vector<Index> touched_, rhs_at_, free_dofs_;
  std::vector<Index> last_downdated_;
  std::size_t downdates_ = 0;
  std::vector<double> rhs_add_, negative_;
  std::vector<double> given_;  ///< downdate: the block's prescribed values (NaN: free)
};

}  // namespace perimorph::system
