#include "perimorph/run/static_run.hpp"

#include "perimorph/evolution/adaptivity.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/local_damage.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/run/window_part.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <filesystem>
#include <limits>

namespace perimorph::run {

std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options) {
  if (!options.output_directory.empty()) return options.output_directory;
  const std::filesystem::path dir(config.output.directory);
  if (dir.is_absolute()) return dir.string();
  return (std::filesystem::path(config.path).parent_path() / dir).lexically_normal().string();
}

setup::Discretization process_part(const casefile::CaseConfig& config, const setup::PhaseCallback& on_phase) {
  // Each process computes the morphed C and the CG/DG flags of the cells near its part only.
  return setup::build_discretization(config, on_phase,
                                     {la::world_size(), la::world_rank(), [](std::vector<char> flags) {
                                        return la::union_over_processes(std::move(flags));
                                      }});
}

namespace {

/// This process's part built on the whole mesh (process_part), and the part of every cell.
std::pair<setup::Discretization, std::vector<int>> whole_mesh_part(const casefile::CaseConfig& config,
                                                                   const setup::PhaseCallback& on_phase) {
  setup::Discretization part = process_part(config, on_phase);
  std::vector<int> owner = partition::coordinate_bisection(part.mesh, la::world_size()).owner;
  return {std::move(part), std::move(owner)};
}

}  // namespace

setup::Discretization process_model(const casefile::CaseConfig& config,
                                    const setup::PhaseCallback& on_phase) {
  const int processes = la::world_size(), rank = la::world_rank();
  if (processes == 1) return process_part(config, on_phase);
  auto [part, owner] =
      setup::has_windows(config) ? window_part(config, on_phase) : whole_mesh_part(config, on_phase);
  if (on_phase) on_phase("piece");
  setup::Discretization piece = setup::cut_to_piece(part, owner, rank, la::any_over_processes);
  // A rebuild for a grown α starts from the part (setup::rebuild_piece_for_alpha).
  if (config.adaptivity.enabled) piece.source = setup::keep_source(std::move(part), std::move(owner));
  return piece;
}

RunSetup prepare_run(const setup::Discretization& disc) {
  RunSetup setup;
  setup.bc = setup::build_dirichlet(disc);
  setup.F = setup::build_external_force(disc);
  setup.sets = setup::reaction_sets(disc);
  const bool fracture = disc.config.fracture.enabled, damage = disc.damage.has_value();
  // The predictor must see a solve before bond failure does (adaptivity.hpp);
  // bonds fail only where the damage is critical, judged after its update.
  if (disc.config.adaptivity.enabled)
    setup.components.push_back(std::make_unique<evolution::Adaptivity>(
        disc, fracture ? setup::critical_stretch(disc) : std::numeric_limits<double>::quiet_NaN()));
  if (damage) setup.components.push_back(std::make_unique<evolution::LocalDamage>(disc));
  if (fracture) setup.components.push_back(std::make_unique<evolution::BondFailure>(disc));
  if (fracture || damage) setup.components.push_back(std::make_unique<evolution::PartSupport>(disc));
  return setup;
}

RunSummary run_static(const setup::Discretization& disc, const RunOptions& options) {
  QuasiStaticRun run(disc, options);
  for (int i = run.first_increment(); i < run.increments(); ++i) {
    run.apply_load(i);
    run.solve();
    // THEORY §5–§6: update the damage, break the bonds over the criterion (and
    // hold what they cut loose), re-equilibrate at fixed load, until no
    // component changes the model.
    while (run.evolve()) run.solve();
    // THEORY §5–§6, adaptive zone: α grows from the increment's failed bonds
    // and critical damage; the increment settles again on the grown model
    // ([adaptivity] redo).
    while (run.adapt()) {
      run.solve();
      while (run.evolve()) run.solve();
    }
    run.write_increment();
    run.adapt_for_next();
    run.checkpoint_if_due();
  }
  return run.finish();
}

}  // namespace perimorph::run
