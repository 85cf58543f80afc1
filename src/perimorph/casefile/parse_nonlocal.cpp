// Case-file parsing of the non-local sections: [nonlocal] (the peridynamic
// model) and [alpha] / [[alpha.region]] (the morphing field α). Format in
// docs/case-file.md; conventions as in parse_case.cpp.

#include "perimorph/casefile/parse_nonlocal.hpp"

#include "perimorph/casefile/choose_option.hpp"
#include "perimorph/casefile/suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

const Options<KernelKind> kKernels{{"constant", KernelKind::constant},
                                   {"conical", KernelKind::conical},
                                   {"exponential", KernelKind::exponential},
                                   {"gaussian", KernelKind::gaussian},
                                   {"pmb", KernelKind::pmb}};
const Options<Discretization> kDiscretizations{
    {"continuous", Discretization::continuous},
    {"discontinuous", Discretization::discontinuous},
    {"discontinuous-constant", Discretization::discontinuous_constant}};
const Options<Coupling> kCouplings{{"morphing", Coupling::morphing}, {"partition", Coupling::partition}};
const Options<CalibrationRule> kCalibrations{{"continuum", CalibrationRule::continuum},
                                             {"discrete", CalibrationRule::discrete}};
const Options<HorizonEdge> kHorizonEdges{{"cutoff", HorizonEdge::cutoff},
                                         {"partial-volume", HorizonEdge::partial_volume}};
const Options<AlphaShapeKind> kShapes{{"interval", AlphaShapeKind::interval},
                                      {"slab", AlphaShapeKind::slab},
                                      {"ball", AlphaShapeKind::ball},
                                      {"cylinder", AlphaShapeKind::cylinder},
                                      {"box", AlphaShapeKind::box}};
const Options<AlphaProfile>& kProfiles = profile_options();

std::string for_dim(int dim) {
  return fmt::format("for dim = {}", dim);
}

/// "[1, -inf]": the first n components of v.
std::string point(const Vec3& v, int n) {
  return fmt::format("[{}]", fmt::join(v.data(), v.data() + n, ", "));
}

/// "[x, y]": the form of a dim-vector, for messages.
std::string vector_form(int dim) {
  constexpr const char* forms[3] = {"[x]", "[x, y]", "[x, y, z]"};
  return forms[dim - 1];
}

double positive(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x > 0)) v.fail(fmt::format("must be positive ({}), got {}", what, x));
  return x;
}

double nonnegative(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x >= 0)) v.fail(fmt::format("must be zero or positive ({}), got {}", what, x));
  return x;
}

/// A non-zero dim-vector (a direction), returned normalized.
Vec3 direction(const Value& v, int dim, std::string_view what) {
  const Vec3 d = v.vector(dim, for_dim(dim));
  if (!(d.norm() > 0)) v.fail(fmt::format("must be a non-zero vector ({}), got {}", what, point(d, dim)));
  return d.normalized();
}

/// An array of dim numbers, each finite or infinite (TOML inf, -inf); nan is
/// rejected.
Vec3 bounds(const Value& v, int dim) {
  if (!v.node().is_array())
    v.fail(fmt::format("expected an array of {} numbers {} (inf and -inf allowed), got {}", dim, for_dim(dim),
                       show(v.node())));
  const std::vector<Value> items = v.elements();
  if (items.size() != static_cast<std::size_t>(dim))
    v.fail(fmt::format("needs {} numbers {}, got {}: {}", dim, for_dim(dim), items.size(), render(v.node())));
  Vec3 out = Vec3::Zero();
  for (int i = 0; i < dim; ++i) {
    const Value& item = items[static_cast<std::size_t>(i)];
    if (const auto* f = item.node().as_floating_point()) {
      out[i] = f->get();
      if (std::isnan(out[i])) item.fail("expected a number (inf and -inf are allowed here), got nan");
    } else {
      out[i] = item.number();  // an integer, or fails with "expected a number"
    }
  }
  return out;
}

// ------------------------------------------------------------ [[alpha.region]]

const std::vector<std::string> kRegionCommonKeys{"shape", "transition", "profile"};

/// The keys that each shape takes, in the order of AlphaShapeKind.
const std::vector<std::string> kShapeKeys[5] = {{"lower", "upper"},
                                                {"point", "normal", "half_width"},
                                                {"center", "radius"},
                                                {"point", "axis", "radius"},
                                                {"lower", "upper"}};

