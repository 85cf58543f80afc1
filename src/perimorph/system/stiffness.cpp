#include "perimorph/system/stiffness.hpp"

#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/piece_distribution.hpp"

#include <chrono>

namespace perimorph::system {

namespace {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point a) {
  return std::chrono::duration<double>(clock::now() - a).count();
}

/// Adds the flagged cells (`cells`, one flag per cell; all if empty) and the
/// cell pairs with a flagged cell, found in the flagged cells' graph rows, into
/// out.K, and finalizes it; the pairs' blocks are those of the whole assembly
/// (NonlocalOptions::min_over_processes).
void assemble_into(AssembledStiffness& out, const setup::Discretization& model,
                   const bonds::BrokenBonds* broken, std::span<const double> damage,
                   std::span<const char> cells) {
  auto flagged = [&](Index c) { return cells.empty() || cells[static_cast<std::size_t>(c)] != 0; };
  auto t0 = clock::now();
  const bool damaged = model.damage && !damage.empty();
  const fem::ConstitutiveField C = damaged ? setup::damaged_stiffness(model.stiffness, *model.damage, damage)
                                           : fem::ConstitutiveField(0, 0, 0);
  assembly::assemble_elasticity(model.local_space(), damaged ? C : model.stiffness, out.K,
                                [&](Index c) { return model.has_local_stiffness(c) && flagged(c); });
  out.local_seconds = seconds_since(t0);
  if (model.nonlocal) {
    t0 = clock::now();
    const assembly::NonlocalSpace space = model.nonlocal_space(broken);
    assembly::NonlocalOptions options;
    if (!cells.empty()) {
      options.rows = cells;
      options.min_over_processes = la::min_over_processes;
    }
    out.nonlocal = assembly::assemble_nonlocal(space, out.K, options);
    out.nonlocal_seconds = seconds_since(t0);
  }
  out.K.finalize();
}

}  // namespace

AssembledStiffness assemble_stiffness(const setup::Discretization& model, const bonds::BrokenBonds* broken,
                                      std::span<const double> damage) {
  const auto t0 = clock::now();
  const bonds::CellGraph* graph = model.nonlocal ? &model.nonlocal->graph : nullptr;
  AssembledStiffness out{la::Matrix(assembly::build_sparsity(model.dofmap, graph)), {}, 0.0, 0.0, 0.0};
  out.setup_seconds = seconds_since(t0);
  assemble_into(out, model, broken, damage, {});
  return out;
}

std::shared_ptr<const la::Distribution> distribution_of(const partition::DofLayout& layout, int part) {
  auto d = std::make_shared<la::Distribution>();
  d->to_distributed = layout.to_distributed;
  d->begin = layout.part_offsets[static_cast<std::size_t>(part)];
  d->end = layout.part_offsets[static_cast<std::size_t>(part) + 1];
  return d;
}

AssembledStiffness assemble_stiffness(const setup::Discretization& model,
                                      const std::shared_ptr<const la::Distribution>& distribution,
                                      const bonds::BrokenBonds* broken, std::span<const double> damage) {
  const auto t0 = clock::now();
  const bonds::CellGraph* graph = model.nonlocal ? &model.nonlocal->graph : nullptr;
  const auto owned = [&](Index n) { return distribution->owns(n); };
  // The owned rows' pattern only (la::Matrix reads no other).
  AssembledStiffness out{
      la::Matrix(assembly::build_sparsity(model.dofmap, graph, owned), distribution), {}, 0.0, 0.0, 0.0};
  // Owner computes: the cells and pairs touching an owned node, their owned rows kept.
  const std::vector<char> touching = partition::cells_touching(model.dofmap, owned);
  for (Index c = 0; c < model.mesh.num_cells() && !model.computed_cells.empty(); ++c)
    PERIMORPH_ASSERT(
        !touching[static_cast<std::size_t>(c)] || model.computed_cells[static_cast<std::size_t>(c)],
        "a process assembles a cell whose morphed C it did not compute");
  out.setup_seconds = seconds_since(t0);
  assemble_into(out, model, broken, damage, touching);
  return out;
}

AssembledStiffness assemble_stiffness_over_processes(const setup::Discretization& model,
                                                     const bonds::BrokenBonds* broken,
                                                     std::span<const double> damage) {
  if (la::world_size() == 1) return assemble_stiffness(model, broken, damage);
  return assemble_stiffness(model, distribution_over_processes(model), broken, damage);
}

std::shared_ptr<const la::Distribution> distribution_over_processes(const setup::Discretization& model) {
  if (la::world_size() == 1) return nullptr;
  if (model.piece) return piece_distribution(model.piece->dofs);
  const partition::Partition p = partition::coordinate_bisection(model.mesh, la::world_size());
  return distribution_of(partition::dof_numbering(model.dofmap, p), la::world_rank());
}

}  // namespace perimorph::system
