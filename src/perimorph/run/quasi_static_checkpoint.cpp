// Checkpoint and restart of a quasi-static run (run/checkpoint.hpp). Part of
// QuasiStaticRun (quasi_static_run.hpp).

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/checkpoint.hpp"
#include "perimorph/io/atomic_file.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/checkpoint.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/run/whole_state.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <utility>

namespace perimorph::run {

std::string basename_of(const casefile::CaseConfig& config) {
  if (!config.output.basename.empty()) return config.output.basename;
  return std::filesystem::path(config.path).stem().string();
}

void QuasiStaticRun::checkpoint_if_due() {
  if (checkpoint_every_ > 0 && state_.increment % checkpoint_every_ == 0) save_checkpoint();
}

void QuasiStaticRun::save_checkpoint() {
  // Process 0 writes it; every process takes part in gathering the
  // distributed system and the vectors a process holds at its halo only,
  // in the whole model's numbers (on a piece, run::WholeState's, onto
  // process 0 alone: the others write nothing and hold nothing whole).
  const std::optional<WholeState> whole_of =
      disc_->piece ? std::optional<WholeState>(std::in_place, *disc_, la::Onto::process_zero) : std::nullopt;
  std::optional<io::AtomicFile> file;
  la::on_process_zero([&] { file.emplace(checkpoint_path_); });
  core::BinaryWriter out([&](std::string_view bytes) {
    if (file) file->write(bytes);
  });
  write_header(out, disc_->config);
  evolution::save_alpha(state_.alpha, out);
  out.tag("run");
  out.put<double>(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  out.put<std::uint64_t>(balls_written_);
  out.put<double>(remodel_seconds_);
  out.put<int>(summary_.preconditioner_rebuilds);
  out.put<int>(summary_.direct_fallback_solves);
  out.put<int>(summary_.most_null_pivots);
  if (whole_of) {
    out.put_vector(whole_of->numbering().whole(u_prev_));
    out.put_vector(whole_of->numbering().whole(fint_prev_));
    evolution::save_state(whole_of->whole(state_, owned_dofs_.of(state_.u)), out);
  } else {
    out.put_vector(owned_dofs_.whole(u_prev_));
    out.put_vector(owned_dofs_.whole(fint_prev_));
    state_.u = whole(state_.u);
    evolution::save_state(state_, out);
  }
  out.tag("output");
  const OutputPosition at = output_->position();
  for (std::size_t rows : {at.rows, at.alpha_rows, at.failure_rows, at.failed_bond_rows})
    out.put<std::uint64_t>(rows);
  out.put<std::uint64_t>(at.pvd.size());
  for (const auto& e : at.pvd) {
    out.put<double>(e.time);
    out.put_string(e.file);
  }
  for (const auto& component : setup_.components) {
    out.tag(component->name());
    component->save(out);
  }
  system_->save(out, whole_of ? &whole_of->numbering() : nullptr);
  out.tag("end");
  out.flush();
  la::on_process_zero([&] { file->commit(); });
  summary_.checkpoint_path = checkpoint_path_;
  summary_.checkpoint_increment = state_.increment;
}

void QuasiStaticRun::restore(const std::string& path, const RunOptions& /*options*/) {
  progress_->phase("restart");
  const core::MappedFile file = read_checkpoint_file(path);
  core::BinaryReader in(file.bytes(), path);
  const auto& config = disc_->config;
  check_header(in, config);

  // The model of the checkpoint: the case's, or rebuilt for a grown α.
  alpha::AlphaField alpha = evolution::restore_alpha(in);
  if (alpha.region_list().size() != state_.alpha.region_list().size() ||
      alpha.constant_value() != state_.alpha.constant_value()) {
    if (disc_->piece && !disc_->source)
      in.fail("a grown alpha, where the case has no [adaptivity] (a piece without its part to rebuild from)");
    owned_ =
        std::make_unique<setup::Discretization>(disc_->piece ? setup::rebuild_piece_for_alpha(*disc_, alpha)
                                                             : setup::rebuild_for_alpha(*disc_, alpha));
    disc_ = owned_.get();
  }
  // On a piece, the checkpoint's vectors are the whole model's (save_checkpoint).
  const std::optional<WholeState> whole_of = disc_->piece ? std::optional<WholeState>(*disc_) : std::nullopt;
  const Index n = whole_of ? whole_of->numbering().whole_dofs() : disc_->dofmap.num_dofs();

  in.expect("run");
  const double elapsed = in.get<double>();
  start_ -=
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(elapsed));
  balls_written_ = in.get<std::uint64_t>();
  remodel_seconds_ = in.get<double>();
  summary_.preconditioner_rebuilds = in.get<int>();
  summary_.direct_fallback_solves = in.get<int>();
  summary_.most_null_pivots = in.get<int>();
  u_prev_ = in.get_vector<double>();
  fint_prev_ = in.get_vector<double>();
  if (u_prev_.size() != static_cast<std::size_t>(n) || fint_prev_.size() != u_prev_.size())
    in.fail(fmt::format("vectors of {} values where the model has {} dofs", u_prev_.size(), n));
  state_ = evolution::RunState(*disc_);
  if (whole_of) {
    u_prev_ = whole_of->numbering().piece_of(u_prev_);  // the constructor keeps their owned entries
    fint_prev_ = whole_of->numbering().piece_of(fint_prev_);
    evolution::RunState whole_state = whole_of->empty_whole();
    evolution::restore_state(whole_state, in);
    state_ = whole_of->piece_of(whole_state);
  } else {
    evolution::restore_state(state_, in);
  }
  if (state_.increment < 1 || state_.increment > increments())
    in.fail(fmt::format("increment {} of a case with {}", state_.increment, increments()));
  summary_.restarted_after = state_.increment;

  in.expect("output");
  OutputPosition at;
  for (std::size_t* rows : {&at.rows, &at.alpha_rows, &at.failure_rows, &at.failed_bond_rows})
    *rows = in.get<std::uint64_t>();
  const auto entries = in.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < entries; ++k) {
    const double time = in.get<double>();
    at.pvd.push_back({time, in.get_string()});
  }

  setup_ = prepare_run(*disc_);
  find_components();
  for (const auto& component : setup_.components) {
    in.expect(component->name());
    component->restore(*disc_, in);
  }
  system_ = system::ConstrainedSystem::restored(*disc_, std::move(setup_.bc), setup_.F, in,
                                                whole_of ? &whole_of->numbering() : nullptr);
  in.expect("end");
  if (!in.at_end()) in.fail("bytes after its end");

  u_ = system_->make_vector();
  internal_ = system_->make_vector();
  u_.assign_replicated(state_.u);
  for (const auto& s : setup_.sets) summary_.reaction_names.push_back(s.name);
  output_ = std::make_unique<RunOutput>(*disc_, summary_.output_directory, basename_of(config),
                                        summary_.reaction_names, &at);
  summary_.checkpoint_path = path;
  summary_.checkpoint_increment = state_.increment;
  progress_->message(
      fmt::format("continuing after increment {} of {} from {}", state_.increment, increments(), path));
}

}  // namespace perimorph::run
