// The commands of the perimorph program (commands.hpp).

#include "commands.hpp"

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/diagnostics/effective_gc.hpp"
#include "perimorph/diagnostics/ghost_forces.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <utility>

namespace perimorph::app {

int check(const std::string& path) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const auto model = perimorph::setup::build_discretization(config);
  // What `run` builds before its first solve, so that check finds every case
  // error run would find (set names, loads, the critical stretch, ...).
  const auto setup = perimorph::run::prepare_run(model);
  fmt::print(
      "{}: OK — {}D, {} cells, {} nodes, {} dofs, {} material(s), {} increment(s), {} constrained dofs\n",
      path, model.dim(), model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_dofs(),
      config.materials.size(), config.loading.factors.size(), setup.bc.dofs.size());
  return 0;
}

namespace {

/// A PETSc session with no options of its own (commands that assemble but do not solve).
std::unique_ptr<perimorph::la::PetscSession> quiet_petsc() {
  return std::make_unique<perimorph::la::PetscSession>();
}

/// The anisotropic micromodulus: its coefficients, the range of Y and how
/// closely c_r Y reproduces C0 (THEORY §2.1, eq. 2.64; exact up to round-off).
void print_angular(const perimorph::setup::NonlocalModel& nl, int dim) {
  namespace pd = perimorph::peridynamics;
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
  fmt::print(
      "kernel     c(xi) = c_hat * phi(r) * Y(xi/r), c_hat = {:.6e}{}; Y {}: {}\n", nl.calibration.scale,
      nl.discrete_factor != 1.0 ? fmt::format(" (discrete calibration factor {:.8f})", nl.discrete_factor)
                                : "",
      pd::to_string(Y.kind), coeffs);
  const auto [lo, hi] = pd::angular_range(Y, dim);
  fmt::print("angular    Y ranges over [{:.6g}, {:.6g}]{}\n", lo, hi,
             lo < 0 ? " -- negative in some directions: those bonds push; the non-local stiffness may be "
                      "indefinite"
                    : "");
  const double moment = nl.calibration.scale * nl.kernel.shape_moment(dim == 2 ? 3 : 4);
  const Eigen::MatrixXd C = pd::angular_bulk_tensor(Y, dim, moment);  // in mesh axes
  const Eigen::MatrixXd& C0 = nl.material.C0;
  const Eigen::VectorXd diag = C0.diagonal();
  fmt::print(
      "equivalent C0 (mesh axes, Voigt) diagonal [{:.6e}], C1122 = {:.6e}; bulk tensor of c: max |C - C0| / "
      "max |C0| = {:.2e}\n",
      fmt::join(std::vector<double>(diag.data(), diag.data() + diag.size()), ", "), C0(0, 1),
      (C - C0).cwiseAbs().maxCoeff() / C0.cwiseAbs().maxCoeff());
  fmt::print("fracture   G_c depends on the crack plane for an anisotropic kernel (not computed)\n");
}

}  // namespace

