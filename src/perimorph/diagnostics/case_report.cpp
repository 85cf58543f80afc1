#include "perimorph/diagnostics/case_report.hpp"

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/diagnostics/effective_gc.hpp"
#include "perimorph/diagnostics/model_memory.hpp"
#include "perimorph/peridynamics/anisotropy.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace perimorph::diagnostics {

namespace {

using Out = std::back_insert_iterator<std::string>;

/// The anisotropic micromodulus: its coefficients, the range of Y and how
/// closely c_r Y reproduces C0 (THEORY §2.1, eq. 2.64; exact up to round-off).
void append_angular(Out out, const setup::NonlocalModel& nl, int dim) {
  namespace pd = peridynamics;
  const auto& Y = nl.kernel.angular;
  const int n = dim == 2 ? 5 : Y.kind == pd::AngularKind::transversely_isotropic ? 3 : 6;
  static const char* names3[] = {"a00", "a20", "a22", "a40", "a42", "a44"};
  static const char* namesT[] = {"a0", "a2", "", "a4"};
  static const char* names2[] = {"a0", "a2", "b2", "a4", "b4"};
  std::string coeffs;
  for (int i = 0, shown = 0; shown < n; ++i) {
    const char* name = dim == 2 ? names2[i] : n == 3 ? namesT[i] : names3[i];
    if (*name == '\0') continue;
    coeffs += fmt::format("{}{} = {:.6e}", shown ? ", " : "", name, Y.a[static_cast<std::size_t>(i)]);
    ++shown;
  }
  fmt::format_to(
      out, "kernel     c(xi) = c_hat * phi(r) * Y(xi/r), c_hat = {:.6e}{}; Y {}: {}\n", nl.calibration.scale,
      nl.discrete_factor != 1.0 ? fmt::format(" (discrete calibration factor {:.8f})", nl.discrete_factor)
                                : "",
      pd::to_string(Y.kind), coeffs);
  const auto [lo, hi] = pd::angular_range(Y, dim);
  fmt::format_to(out, "angular    Y ranges over [{:.6g}, {:.6g}]{}\n", lo, hi,
                 lo < 0 ? " -- negative in some directions: those bonds push; the non-local stiffness may be "
                          "indefinite"
                        : "");
  const double moment = nl.calibration.scale * nl.kernel.shape_moment(dim == 2 ? 3 : 4);
  const Eigen::MatrixXd C = pd::angular_bulk_tensor(Y, dim, moment);  // in mesh axes
  const Eigen::MatrixXd& C0 = nl.material.C0;
  const Eigen::VectorXd diag = C0.diagonal();
  fmt::format_to(
      out,
      "equivalent C0 (mesh axes, Voigt) diagonal [{:.6e}], C1122 = {:.6e}; bulk tensor of c: max |C - C0| / "
      "max |C0| = {:.2e}\n",
      fmt::join(std::vector<double>(diag.data(), diag.data() + diag.size()), ", "), C0(0, 1),
      (C - C0).cwiseAbs().maxCoeff() / C0.cwiseAbs().maxCoeff());
  fmt::format_to(out, "fracture   G_c depends on the crack plane for an anisotropic kernel (not computed)\n");
}

/// The model's memory (model_memory.hpp): what a process of a distributed
/// run holds whole, stage by stage, and per cell.
void append_memory(std::back_insert_iterator<std::string> out, const setup::Discretization& model) {
  const ModelMemory m = model_memory(model);
  // A process also holds, per cell, where its points are (NonlocalPoints::slot).
  const std::size_t whole =
      m.whole() + (model.nonlocal && model.nonlocal->points.holds_every_cell()
                       ? static_cast<std::size_t>(model.mesh.num_cells()) * sizeof(Index)
                       : 0);
  const auto MB = [](std::size_t b) { return static_cast<double>(b) / 1e6; };
  const std::string nonlocal = model.nonlocal
                                   ? fmt::format(
                                         ", alpha bounds of the non-local points per cell {:.2f} MB, purely "
                                         "non-local flags {:.2f} MB",
                                         MB(m.cell_alpha), MB(m.flags))
                                   : std::string();
  const std::string part =
      model.nonlocal
          ? fmt::format(
                "cell graph {:.2f} MB, non-local points {:.2f} MB and local stiffness C {:.2f} MB, "
                "of which a process holds its part's (the graph rows and morphed C of its cells "
                "and their node neighbours, and the points of the cells those rows reach)",
                MB(m.graph), MB(m.points), MB(m.stiffness))
          : fmt::format("local stiffness C {:.2f} MB", MB(m.stiffness));
  const auto per_cell = [&](std::size_t b) {
    return static_cast<double>(b) / static_cast<double>(std::max<Index>(model.mesh.num_cells(), 1));
  };
  fmt::format_to(
      out,
      "memory     the model: mesh {:.2f} MB, dof map {:.2f} MB{}: {:.0f} bytes per cell with the "
      "place of each cell's points, held whole by every process of a distributed run; {}. A run "
      "adds, whole on every process, u {:.2f} MB and the dof nodes' distributed numbers {:.2f} MB: "
      "{:.0f} bytes per cell in all\n",
      MB(m.mesh), MB(m.dofs), nonlocal, per_cell(whole), part, MB(m.displacement), MB(m.distribution),
      per_cell(whole + m.displacement + m.distribution));
}

}  // namespace

