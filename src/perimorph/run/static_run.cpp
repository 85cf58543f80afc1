#include "perimorph/run/static_run.hpp"

#include "perimorph/evolution/adaptivity.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/setup/critical_stretch.hpp"

#include <filesystem>

namespace perimorph::run {

std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options) {
  if (!options.output_directory.empty()) return options.output_directory;
  const std::filesystem::path dir(config.output.directory);
  if (dir.is_absolute()) return dir.string();
  return (std::filesystem::path(config.path).parent_path() / dir).lexically_normal().string();
}

RunSetup prepare_run(const setup::Discretization& disc) {
  RunSetup setup;
  setup.bc = setup::build_dirichlet(disc);
  setup.F = setup::build_external_force(disc);
  setup.sets = setup::reaction_sets(disc);
  if (disc.config.fracture.enabled) {
    // The predictor must see a solve before bond failure does (adaptivity.hpp).
    if (disc.config.adaptivity.enabled)
      setup.components.push_back(
          std::make_unique<evolution::Adaptivity>(disc, setup::critical_stretch(disc)));
    setup.components.push_back(std::make_unique<evolution::BondFailure>(disc));
    setup.components.push_back(std::make_unique<evolution::PartSupport>(disc));
  }
  return setup;
}

RunSummary run_static(const setup::Discretization& disc, const RunOptions& options) {
  QuasiStaticRun run(disc, options);
  for (int i = 0; i < run.increments(); ++i) {
    run.apply_load(i);
    run.solve();
    // THEORY §5: break the bonds over the criterion (and hold what they cut
    // loose), re-equilibrate at fixed load, until no component changes the model.
    while (run.evolve()) run.solve();
    // THEORY §5, adaptive zone: α grows from the increment's failed bonds;
    // the increment settles again on the grown model ([adaptivity] redo).
    while (run.adapt()) {
      run.solve();
      while (run.evolve()) run.solve();
    }
    run.write_increment();
    run.adapt_for_next();
  }
  return run.finish();
}

}  // namespace perimorph::run
