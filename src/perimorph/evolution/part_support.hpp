#pragma once
// The support of what bond failure cuts loose (THEORY §5), the second
// evolution component (component.hpp). After bonds fail, a free dof may be
// left with no stiffness at all (its row of A is zero: the matrix turns
// singular), and a cell pair that lost its last intact bond may have cut a
// part free of every support (floating_parts.hpp). Such a dof is held at zero
// by a spring of its initial stiffness, such a part by springs on a minimal
// set of its dofs (statically determinate, so they carry no force when the
// part's loads balance), and a motion inside one cell that no intact bond
// resists (cell_mechanisms.hpp) likewise. Effect::hold. The dofs it finds
// and records are named by setup::dof_name, so that every process of a run
// on pieces of the model finds and holds the same ones (each the dofs of its
// piece among them).

#include "perimorph/evolution/component.hpp"
#include "perimorph/setup/discretization.hpp"

#include <vector>

namespace perimorph::evolution {

class PartSupport final : public Component {
 public:
  explicit PartSupport(const setup::Discretization& disc) : disc_(&disc) {}

  std::string_view name() const override { return "support of parts cut free"; }
  /// Looks at the bonds failed and the damage grown since the last inspect:
  /// the free dofs the system's last downdate left with no stiffness, and, if one of their cell
  /// pairs has no intact bond left, the parts cut free; and the free motions
  /// inside the cells of the failed bonds. Throws Error for a
  /// detached dof under an applied force, or a part whose applied forces do
  /// work on a free rigid-body mode: there is no quasi-static equilibrium.
  /// The proposal counts the dofs to hold.
  Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) override;
  /// Holds the proposed dofs (ConstrainedSystem::hold: detached dofs with a
  /// zero right-hand side, then the pins of the parts and of the cells) and
  /// records them in the state (held dofs, detached dofs, floating parts,
  /// cell mechanisms). Effect::hold.
  Effect apply(RunState& state, system::ConstrainedSystem& system) override;
  /// Holds again, on the new system, what was held: every free dof with no
  /// stiffness, and (when bonds have failed) the parts cut free and the free
  /// motions inside the cells of failed bonds, found anew on the whole model;
  /// the state's held dofs become these (counts kept).
  void rebind(const setup::Discretization& disc, RunState& state, system::ConstrainedSystem& system) override;
  /// The held dofs and parts found so far, how far the failures were read.
  void save(core::BinaryWriter& out) const override;
  void restore(const setup::Discretization& disc, core::BinaryReader& in) override;

 private:
  const setup::Discretization* disc_;  ///< non-owning: the run's current discretization
  std::size_t seen_ = 0;               ///< failed bonds already looked at (RunState::failed_over_model)
  std::size_t downdates_seen_ = 0;     ///< ConstrainedSystem::downdate_count() at the last inspect
  std::vector<Index> detached_, pins_, cell_pins_;
  int parts_ = 0;
  std::size_t mechanisms_ = 0;  ///< cells with a free motion (cell_mechanisms.hpp) found by the last inspect
};

}  // namespace perimorph::evolution