std::string shape_takes(AlphaShapeKind kind, int dim) {
  const std::string v = vector_form(dim);
  switch (kind) {
    case AlphaShapeKind::interval:
      return "an interval takes lower = x0 and upper = x1 (numbers)";
    case AlphaShapeKind::slab:
      return fmt::format("a slab takes point = {}, normal = {} and half_width", v, v);
    case AlphaShapeKind::ball:
      return fmt::format("a ball takes center = {} and radius", v);
    case AlphaShapeKind::cylinder:
      return fmt::format("a cylinder takes point = {}, axis = {} and radius", v, v);
    case AlphaShapeKind::box:
      return fmt::format("a box takes lower = {} and upper = {} (inf and -inf allowed)", v, v);
  }
  return {};
}

std::string shapes_for(int dim) {
  constexpr const char* shapes[3] = {"\"interval\", \"slab\", \"ball\" or \"box\"",
                                     "\"slab\", \"ball\" (a disk) or \"box\"",
                                     "\"slab\", \"ball\", \"cylinder\" or \"box\""};
  return fmt::format("{} use {}", for_dim(dim), shapes[dim - 1]);
}

void read_shape(const Table& t, AlphaShapeKind kind, int dim, AlphaRegionSpec& r) {
  const std::string takes = shape_takes(kind, dim);
  switch (kind) {
    case AlphaShapeKind::interval: {
      r.lower.x() = t.require("lower", takes).number();
      const Value hi = t.require("upper", takes);
      r.upper.x() = hi.number();
      if (!(r.upper.x() > r.lower.x()))
        hi.fail(fmt::format("must be greater than {} = {}, got {}", t.key_path("lower"), r.lower.x(),
                            r.upper.x()));
      return;
    }
    case AlphaShapeKind::slab:
      r.point = t.require("point", takes).vector(dim, for_dim(dim));
      r.direction = direction(t.require("normal", takes), dim, "the slab's normal");
      r.half_width = nonnegative(t.require("half_width", takes),
                                 "half the slab's thickness; 0 is a plane widened by the transition only");
      return;
    case AlphaShapeKind::ball:
      r.point = t.require("center", takes).vector(dim, for_dim(dim));
      r.radius = positive(t.require("radius", takes), "the ball's radius");
      return;
    case AlphaShapeKind::cylinder:
      r.point = t.require("point", takes).vector(dim, for_dim(dim));
      r.direction = direction(t.require("axis", takes), dim, "the cylinder's axis");
      r.radius = positive(t.require("radius", takes), "the cylinder's radius");
      return;
    case AlphaShapeKind::box: {
      r.lower = bounds(t.require("lower", takes), dim);
      const Value hi = t.require("upper", takes);
      r.upper = bounds(hi, dim);
      constexpr const char* axes[3] = {"x", "y", "z"};
      for (int i = 0; i < dim; ++i)
        if (!(r.upper[i] > r.lower[i]))
          hi.elements()[static_cast<std::size_t>(i)].fail(fmt::format(
              "must be greater than {}[{}] = {} (the box needs a positive extent along {}), got {}",
              t.key_path("lower"), i + 1, r.lower[i], axes[i], r.upper[i]));
      return;
    }
  }
}

