#pragma once
// The one interface of what changes the model during a run (THEORY §5, §6):
// bond failure, the support of parts cut free, and later adaptive α and
// local damage. After each solve the run loop asks every component, in order,
// to inspect the state and propose a change, then to apply it; it solves
// again until every component is quiet (run/static_run.cpp). A component
// keeps its proposal between inspect and apply; inspect changes nothing.

#include "perimorph/evolution/run_state.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <cstddef>
#include <string_view>

namespace perimorph::core {
class BinaryWriter;
class BinaryReader;
}  // namespace perimorph::core

namespace perimorph::evolution {

/// What an applied proposal changed in the constrained system, from the
/// cheapest to the dearest update:
enum class Effect {
  none,        ///< the state only
  downdate,    ///< blocks subtracted from K and A (ConstrainedSystem::downdate)
  hold,        ///< springs on A's diagonal (ConstrainedSystem::hold)
  reassemble,  ///< the stiffness of some cells recomputed
  rebuild,     ///< the state's α grew: the run rebuilds the discretization and the system, then
               ///< re-solves before any other component inspects (Component::rebind)
};

/// A proposed change: how many things it changes (bonds, dofs, cells); 0 is
/// quiet.
struct Proposal {
  std::size_t changes = 0;
  bool quiet() const { return changes == 0; }
};

class Component {
 public:
  virtual ~Component() = default;
  /// For messages ("bond failure").
  virtual std::string_view name() const = 0;
  /// Looks at the state after a solve (and at the system's last changes) and
  /// keeps a proposal. Throws Error when the state has no quasi-static
  /// continuation (e.g. a part cut free under unbalanced loads).
  virtual Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) = 0;
  /// Applies the proposal of the last inspect to the state and the system.
  /// The caller hands the changed operator to the solver once all components
  /// have applied (ConstrainedSystem::operator_changed).
  virtual Effect apply(RunState& state, system::ConstrainedSystem& system) = 0;
  /// The run has moved to a rebuilt discretization (α grew: a component's
  /// apply returned Effect::rebuild) with a new system and the state carried
  /// over (u on the new dofs, held dofs empty): take them. The default keeps
  /// nothing that depends on the discretization.
  virtual void rebind(const setup::Discretization& /*disc*/, RunState& /*state*/,
                      system::ConstrainedSystem& /*system*/) {}
  /// Writes what the component keeps from one increment to the next (a
  /// checkpoint, run/checkpoint.hpp; called between increments, with no
  /// proposal pending). The default keeps nothing.
  virtual void save(core::BinaryWriter& /*out*/) const {}
  /// Takes back what save wrote, on a run restored onto `disc` whose state and
  /// system are restored as they were (nothing to hold or reassemble). A
  /// component that keeps `disc` or anything else overrides it.
  virtual void restore(const setup::Discretization& /*disc*/, core::BinaryReader& /*in*/) {}
};

}  // namespace perimorph::evolution
