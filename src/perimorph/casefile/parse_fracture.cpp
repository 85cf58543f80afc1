// Case-file parsing of [fracture]: bond failure by critical stretch in the
// non-local model (THEORY §5). Format in docs/case-file.md; conventions as in
// parse_case.cpp.

#include "perimorph/casefile/parse_fracture.hpp"

#include "perimorph/casefile/suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

const std::vector<std::pair<std::string, BreakRule>> kRules{{"all", BreakRule::all},
                                                            {"fraction", BreakRule::fraction}};

constexpr const char* kCriterion =
    "s_crit = ... (the critical bond stretch, dimensionless, > 0) or G_c = ... (the critical energy "
    "release rate, energy per area, > 0; s_crit then follows from the bulk closed form of THEORY §5)";

BreakRule rule_of(const Value& v) {
  const std::string given = v.string();
  std::vector<std::string> names, quoted;
  for (const auto& [name, rule] : kRules) {
    if (name == given) return rule;
    names.push_back(name);
    quoted.push_back(fmt::format("{:?}", name));
  }
  const std::string close = closest_match(given, names);
  v.fail(fmt::format(
      "unknown rule {:?}; {}allowed: {} (\"all\": every bond over the criterion breaks in one iteration; "
      "\"fraction\": only those with s/s_crit >= fraction × the largest s/s_crit)",
      given, close.empty() ? "" : fmt::format("did you mean {:?}? ", close), fmt::join(quoted, ", ")));
}

double positive(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x > 0)) v.fail(fmt::format("must be positive ({}), got {}", what, x));
  return x;
}

}  // namespace

void read_fracture(const Table& root, CaseConfig& c) {
  const auto t = root.table("fracture");
  if (!t) return;
  if (!c.nonlocal.enabled)
    t->fail(
        "bond failure needs a [nonlocal] section: bonds exist, and break, only in the non-local "
        "(peridynamic) model that [nonlocal] defines (kernel, horizon); add it, or remove [fracture]");
  t->check_keys({"s_crit", "G_c", "rule", "fraction", "max_iterations", "no_fail", "intra_cell_failure"});
  FractureSpec& f = c.fracture;
  f.enabled = true;
  f.where = t->where();

  const std::optional<Value> s_crit = t->get("s_crit");
  const std::optional<Value> G_c = t->get("G_c");
  if (s_crit && G_c) {
    const bool gc_last =
        G_c->where().line > s_crit->where().line ||
        (G_c->where().line == s_crit->where().line && G_c->where().column > s_crit->where().column);
    const Value& second = gc_last ? *G_c : *s_crit;
    const Value& first = gc_last ? *s_crit : *G_c;
    second.fail(fmt::format(
        "cannot be combined with {} (line {}); give exactly one failure criterion: either s_crit (the "
        "critical bond stretch) or G_c (the critical energy release rate, from which s_crit follows), "
        "and remove the other",
        first.path(), first.where().line));
  }
  if (!s_crit && !G_c) t->fail(fmt::format("gives no failure criterion: set exactly one of {}", kCriterion));
  if (s_crit)
    f.s_crit = positive(*s_crit,
                        "the critical bond stretch, dimensionless; a bond breaks when its stretch "
                        "exceeds it");
  else
    f.G_c = positive(*G_c, "the critical energy release rate, energy per area");

  const std::optional<Value> rule = t->get("rule");
  const std::optional<Value> fraction = t->get("fraction");
  if (rule) f.rule = rule_of(*rule);
  if (f.rule == BreakRule::fraction) {
    const Value v = t->require(
        "fraction",
        "rule = \"fraction\" needs fraction, 0 < fraction <= 1: in each iteration the bonds with s/s_crit "
        ">= fraction × the largest s/s_crit break (1: only the most stretched)");
    f.fraction = v.number();
    if (!(f.fraction > 0 && f.fraction <= 1))
      v.fail(fmt::format(
          "must lie in (0, 1], got {}: the bonds with s/s_crit >= fraction × the largest s/s_crit break in "
          "an iteration (1: only the most stretched; smaller: more at once)",
          f.fraction));
  } else if (fraction) {
    fraction->fail(fmt::format(
        "applies only with rule = \"fraction\"{}; rule \"all\" breaks every bond over the criterion in "
        "one iteration. Add rule = \"fraction\" to break only the most stretched bonds, or remove "
        "fraction",
        rule ? fmt::format(" (rule is \"all\", line {})", rule->where().line)
             : " (rule defaults to \"all\")"));
  }

  if (auto v = t->get("max_iterations")) {
    const int n = v->integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    if (n < 1)
      v->fail(fmt::format(
          "must be an integer of at least 1 (the bond-breaking iterations allowed per load increment), got "
          "{}",
          n));
    f.max_iterations = n;
  }

  if (auto v = t->get("intra_cell_failure")) f.intra_cell_failure = v->boolean();

  if (auto v = t->get("no_fail")) {
    std::vector<Value> names;
    if (v->node().is_array())
      names = v->elements();
    else
      names.push_back(*v);
    std::vector<std::string> known;
    for (const RegionSpec& r : c.regions) known.push_back(r.name);
    for (const Value& n : names) {
      const std::string name = n.name();
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        const std::string close = closest_match(name, known);
        n.fail(fmt::format(
            "no [[region]] is named {:?}; {}no_fail takes the names of [[region]] boxes whose bonds never "
            "fail{}",
            name, close.empty() ? "" : fmt::format("did you mean {:?}? ", close),
            known.empty() ? " (this case defines none: add a [[region]] with name, lower, upper)"
                          : fmt::format(" (defined: {})", fmt::join(known, ", "))));
      }
      if (std::find(f.no_fail.begin(), f.no_fail.end(), name) != f.no_fail.end())
        n.fail(fmt::format("region {:?} is listed twice", name));
      f.no_fail.push_back(name);
    }
  }
}

}  // namespace perimorph::casefile::detail