AlphaRegionSpec read_alpha_region(const Table& t, int dim) {
  // First against every key of every shape, so that a misspelt key gets a
  // suggestion even before the shape is known.
  std::vector<std::string> every = kRegionCommonKeys;
  for (const auto& keys : kShapeKeys)
    for (const std::string& k : keys)
      if (std::find(every.begin(), every.end(), k) == every.end()) every.push_back(k);
  t.check_keys(every);

  AlphaRegionSpec r;
  r.where = t.where();
  const Value shape = t.require(
      "shape", "the region's shape: \"interval\" (1D), \"slab\", \"ball\", \"cylinder\" (3D) or \"box\"");
  r.shape = choose(shape, kShapes, "shape");
  if (r.shape == AlphaShapeKind::interval && dim != 1)
    shape.fail(fmt::format("\"interval\" is a 1D shape (an interval along x), but mesh.dim = {}; {}", dim,
                           shapes_for(dim)));
  if (r.shape == AlphaShapeKind::cylinder && dim != 3)
    shape.fail(
        fmt::format("\"cylinder\" is a 3D shape (points within radius of an axis), but mesh.dim = {}; {}",
                    dim, shapes_for(dim)));

  // Then exactly the keys of this shape.
  const std::vector<std::string>& own = kShapeKeys[static_cast<std::size_t>(r.shape)];
  std::vector<std::string> allowed = kRegionCommonKeys;
  allowed.insert(allowed.end(), own.begin(), own.end());
  std::vector<std::pair<std::string, std::string>> hints;
  for (const std::string& k : every)
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      hints.emplace_back(k,
                         fmt::format("{}; transition and profile are optional", shape_takes(r.shape, dim)));
  t.check_keys(allowed, hints);

  if (auto v = t.get("transition"))
    r.transition = nonnegative(*v, "the width of the transition zone around the shape; 0 is a sharp edge");
  if (auto v = t.get("profile")) r.profile = choose(*v, kProfiles, "profile");
  read_shape(t, r.shape, dim, r);
  return r;
}

}  // namespace

// ------------------------------------------------------------ [nonlocal]

void read_nonlocal(const Table& root, CaseConfig& c) {
  const auto t = root.table("nonlocal");
  if (!t) return;
  t->check_keys({"kernel", "horizon", "length", "quadrature", "discretization", "coupling", "calibration",
                 "horizon_edge"});
  NonlocalSpec& n = c.nonlocal;
  n.enabled = true;
  n.where = t->where();
  const Value kernel = t->require(
      "kernel",
      "the micromodulus kernel: \"constant\", \"conical\", \"exponential\", \"gaussian\" or \"pmb\"");
  n.kernel = choose(kernel, kKernels, "kernel");
  n.horizon =
      positive(t->require("horizon", "the horizon δ > 0, the reach of the non-local bonds"), "the horizon δ");
  const std::string name = kernel.string();
  if (n.kernel == KernelKind::exponential || n.kernel == KernelKind::gaussian)
    n.length =
        positive(t->require("length", fmt::format("the {:?} kernel needs its length scale l > 0", name)),
                 "the kernel's length scale l");
  else if (auto v = t->get("length"))
    v->fail(fmt::format(
        "the {:?} kernel has no length scale; remove it (length applies to the \"exponential\" and "
        "\"gaussian\" kernels)",
        name));
  if (auto v = t->get("quadrature")) n.quadrature = v->integer(1, 6);
  if (auto v = t->get("discretization")) n.discretization = choose(*v, kDiscretizations, "discretization");
  if (auto v = t->get("coupling")) n.coupling = choose(*v, kCouplings, "coupling");
  if (auto v = t->get("calibration")) n.calibration = choose(*v, kCalibrations, "calibration");
  if (auto v = t->get("horizon_edge")) n.horizon_edge = choose(*v, kHorizonEdges, "horizon_edge");
}

// ------------------------------------------------------------ [alpha]

void read_alpha(const Table& root, CaseConfig& c) {
  const auto t = root.table("alpha");
  if (!t) return;
  if (!c.nonlocal.enabled)
    t->fail(
        "an alpha field needs a [nonlocal] section: α blends the local model with the non-local one that "
        "[nonlocal] defines (kernel, horizon); add it, or remove [alpha]");
  t->check_keys({"value", "region"});
  AlphaSpec& a = c.alpha;
  a.where = t->where();
  const std::optional<Value> value = t->get("value");
  const std::vector<Table> regions = t->tables("region");
  if (value && t->has("region"))
    value->fail(
        fmt::format("cannot be combined with [[alpha.region]]{}; give either a constant value or regions",
                    regions.empty() ? "" : fmt::format(" (line {})", regions.front().where().line)));
  if (value) {
    a.value = value->number();
    if (!(a.value >= 0 && a.value <= 1))
      value->fail(fmt::format("must lie in [0, 1] (0 purely local, 1 purely non-local), got {}", a.value));
    return;
  }
  if (regions.empty())
    t->fail(
        "gives no field: set a constant value in [0, 1] (0 purely local, 1 purely non-local) or add "
        "[[alpha.region]] entries");
  for (const Table& r : regions) a.regions.push_back(read_alpha_region(r, c.dim()));
}

}  // namespace perimorph::casefile::detail
