// The adaptive step of a quasi-static run (THEORY §5, thesis §3.3.4): α grows
// with the crack, and the run moves to the grown model. Part of
// QuasiStaticRun (quasi_static_run.hpp).

#include "perimorph/core/error.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/run/next_piece_state.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/remodel.hpp"

#include <chrono>
#include <cmath>

namespace perimorph::run {

double QuasiStaticRun::strain_energy() {
  system_->apply_K(u_, internal_);
  const std::vector<double> a = owned(u_), b = owned(internal_);
  return add_over_dofs(0.0, [&](std::size_t j) { return 0.5 * a[j] * b[j]; });
}

bool QuasiStaticRun::grow_alpha() {
  adaptivity_->allow_growth();
  evolution::Proposal proposal;
  try {
    proposal = adaptivity_->inspect(state_, *system_);
  } catch (const Error& e) {
    stop_unsupported(e);
  }
  if (proposal.quiet()) return false;
  const evolution::Effect effect = adaptivity_->apply(state_, *system_);
  PERIMORPH_ASSERT(effect == evolution::Effect::rebuild, "the adaptive step must rebuild");
  rebuild();
  return true;
}

bool QuasiStaticRun::adapt() {
  const auto& spec = disc_->config.adaptivity;
  if (!adaptivity_ || spec.update != casefile::AdaptivityUpdate::increment || !spec.redo) return false;
  if (rec_.break_iterations == disc_->config.fracture.max_iterations) stop_unsettled(0);
  if (!grow_alpha()) return false;
  ++rec_.break_iterations;  // the next solve is at fixed load
  bonds_failed_in_pass_ = false;
  return true;
}

void QuasiStaticRun::adapt_for_next() {
  const auto& spec = disc_->config.adaptivity;
  if (!adaptivity_ || spec.update != casefile::AdaptivityUpdate::increment || spec.redo) return;
  if (!grow_alpha()) return;
  // The next increment's elastic step starts from the last state on the new model.
  u_prev_ = owned_dofs_.of(state_.u);
  la::Vector Ku = system_->make_vector();
  u_.assign_replicated(state_.u);
  system_->apply_K(u_, Ku);
  fint_prev_ = owned(Ku);
}

void QuasiStaticRun::rebuild() {
  const auto t0 = std::chrono::steady_clock::now();
  progress_->phase("remodel");
  const double before_energy = strain_energy();
  std::unique_ptr<setup::Discretization> next;
  std::vector<double> u_prev_next;
  if (disc_->piece) {
    next = std::make_unique<setup::Discretization>(setup::rebuild_piece_for_alpha(*disc_, state_.alpha));
    u_prev_next = move_to_piece(*next);
  } else {
    // Carried over whole (from the owners where a process holds its halo only).
    const std::vector<double> u_whole = whole(state_.u), u_prev_whole = owned_dofs_.whole(u_prev_);
    next = std::make_unique<setup::Discretization>(setup::rebuild_for_alpha(*disc_, state_.alpha));
    system::Remodelled r =
        system::remodel(*system_, *disc_, *next, &state_.failed, setup::build_dirichlet(*next),
                        setup::build_external_force(*next), state_.history);
    state_.u = system::transfer_dof_vector(*disc_, *next, u_whole);
    u_prev_next = system::transfer_dof_vector(*disc_, *next, u_prev_whole);
    system_ = std::move(r.system);
  }
  system_->attach_solver();
  setup_.sets = setup::reaction_sets(*next);
  disc_ = next.get();
  owned_ = std::move(next);  // the previous discretization (and its system) are gone now
  u_ = system_->make_vector();
  internal_ = system_->make_vector();
  u_.assign_replicated(state_.u);  // on a piece, the owned dofs only are carried (move_to_piece)
  choose_gather();
  if (disc_->piece) state_.u = gather(u_);
  u_prev_ = owned_dofs_.of(u_prev_next);
  fint_prev_.assign(owned_dofs_.size(), 0.0);  // recomputed where it is used next (record, adapt_for_next)
  state_.energy.model_change += strain_energy() - before_energy;
  for (auto& component : setup_.components) {
    try {
      component->rebind(*disc_, state_, *system_);
    } catch (const Error& e) {
      stop_unsupported(e);
    }
  }
  system_->operator_changed();
  remodel_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> QuasiStaticRun::move_to_piece(const setup::Discretization& next) {
  // The next piece holds this one's cells and the cells its grown halo
  // reaches: the state of the new cells comes from their parts' processes
  // (next_piece_state); u, the last recorded u and the reference diagonal go
  // across at the next piece's owned dofs, every cell using one being in
  // both pieces (transfer_dof_vector), and from their owners to its halo.
  const std::vector<double> u_prev = gather_owned(u_prev_);
  const std::vector<double> reference = gather_owned(system_->reference_diagonal());
  evolution::RunState next_state = next_piece_state(*disc_, next, state_);
  system::Remodelled r =
      system::remodel_piece(*disc_, reference, next, &next_state.failed, setup::build_dirichlet(next),
                            setup::build_external_force(next), next_state.history);
  next_state.u = system::transfer_dof_vector(*disc_, next, state_.u);
  for (double v : r.system->owned_dofs().of(next_state.u))
    PERIMORPH_ASSERT(std::isfinite(v), "move_to_piece: an owned dof the last piece did not read");
  state_ = std::move(next_state);
  system_ = std::move(r.system);
  return system::transfer_dof_vector(*disc_, next, u_prev);
}

std::vector<double> QuasiStaticRun::gather_owned(std::span<const double> owned_values) {
  la::Vector x = system_->make_vector();
  x.assign_owned(owned_dofs_, owned_values);
  return gather(x);
}

}  // namespace perimorph::run