std::string info_report(const setup::Discretization& model, const std::string& path) {
  namespace pd = peridynamics;
  const auto& config = model.config;
  std::string text;
  auto out = std::back_inserter(text);
  fmt::format_to(out, "case       {}\n", path);
  fmt::format_to(out, "mesh       {}D, {} cells, {} nodes; {} dof nodes, {} dofs\n", model.dim(),
                 model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_nodes(),
                 model.dofmap.num_dofs());
  if (!model.nonlocal) {
    fmt::format_to(out, "model      local only (no [nonlocal] section)\n");
    append_memory(out, model);
    return text;
  }
  const auto& nl = *model.nonlocal;
  const auto& cal = nl.calibration;
  const bool has_length =
      nl.kernel.shape == pd::KernelShape::exponential || nl.kernel.shape == pd::KernelShape::gaussian;
  fmt::format_to(out, "kernel     {}, horizon delta = {}{}\n", pd::to_string(nl.kernel.shape),
                 nl.kernel.horizon, has_length ? fmt::format(", length l = {}", nl.kernel.length) : "");
  for (const auto& note : nl.material.notes) fmt::format_to(out, "material   {}\n", note);
  const auto& fracture = config.fracture;
  if (nl.kernel.angular.kind == pd::AngularKind::isotropic) {
    fmt::format_to(out, "scale      c_hat = {:.6e}  (micromodulus c(r) = c_hat * phi(r)){}\n", cal.scale,
                   nl.discrete_factor != 1.0
                       ? fmt::format("; discrete calibration factor {:.8f}", nl.discrete_factor)
                       : "");
    if (model.dim() > 1)
      fmt::format_to(out, "equivalent lambda = mu = {:.6e}, E = {:.6e}, nu = {:.6f}\n", cal.lame, cal.E,
                     cal.nu);
    else
      fmt::format_to(out, "equivalent E = {:.6e}\n", cal.E);
    fmt::format_to(out, "fracture   G_c = {:.6e} * s_crit^2  (bulk closed form, THEORY §5)\n", cal.gc_factor);
    if (fracture.enabled && fracture.s_crit > 0)
      fmt::format_to(out, "           [fracture] s_crit = {:.6g}: G_c = {:.6e}\n", fracture.s_crit,
                     cal.gc_factor * fracture.s_crit * fracture.s_crit);
    else if (fracture.enabled)
      fmt::format_to(out, "           [fracture] G_c = {:.6e}: s_crit = {:.6g}\n", fracture.G_c,
                     std::sqrt(fracture.G_c / cal.gc_factor));
  } else {
    append_angular(out, nl, model.dim());
    if (fracture.enabled && fracture.s_crit > 0)
      fmt::format_to(out, "           [fracture] s_crit = {:.6g}\n", fracture.s_crit);
  }
  Index positive = 0, pure = 0;
  for (Index c = 0; c < model.mesh.num_cells(); ++c) {
    positive += nl.points.cell_alpha_max[static_cast<std::size_t>(c)] > 0 ? 1 : 0;
    pure += nl.morph.purely_nonlocal[static_cast<std::size_t>(c)] ? 1 : 0;
  }
  fmt::format_to(out, "alpha      {} cells with alpha > 0, {} morphing cells, {} purely non-local cells\n",
                 positive, nl.morph.morphing_cells, pure);
  fmt::format_to(
      out,
      "           morphing: the local stiffness C(x) is reduced from C0 but not 0 (alpha > 0 on the cell or "
      "its horizon, THEORY §3); purely non-local: C = 0, only bonds{}\n",
      config.nonlocal.discretization == casefile::Discretization::continuous
          ? ""
          : (config.nonlocal.discretization == casefile::Discretization::discontinuous
                 ? " (DG cells)"
                 : " (DG degree 0 cells)"));
  const assembly::NonlocalSpace space = model.nonlocal_space();
  const auto count = assembly::count_bonds(space);
  fmt::format_to(
      out,
      "bonds      {} bonds (pairs of non-local points with alpha c > 0), {} non-local points per cell, "
      "{} interacting cell pairs ({} with bonds)\n",
      count.bonds, nl.points.per_cell, nl.graph.num_pairs(), count.cell_pairs);
  if (nl.points.partial_volume())
    fmt::format_to(out, "edge       partial volume: bonds weighed near |xi| = delta, reach up to {:.6g}\n",
                   nl.points.bond_reach(nl.kernel.horizon));
  else
    fmt::format_to(out, "edge       cut-off: a bond counts iff |xi| < delta\n");
  append_memory(out, model);
  return text;
}