int info(const std::string& path) {
  namespace pd = perimorph::peridynamics;
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = perimorph::setup::build_discretization(config);
  fmt::print("case       {}\n", path);
  fmt::print("mesh       {}D, {} cells, {} nodes; {} dof nodes, {} dofs\n", model.dim(),
             model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_nodes(),
             model.dofmap.num_dofs());
  if (!model.nonlocal) {
    fmt::print("model      local only (no [nonlocal] section)\n");
    return 0;
  }
  const auto& nl = *model.nonlocal;
  const auto& cal = nl.calibration;
  const bool has_length =
      nl.kernel.shape == pd::KernelShape::exponential || nl.kernel.shape == pd::KernelShape::gaussian;
  fmt::print("kernel     {}, horizon delta = {}{}\n", pd::to_string(nl.kernel.shape), nl.kernel.horizon,
             has_length ? fmt::format(", length l = {}", nl.kernel.length) : "");
  for (const auto& note : nl.material.notes) fmt::print("material   {}\n", note);
  const auto& fracture = config.fracture;
  if (nl.kernel.angular.kind == pd::AngularKind::isotropic) {
    fmt::print("scale      c_hat = {:.6e}  (micromodulus c(r) = c_hat * phi(r)){}\n", cal.scale,
               nl.discrete_factor != 1.0
                   ? fmt::format("; discrete calibration factor {:.8f}", nl.discrete_factor)
                   : "");
    if (model.dim() > 1)
      fmt::print("equivalent lambda = mu = {:.6e}, E = {:.6e}, nu = {:.6f}\n", cal.lame, cal.E, cal.nu);
    else
      fmt::print("equivalent E = {:.6e}\n", cal.E);
    fmt::print("fracture   G_c = {:.6e} * s_crit^2  (bulk closed form, THEORY §5)\n", cal.gc_factor);
    if (fracture.enabled && fracture.s_crit > 0)
      fmt::print("           [fracture] s_crit = {:.6g}: G_c = {:.6e}\n", fracture.s_crit,
                 cal.gc_factor * fracture.s_crit * fracture.s_crit);
    else if (fracture.enabled)
      fmt::print("           [fracture] G_c = {:.6e}: s_crit = {:.6g}\n", fracture.G_c,
                 std::sqrt(fracture.G_c / cal.gc_factor));
  } else {
    print_angular(nl, model.dim());
    if (fracture.enabled && fracture.s_crit > 0)
      fmt::print("           [fracture] s_crit = {:.6g}\n", fracture.s_crit);
  }
  perimorph::Index positive = 0, pure = 0;
  for (perimorph::Index c = 0; c < model.mesh.num_cells(); ++c) {
    positive += nl.points.cell_alpha_max[static_cast<std::size_t>(c)] > 0 ? 1 : 0;
    pure += nl.morph.purely_nonlocal[static_cast<std::size_t>(c)] ? 1 : 0;
  }
  fmt::print("alpha      {} cells with alpha > 0, {} morphing cells, {} purely non-local cells\n", positive,
             nl.morph.morphing_cells, pure);
  fmt::print(
      "           morphing: the local stiffness C(x) is reduced from C0 but not 0 (alpha > 0 on the cell or "
      "its horizon, THEORY §3); purely non-local: C = 0, only bonds{}\n",
      config.nonlocal.discretization == perimorph::casefile::Discretization::continuous
          ? ""
          : (config.nonlocal.discretization == perimorph::casefile::Discretization::discontinuous
                 ? " (DG cells)"
                 : " (DG degree 0 cells)"));
  const perimorph::assembly::NonlocalSpace space{model.mesh, model.dofmap, nl.points, nl.graph, nl.kernel};
  const auto count = perimorph::assembly::count_bonds(space);
  fmt::print(
      "bonds      {} bonds (pairs of non-local points with alpha c > 0), {} non-local points per cell, "
      "{} interacting cell pairs ({} with bonds)\n",
      count.bonds, nl.points.per_cell, nl.graph.num_pairs(), count.cell_pairs);
  if (nl.points.partial_volume())
    fmt::print("edge       partial volume: bonds weighed near |xi| = delta, reach up to {:.6g}\n",
               nl.points.bond_reach(nl.kernel.horizon));
  else
    fmt::print("edge       cut-off: a bond counts iff |xi| < delta\n");
  return 0;
}

int ghost_forces(const std::string& path, const std::vector<double>& strain, const std::string& out_dir) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const int dim = config.dim();
  const std::size_t expected = dim == 1 ? 1 : dim == 2 ? 3 : 6;
  if (strain.size() != expected)
    throw perimorph::InputError(fmt::format("--strain needs {} values in {}D ({}); got {}", expected, dim,
                                            dim == 1   ? "exx"
                                            : dim == 2 ? "exx,eyy,exy"
                                                       : "exx,eyy,ezz,eyz,exz,exy",
                                            strain.size()));
  perimorph::Mat3 eps = perimorph::Mat3::Zero();
  eps(0, 0) = strain[0];
  if (dim == 2) {
    eps(1, 1) = strain[1];
    eps(0, 1) = eps(1, 0) = strain[2];
  } else if (dim == 3) {
    eps(1, 1) = strain[1];
    eps(2, 2) = strain[2];
    eps(1, 2) = eps(2, 1) = strain[3];
    eps(0, 2) = eps(2, 0) = strain[4];
    eps(0, 1) = eps(1, 0) = strain[5];
  }
  auto petsc = quiet_petsc();
  const auto model = perimorph::setup::build_discretization(config);
  const auto g = perimorph::diagnostics::compute_ghost_forces(model, eps);
  const std::string dir = perimorph::run::resolve_output_directory(config, {out_dir, true});
  const std::string base =
      config.output.basename.empty() ? std::filesystem::path(path).stem().string() : config.output.basename;
  const auto csv = perimorph::diagnostics::write_ghost_forces(model, g, dir, base);
  fmt::print("max ghost-force density {:.6e}; wrote {}\n", g.max_density, csv);
  return 0;
}

