#include "perimorph/system/stiffness.hpp"

#include "perimorph/assembly/sparsity.hpp"

#include <chrono>

namespace perimorph::system {

AssembledStiffness assemble_stiffness(const setup::Discretization& model, const bonds::BrokenBonds* broken,
                                      std::span<const double> damage) {
  using clock = std::chrono::steady_clock;
  auto seconds = [](clock::time_point a) { return std::chrono::duration<double>(clock::now() - a).count(); };
  auto t0 = clock::now();
  const bonds::CellGraph* graph = model.nonlocal ? &model.nonlocal->graph : nullptr;
  AssembledStiffness out{la::Matrix(assembly::build_sparsity(model.dofmap, graph)), {}, 0.0, 0.0, 0.0};
  out.setup_seconds = seconds(t0);
  t0 = clock::now();
  const bool damaged = model.damage && !damage.empty();
  const fem::ConstitutiveField C = damaged ? setup::damaged_stiffness(model.stiffness, *model.damage, damage)
                                           : fem::ConstitutiveField(0, 0, 0);
  assembly::assemble_elasticity(model.local_space(), damaged ? C : model.stiffness, out.K,
                                [&](Index c) { return model.has_local_stiffness(c); });
  out.local_seconds = seconds(t0);
  if (model.nonlocal) {
    t0 = clock::now();
    const assembly::NonlocalSpace space = model.nonlocal_space(broken);
    out.nonlocal = assembly::assemble_nonlocal(space, out.K);
    out.nonlocal_seconds = seconds(t0);
  }
  out.K.finalize();
  return out;
}

}  // namespace perimorph::system
