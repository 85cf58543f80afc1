// Case-file parsing of [adaptivity]: the non-local zone that grows with the
// crack (THEORY §5, thesis §3.3.4) and the predictor that grows it before
// bonds fail. Format in docs/case-file.md; conventions as in parse_case.cpp.

#include "perimorph/casefile/parse_adaptivity.hpp"

#include "perimorph/casefile/choose_option.hpp"

#include <fmt/format.h>

#include <string_view>

namespace perimorph::casefile::detail {

namespace {

const Options<AdaptivityUpdate> kUpdates{{"increment", AdaptivityUpdate::increment},
                                         {"iteration", AdaptivityUpdate::iteration}};

double length(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x >= 0)) v.fail(fmt::format("must be a length >= 0 ({}), got {}", what, x));
  return x;
}

}  // namespace

void read_adaptivity(const Table& root, CaseConfig& c) {
  const auto t = root.table("adaptivity");
  if (!t) return;
  t->check_keys({"enabled", "core", "transition", "profile", "update", "redo", "predictor", "theta"});
  AdaptivitySpec& a = c.adaptivity;
  a.where = t->where();
  a.enabled = true;
  if (auto v = t->get("enabled")) a.enabled = v->boolean();
  bool hands_over = false;  // THEORY §6: α grows from the critical damage
  for (const MaterialSpec& m : c.materials)
    hands_over = hands_over || (m.damage.enabled && m.damage.d_c < 1.0);
  if (!c.nonlocal.enabled || !(c.fracture.enabled || hands_over))
    t->fail(fmt::format(
        "an adaptive non-local zone needs [nonlocal] (the model α blends in) and [fracture] (the failed "
        "bonds it follows) or a material whose damage hands over to it ([material.damage] with d_c < 1); "
        "this case has {}",
        !c.nonlocal.enabled ? "no [nonlocal]" : "no [fracture] and no such material"));
  if (c.alpha.regions.empty() && c.alpha.value > 0.0)
    t->fail(fmt::format(
        "α cannot grow from the constant [alpha] value = {} ({}): adaptivity adds balls of α = 1 to α ≡ 0 or "
        "to [[alpha.region]] entries; remove [alpha] value, or give regions",
        c.alpha.value, c.alpha.where.describe()));
  if (auto v = t->get("core"))
    a.core = length(*v,
                    "α = 1 out to the cell size plus core around a cell with a failed bond; default the "
                    "horizon");
  if (auto v = t->get("transition"))
    a.transition =
        length(*v, "the width over which α falls from 1 to 0 beyond the core; default the horizon");
  if (auto v = t->get("profile")) a.profile = choose(*v, profile_options(), "profile");
  if (auto v = t->get("update")) a.update = choose(*v, kUpdates, "update");
  if (auto v = t->get("redo")) a.redo = v->boolean();
  if (auto v = t->get("predictor")) {
    a.predictor = v->boolean();
    if (a.predictor && !c.fracture.enabled)
      v->fail(
          "the predictor compares the strain with theta · s_crit: it needs [fracture]; add it, or remove "
          "predictor");
  }
  const auto theta = t->get("theta");
  if (theta) {
    if (!a.predictor)
      theta->fail(
          "applies only with predictor = true (α grows where the strain stretches some direction beyond "
          "theta · s_crit); add predictor = true, or remove theta");
    a.theta = theta->number();
    if (!(a.theta > 0 && a.theta <= 1))
      theta->fail(fmt::format(
          "must lie in (0, 1], got {}: a cell gets its ball of α = 1 when its strain stretches some "
          "direction beyond theta · s_crit (smaller: earlier)",
          a.theta));
  }
}

}  // namespace perimorph::casefile::detail