/// The critical energy release rate of a crack plane: closed form, actual
/// geometry and bulk window (diagnostics/effective_gc.hpp).
int gc(const std::string& path, std::vector<double> point, std::vector<double> normal,
       std::optional<double> s_option) {
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = perimorph::setup::build_discretization(config);
  if (!model.nonlocal)
    throw perimorph::InputError(
        fmt::format("{}: no [nonlocal] section: G_c is a property of the bond model", path));
  // One number per axis of the case at least (a shorter vector would put the
  // plane somewhere the user did not say); a z of 0 may follow in 2D.
  for (const auto& [name, v] : {std::pair{"--point", &point}, std::pair{"--normal", &normal}})
    if (static_cast<int>(v->size()) < model.dim())
      throw perimorph::InputError(fmt::format("{} has {} number{} but {} is {}D: give one per axis ({})",
                                              name, v->size(), v->size() == 1 ? "" : "s", path, model.dim(),
                                              model.dim() == 2 ? "x y" : "x y z"));
  point.resize(3, 0.0);
  normal.resize(3, 0.0);
  const double kappa = model.nonlocal->calibration.gc_factor;
  const auto s = perimorph::setup::resolve_critical_stretch(config.fracture, kappa, s_option);
  const auto g = perimorph::diagnostics::effective_gc(
      model, {{point[0], point[1], point[2]}, {normal[0], normal[1], normal[2]}}, s.value);
  const bool per_s2 = s.source == perimorph::setup::StretchSource::unit;
  const char* unit = per_s2 ? " per s_crit^2" : "";
  const char* from = s.source == perimorph::setup::StretchSource::option        ? "--s-crit"
                     : s.source == perimorph::setup::StretchSource::case_s_crit ? "[fracture] s_crit"
                     : s.source == perimorph::setup::StretchSource::case_G_c
                         ? "[fracture] G_c through the closed form"
                         : "none given: figures are per s_crit^2";
  const auto& p = g.plane;
  fmt::print("case         {}\n", path);
  fmt::print("plane        through ({:.6g}, {:.6g}, {:.6g}), unit normal ({:.6g}, {:.6g}, {:.6g})\n",
             p.point.x(), p.point.y(), p.point.z(), p.normal.x(), p.normal.y(), p.normal.z());
  fmt::print("s_crit       {:.6g} ({})\n", s.value, from);
  if (std::isfinite(g.closed_form))
    fmt::print("closed form  G_c = {:.6e}{}  (bulk, kappa s_crit^2, kappa = {:.6e}, THEORY §5)\n",
               g.closed_form, unit, kappa);
  else
    fmt::print("closed form  not available: an anisotropic kernel's G_c depends on the plane\n");
  auto ratio = [&](double v) {
    return std::isfinite(g.closed_form) && std::isfinite(v)
               ? fmt::format(", {:.4f} of the closed form", v / g.closed_form)
               : std::string();
  };
  fmt::print("actual       G_c = {:.6e}{}  (every crossing bond over the plane's area{})\n", g.actual.gc(),
             unit, ratio(g.actual.gc()));
  if (g.window.area > 0)
    fmt::print("bulk window  G_c = {:.6e}{}  (crossing farther than delta = {:.6g} from every face{})\n",
               g.window.gc(), unit, g.horizon, ratio(g.window.gc()));
  else
    fmt::print("bulk window  none: no part of the plane is farther than delta = {:.6g} from every face\n",
               g.horizon);
  fmt::print(
      "bonds        {} crossing ({} with one end on the plane, weight 1/2), {} in the window; {} cut "
      "by a pre-crack and left out{}\n",
      g.actual.bonds, g.touching, g.window.bonds, g.cut,
      g.cut > 0 ? " (from both figures; the areas include the pre-cracked part)" : "");
  if (g.reduced_alpha > 0)
    fmt::print(
        "alpha        {} of the counted bonds have mean alpha < 1 (morphing or local zone): their energy is "
        "scaled by alpha, and the local model's share is not counted\n",
        g.reduced_alpha);
  fmt::print("area         plane {:.6e}, window {:.6e}{}\n", g.actual.area, g.window.area,
             model.dim() == 2   ? " (length x thickness)"
             : model.dim() == 1 ? " (cross-section)"
                                : "");
  fmt::print(
      "units        G_c in energy per crack area = the case's stiffness unit x length unit (e.g. "
      "MPa mm = N/mm = mJ/mm^2)\n");
  return 0;
}

int run(const std::string& path, const std::string& out_dir, bool quiet, std::vector<std::string> petsc_args,
        std::chrono::steady_clock::time_point start) {
  const auto config = perimorph::casefile::parse_case_file(path);
  perimorph::io::ProgressLine progress(static_cast<int>(config.loading.factors.size()), !quiet, start);
  progress.phase("PETSc");
  // PETSc sees only the options meant for it (the program name first).
  std::vector<std::string> args{"perimorph"};
  args.insert(args.end(), petsc_args.begin(), petsc_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(args.size());
  char** argv_ptr = argv.data();
  perimorph::la::PetscSession petsc(argc, argv_ptr);
  const auto model = perimorph::setup::build_discretization(
      config, [&](const std::string& phase) { progress.phase(phase); });
  const auto summary = perimorph::run::run_static(model, {out_dir, quiet, &progress});
  progress.finish();
  if (!quiet) {
    fmt::print("{}: {} increment(s), {} dofs; last solve {} + {}: {} iterations, relative residual {:.2e}\n",
               path, summary.increments_done, model.dofmap.num_dofs(), summary.last_solve.ksp_type,
               summary.last_solve.pc_type, summary.last_solve.iterations,
               summary.last_solve.relative_residual);
    fmt::print("strain energy {:.6e}, external work {:.6e}\n", summary.strain_energy, summary.external_work);
    for (std::size_t k = 0; k < summary.reactions.size(); ++k)
      fmt::print("reaction on '{}': ({:.6e}, {:.6e}, {:.6e})\n", summary.reaction_names[k],
                 summary.reactions[k].x(), summary.reactions[k].y(), summary.reactions[k].z());
    fmt::print("wrote {}{}\n", summary.csv_path, summary.pvd_path.empty() ? "" : " and " + summary.pvd_path);
  }
  return 0;
}

}  // namespace perimorph::app
