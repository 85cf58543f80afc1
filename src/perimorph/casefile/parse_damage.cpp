// Case-file parsing of [material.damage] and [damage] (THEORY §6). Format in
// docs/case-file.md; conventions as in parse_case.cpp.

#include "perimorph/casefile/parse_damage.hpp"

#include "perimorph/casefile/choose_option.hpp"

#include <fmt/format.h>

namespace perimorph::casefile::detail {

void read_material_damage(const Table& material, MaterialSpec& m) {
  const auto t = material.table("damage");
  if (!t) return;
  t->check_keys({"k0", "k1", "d_c"});
  DamageSpec& d = m.damage;
  d.enabled = true;
  d.where = t->where();
  if (m.kind != MaterialKind::isotropic)
    t->fail(
        "the damage law of THEORY §6 is isotropic (σ = (1 − d) C₀ : ε with Y = ½ ε : C₀ : ε); this material "
        "is not: give an isotropic material (E, nu), or remove [material.damage]");
  const Value k0 = t->require("k0", "the damage-force threshold at onset, k0 >= 0 (stress units, as E)");
  d.k0 = k0.number();
  if (!(d.k0 >= 0))
    k0.fail(fmt::format("must be >= 0, got {}: damage starts where Y = ½ ε : C₀ : ε exceeds k0", d.k0));
  const Value k1 = t->require("k1", "the hardening modulus of the threshold, k1 > 0 (stress units, as E)");
  d.k1 = k1.number();
  if (!(d.k1 > 0))
    k1.fail(fmt::format(
        "must be > 0, got {}: the threshold k0 + k1 d must rise with d (k1 <= 0 would let d jump to d_c "
        "at onset)",
        d.k1));
  if (auto v = t->get("d_c")) {
    d.d_c = v->number();
    if (!(d.d_c > 0 && d.d_c <= 1))
      v->fail(fmt::format(
          "must lie in (0, 1], got {}: the critical damage where the local model stops (1: the local "
          "damage model alone)",
          d.d_c));
  }
}

void read_damage(const Table& root, CaseConfig& c) {
  for (const MaterialSpec& m : c.materials)
    if (m.damage.enabled && c.nonlocal.enabled && m.damage.d_c >= 1.0)
      fail(m.damage.where,
           "d_c = 1 with [nonlocal]: the non-local model takes over the residual branch (1 − d_c) C₀, "
           "which would have no stiffness; give d_c < 1 (the damage where the local model stops), or "
           "remove [nonlocal] for the local damage model alone");
  const auto t = root.table("damage");
  if (!t) return;
  t->check_keys({"solver", "tolerance", "max_iterations"});
  c.damage.where = t->where();
  if (!c.has_damage())
    t->fail(
        "[damage] sets the damage iterations, but no material has a [material.damage] table; add one "
        "(k0, k1, d_c) after its [[material]], or remove [damage]");
  if (auto v = t->get("tolerance")) {
    c.damage.tolerance = v->number();
    if (!(c.damage.tolerance > 0 && c.damage.tolerance < 1))
      v->fail(fmt::format(
          "must lie in (0, 1), got {}: an increment's damage has converged when no quadrature point's d "
          "would change by more than tolerance",
          c.damage.tolerance));
  }
  if (auto v = t->get("max_iterations")) c.damage.max_iterations = v->integer(1, 1000000);
  static const Options<DamageSolver> solvers{{"secant", DamageSolver::secant},
                                             {"newton", DamageSolver::newton}};
  if (auto v = t->get("solver")) c.damage.solver = choose(*v, solvers, "solver");
}

}  // namespace perimorph::casefile::detail
