// How a quasi-static run stops before its end (docs/output.md, "A run that
// stops"): a stop request, a state with no quasi-static continuation, an
// increment that does not settle, numbers that are not finite. Each names the
// increment and what is kept on disk. Part of QuasiStaticRun
// (quasi_static_run.hpp).

#include "perimorph/core/error.hpp"
#include "perimorph/core/interrupt.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/quasi_static_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

namespace perimorph::run {

namespace {

/// "[fracture] max_iterations in case.toml (now 7)" or "(default 10000)".
std::string max_iterations_source(const casefile::FractureSpec& spec) {
  const bool given = spec.max_iterations != casefile::FractureSpec{}.max_iterations;
  return fmt::format("[fracture] max_iterations in {} ({} {})", spec.where.file, given ? "now" : "default",
                     spec.max_iterations);
}

}  // namespace

std::string QuasiStaticRun::kept() const {
  const int done = state_.increment - 1;
  std::string out =
      done == 0 ? fmt::format("No increment completed (output directory {})", summary_.output_directory)
                : fmt::format("Results of increments 1..{} are in {}", done, summary_.output_directory);
  if (!summary_.checkpoint_path.empty())
    out += fmt::format(". The checkpoint of increment {} is {}: continue with perimorph run {} --restart {}",
                       summary_.checkpoint_increment, summary_.checkpoint_path, disc_->config.path,
                       summary_.checkpoint_path);
  return out;
}

void QuasiStaticRun::stop_unsettled(std::size_t over) {
  rec_.bonds_broken_increment = bonds_failed() - failed_before_;
  rec_.dissipated_increment = state_.energy.dissipated - dissipated_before_;
  record(true);
  progress_->finish();
  const int i = state_.increment;
  const auto& output = *output_;
  const std::string files = output.writes_vtu()
                                ? fmt::format("{} and its row in {}", output.vtu_path(i), output.csv_path())
                                : fmt::format("its row in {} ([output] vtu = false)", output.csv_path());
  throw RunStopped(fmt::format(
      "increment {}/{} (load factor {}): bonds still fail after {} bond-breaking iterations: {} "
      "bonds "
      "failed in this increment and {} more are over the criterion now. The crack is running "
      "unstably at this load (or the iterations do not settle). Use smaller load increments or "
      "raise {}. The state after the last iteration is kept as increment {}: {}; every iteration "
      "is in {}. {}",
      i, increments(), state_.load_factor, rec_.break_iterations, rec_.bonds_broken_increment, over,
      max_iterations_source(disc_->config.fracture), i, files, output.failures_csv_path(), kept()));
}

void QuasiStaticRun::stop_if_asked() {
  // Every process of a distributed run stops before the same solve: a signal
  // seen by one of them (mpirun passes it to all, each in its own time) stops all.
  const int signal = la::max_over_processes(stop_requested());
  if (signal == 0) return;
  progress_->finish();
  const int i = state_.increment;
  // Before the first solve of an increment the state is still that of the
  // last one: it can be kept as a checkpoint.
  std::string saved;
  if (rec_.break_iterations == 0 && i > 1 && summary_.checkpoint_increment != i - 1) {
    const double lambda = state_.load_factor;
    state_.increment = i - 1;
    state_.load_factor = disc_->config.loading.factors[static_cast<std::size_t>(i - 2)];
    try {
      save_checkpoint();
    } catch (const Error& e) {
      saved = fmt::format(" The checkpoint could not be written: {}.", e.what());
    }
    state_.increment = i;
    state_.load_factor = lambda;
  }
  throw Interrupted(
      fmt::format("{} received: the run stops in increment {}/{} (load factor {}) before its solve "
                  "{}; that increment is not written. {}{}",
                  signal_name(signal), i, increments(), state_.load_factor, rec_.break_iterations + 1, kept(),
                  saved),
      signal);
}

void QuasiStaticRun::stop_unsupported(const std::exception& e) {
  progress_->finish();
  const int i = state_.increment;
  write_vtu(i);
  throw RunStopped(
      fmt::format("increment {}/{} (load factor {}), iteration {}: {}. The displacement "
                  "before this iteration is written as increment {} ({}); {}",
                  i, increments(), state_.load_factor, rec_.break_iterations, e.what(), i,
                  output_->writes_vtu() ? output_->vtu_path(i) : "no VTU: [output] vtu = false", kept()));
}

void QuasiStaticRun::stop_if_not_finite() {
  static constexpr const char* axes = "xyz";
  std::vector<std::pair<std::string, double>> values{{"strain_energy", rec_.strain_energy},
                                                     {"external_work", rec_.external_work}};
  for (std::size_t k = 0; k < rec_.reactions.size(); ++k)
    for (int d = 0; d < disc_->dim(); ++d)
      values.emplace_back(fmt::format("reaction_{}_{}", summary_.reaction_names[k], axes[d]),
                          rec_.reactions[k][d]);
  if (fracture_ || damage_)
    values.insert(values.end(), {{"dissipated_energy", rec_.dissipated},
                                 {"overshoot_energy", rec_.overshoot},
                                 {"damage_dissipated_energy", rec_.damage_dissipated},
                                 {"released_energy", rec_.released}});
  if (adaptivity_) values.emplace_back("model_energy_change", rec_.model_change);
  std::vector<std::string> bad;
  for (const auto& [name, v] : values)
    if (!std::isfinite(v)) bad.push_back(fmt::format("{} = {}", name, v));
  if (bad.empty()) return;
  progress_->finish();
  const int i = state_.increment;
  throw SolverError(fmt::format(
      "increment {}/{} (load factor {}): {} (CSV columns) although the solution is finite: numbers "
      "beyond double precision (the loads or the moduli of the case, e.g. a prescribed displacement of "
      "1e200). The increment is written as it came out, its CSV row {}; the run stops here",
      i, increments(), state_.load_factor, fmt::join(bad, ", "),
      output_->writes_vtu() ? fmt::format("and {}", output_->vtu_path(i)) : "(no VTU)"));
}

void QuasiStaticRun::stop_damage_unsettled() {
  record(true);
  progress_->finish();
  const int i = state_.increment;
  const int n = disc_->config.damage.max_iterations;
  throw RunStopped(fmt::format(
      "increment {}/{} (load factor {}): the damage still changes by {:.3g} (tolerance {:g}) after {} "
      "consecutive fixed-point iterations: the local damage does not settle at this load (a snap-back, or a "
      "load step too large for the secant iteration). Use smaller load increments, or raise [damage] "
      "max_iterations (now {}) or tolerance. The state after the last iteration is kept as increment "
      "{} ({}). {}",
      i, increments(), state_.load_factor, damage_->largest_change(), disc_->config.damage.tolerance, n, n, i,
      output_->writes_vtu() ? output_->vtu_path(i) : output_->csv_path(), kept()));
}

}  // namespace perimorph::run