std::string gc_report(const setup::Discretization& model, const std::string& path, const Vec3& point,
                      const Vec3& normal, std::optional<double> s_option) {
  if (!model.nonlocal)
    throw InputError(fmt::format("{}: no [nonlocal] section: G_c is a property of the bond model", path));
  const auto& config = model.config;
  std::string text;
  auto out = std::back_inserter(text);
  const double kappa = model.nonlocal->calibration.gc_factor;
  const auto s = setup::resolve_critical_stretch(config.fracture, kappa, s_option);
  const auto g = effective_gc(model, {point, normal}, s.value);
  const bool per_s2 = s.source == setup::StretchSource::unit;
  const char* unit = per_s2 ? " per s_crit^2" : "";
  const char* from = s.source == setup::StretchSource::option        ? "--s-crit"
                     : s.source == setup::StretchSource::case_s_crit ? "[fracture] s_crit"
                     : s.source == setup::StretchSource::case_G_c ? "[fracture] G_c through the closed form"
                                                                  : "none given: figures are per s_crit^2";
  const auto& p = g.plane;
  fmt::format_to(out, "case         {}\n", path);
  fmt::format_to(out, "plane        through ({:.6g}, {:.6g}, {:.6g}), unit normal ({:.6g}, {:.6g}, {:.6g})\n",
                 p.point.x(), p.point.y(), p.point.z(), p.normal.x(), p.normal.y(), p.normal.z());
  fmt::format_to(out, "s_crit       {:.6g} ({})\n", s.value, from);
  if (std::isfinite(g.closed_form))
    fmt::format_to(out, "closed form  G_c = {:.6e}{}  (bulk, kappa s_crit^2, kappa = {:.6e}, THEORY §5)\n",
                   g.closed_form, unit, kappa);
  else
    fmt::format_to(out, "closed form  not available: an anisotropic kernel's G_c depends on the plane\n");
  auto ratio = [&](double v) {
    return std::isfinite(g.closed_form) && std::isfinite(v)
               ? fmt::format(", {:.4f} of the closed form", v / g.closed_form)
               : std::string();
  };
  fmt::format_to(out, "actual       G_c = {:.6e}{}  (every crossing bond over the plane's area{})\n",
                 g.actual.gc(), unit, ratio(g.actual.gc()));
  if (g.window.area > 0)
    fmt::format_to(out,
                   "bulk window  G_c = {:.6e}{}  (crossing farther than delta = {:.6g} from every face{})\n",
                   g.window.gc(), unit, g.horizon, ratio(g.window.gc()));
  else
    fmt::format_to(out,
                   "bulk window  none: no part of the plane is farther than delta = {:.6g} from every face\n",
                   g.horizon);
  fmt::format_to(
      out,
      "bonds        {} crossing ({} with one end on the plane, weight 1/2), {} in the window; {} cut "
      "by a pre-crack and left out{}\n",
      g.actual.bonds, g.touching, g.window.bonds, g.cut,
      g.cut > 0 ? " (from both figures; the areas include the pre-cracked part)" : "");
  if (g.reduced_alpha > 0)
    fmt::format_to(
        out,
        "alpha        {} of the counted bonds have mean alpha < 1 (morphing or local zone): their energy is "
        "scaled by alpha, and the local model's share is not counted\n",
        g.reduced_alpha);
  fmt::format_to(out, "area         plane {:.6e}, window {:.6e}{}\n", g.actual.area, g.window.area,
                 model.dim() == 2   ? " (length x thickness)"
                 : model.dim() == 1 ? " (cross-section)"
                                    : "");
  fmt::format_to(out,
                 "units        G_c in energy per crack area = the case's stiffness unit x length unit (e.g. "
                 "MPa mm = N/mm = mJ/mm^2)\n");
  return text;
}

}  // namespace perimorph::diagnostics
