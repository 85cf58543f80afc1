// perimorph: the command-line program. A thin layer: parse the command line,
// read the case file, hand over to the driver, report errors once.
//
//   perimorph check CASE                 validate a case file without running
//   perimorph info CASE                  calibration and discretization figures
//   perimorph run CASE [-o DIR] [--quiet] [PETSc options...]
//   perimorph ghost-forces CASE --strain ... [-o DIR]
//   perimorph gc CASE --point X Y Z --normal NX NY NZ [--s-crit S]

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/casefile/suggest.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/driver/effective_gc.hpp"
#include "perimorph/driver/ghost_forces.hpp"
#include "perimorph/driver/model.hpp"
#include "perimorph/driver/static_run.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

const char* perimorph_build_commit();  // generated at build time (cmake/write_version.cmake)

namespace {

/// A first argument that is neither an option nor a command: name it, suggest
/// the closest command and list them (CLI11 alone reports it as a missing
/// command). Returns the message, or "" when the first argument is fine.
std::string unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return {};
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return {};
  const std::string near = perimorph::casefile::closest_match(word, names);
  return fmt::format("unknown command '{}'{}; the commands are {} (perimorph --help)", word,
                     near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), fmt::join(names, ", "));
}

int check(const std::string& path) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const auto model = perimorph::driver::build_model(config);
  fmt::print("{}: OK — {}D, {} cells, {} nodes, {} dofs, {} material(s), {} increment(s)\n", path,
             model.dim(), model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_dofs(),
             config.materials.size(), config.loading.factors.size());
  return 0;
}

/// A PETSc session with no options of its own (commands that assemble but do not solve).
std::unique_ptr<perimorph::la::PetscSession> quiet_petsc() {
  return std::make_unique<perimorph::la::PetscSession>();
}

/// The anisotropic micromodulus: its coefficients, the range of Y and how
/// closely c_r Y reproduces C0 (THEORY §2.1, eq. 2.64; exact up to round-off).
void print_angular(const perimorph::driver::NonlocalModel& nl, int dim) {
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

int info(const std::string& path) {
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = perimorph::driver::build_model(config);
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
  fmt::print("kernel     {}, horizon delta = {}, length l = {}\n",
             perimorph::peridynamics::to_string(nl.kernel.shape), nl.kernel.horizon, nl.kernel.length);
  for (const auto& note : nl.material.notes) fmt::print("material   {}\n", note);
  if (nl.kernel.angular.kind == perimorph::peridynamics::AngularKind::isotropic) {
    fmt::print("scale      c_hat = {:.6e}  (micromodulus c(r) = c_hat * phi(r)){}\n", cal.scale,
               nl.discrete_factor != 1.0
                   ? fmt::format("; discrete calibration factor {:.8f}", nl.discrete_factor)
                   : "");
    if (model.dim() > 1)
      fmt::print("equivalent lambda = mu = {:.6e}, E = {:.6e}, nu = {:.6f}\n", cal.lame, cal.E, cal.nu);
    else
      fmt::print("equivalent E = {:.6e}\n", cal.E);
    fmt::print("fracture   G_c = {:.6e} * s_crit^2  (bulk closed form, THEORY §5)\n", cal.gc_factor);
  } else {
    print_angular(nl, model.dim());
  }
  perimorph::Index positive = 0, pure = 0;
  for (perimorph::Index c = 0; c < model.mesh.num_cells(); ++c) {
    positive += nl.points.cell_alpha_max[static_cast<std::size_t>(c)] > 0 ? 1 : 0;
    pure += nl.morph.purely_nonlocal[static_cast<std::size_t>(c)] ? 1 : 0;
  }
  fmt::print("alpha      {} cells with alpha > 0, {} morphing cells, {} purely non-local cells\n", positive,
             nl.morph.morphing_cells, pure);
  fmt::print("bonds      {} non-local points per cell, {} interacting cell pairs\n", nl.points.per_cell,
             nl.graph.num_pairs());
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
  const auto model = perimorph::driver::build_model(config);
  const auto g = perimorph::driver::compute_ghost_forces(model, eps);
  const std::string dir = perimorph::driver::resolve_output_directory(config, {out_dir, true});
  const std::string base =
      config.output.basename.empty() ? std::filesystem::path(path).stem().string() : config.output.basename;
  const auto csv = perimorph::driver::write_ghost_forces(model, g, dir, base);
  fmt::print("max ghost-force density {:.6e}; wrote {}\n", g.max_density, csv);
  return 0;
}

/// The critical energy release rate of a crack plane: closed form, actual
/// geometry and bulk window (driver/effective_gc.hpp).
int gc(const std::string& path, std::vector<double> point, std::vector<double> normal,
       std::optional<double> s_option) {
  namespace drv = perimorph::driver;
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = drv::build_model(config);
  if (!model.nonlocal)
    throw perimorph::InputError(
        fmt::format("{}: no [nonlocal] section: G_c is a property of the bond model", path));
  point.resize(3, 0.0);
  normal.resize(3, 0.0);
  const double kappa = model.nonlocal->calibration.gc_factor;
  const auto s = drv::resolve_critical_stretch(config.fracture, kappa, s_option);
  const auto g =
      drv::effective_gc(model, {{point[0], point[1], point[2]}, {normal[0], normal[1], normal[2]}}, s.value);
  const bool per_s2 = s.source == drv::StretchSource::unit;
  const char* unit = per_s2 ? " per s_crit^2" : "";
  const char* from = s.source == drv::StretchSource::option        ? "--s-crit"
                     : s.source == drv::StretchSource::case_s_crit ? "[fracture] s_crit"
                     : s.source == drv::StretchSource::case_G_c    ? "[fracture] G_c through the closed form"
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

int run(const std::string& path, const std::string& out_dir, bool quiet,
        std::vector<std::string> petsc_args) {
  const auto config = perimorph::casefile::parse_case_file(path);
  // PETSc sees only the options meant for it (the program name first).
  std::vector<std::string> args{"perimorph"};
  args.insert(args.end(), petsc_args.begin(), petsc_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(args.size());
  char** argv_ptr = argv.data();
  perimorph::la::PetscSession petsc(argc, argv_ptr);
  const auto model = perimorph::driver::build_model(config);
  const auto summary = perimorph::driver::run_static(model, {out_dir, quiet});
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "perimorph — hybrid local/non-local (peridynamics) fracture simulator.\n"
      "Case-file format: docs/case-file.md. PETSc options (e.g. -ksp_type preonly -pc_type cholesky) may\n"
      "follow the case file of `run`; they override the case's [solver] petsc_options."};
  app.require_subcommand(1);
  app.set_version_flag("--version",
                       fmt::format("perimorph {} (commit {})", PERIMORPH_VERSION, perimorph_build_commit()));

  std::string case_path;
  auto* check_cmd =
      app.add_subcommand("check", "Validate a case file (and build its mesh) without running it");
  check_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();

  auto* info_cmd = app.add_subcommand("info",
                                      "Print the calibrated micromodulus (scale, equivalent lambda = mu, E, "
                                      "nu, G_c factor) and the discretization figures of a case");
  info_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();

  std::string out_dir;
  bool quiet = false;
  auto* run_cmd = app.add_subcommand("run", "Run a case: every load increment, VTU/PVD and CSV output");
  run_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  run_cmd->add_option("-o,--output", out_dir, "Output directory (default: the case's [output] directory)");
  run_cmd->add_flag("-q,--quiet", quiet, "No progress line and no summary");
  run_cmd->allow_extras();
  run_cmd->footer("Any further argument starting with '-' is passed to PETSc's options database.");

  std::vector<double> strain;
  auto* ghost_cmd = app.add_subcommand(
      "ghost-forces",
      "Impose u = strain * x on every degree of freedom and write the residual (ghost forces) and its "
      "density per nodal volume, as VTU and CSV (THEORY §3.2)");
  ghost_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  ghost_cmd
      ->add_option("--strain", strain,
                   "Imposed strain: exx (1D); exx,eyy,exy (2D); exx,eyy,ezz,eyz,exz,exy "
                   "(3D), tensorial shear")
      ->required()
      ->delimiter(',');
  ghost_cmd->add_option("-o,--output", out_dir, "Output directory (default: the case's [output] directory)");

  std::vector<double> gc_point, gc_normal;
  std::optional<double> gc_s_crit;
  auto* gc_cmd = app.add_subcommand(
      "gc",
      "Critical energy release rate of the crack plane through --point with normal --normal: the bulk closed "
      "form kappa s_crit^2, the actual geometry (every bond crossing the plane, incomplete horizons near "
      "free faces included, pre-cracked bonds left out) and the bulk window (crossings farther than delta "
      "from every face) (THEORY §5)");
  gc_cmd->add_option("CASE", case_path, "Case file (TOML) with a [nonlocal] section")->required();
  gc_cmd->add_option("--point", gc_point, "A point of the plane: X [Y [Z]]")->required()->expected(1, 3);
  gc_cmd
      ->add_option("--normal", gc_normal,
                   "The plane's normal: NX [NY [NZ]], any length; in 2D without z component, in 1D 1 0 0")
      ->required()
      ->expected(1, 3);
  gc_cmd->add_option("--s-crit", gc_s_crit,
                     "Critical bond stretch (default: the case's [fracture] s_crit, or s_crit from its G_c; "
                     "else the figures are per s_crit^2)");
  gc_cmd->footer(
      "Any crack plane of a box: its area inside the box is computed for any normal (a polygon in 3D, a "
      "segment times the thickness in 2D).");

  if (const std::string message = unknown_command(app, argc, argv); !message.empty()) {
    fmt::print(stderr, "error: {}\n", message);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*check_cmd) return check(case_path);
    if (*info_cmd) return info(case_path);
    if (*ghost_cmd) return ghost_forces(case_path, strain, out_dir);
    if (*gc_cmd) return gc(case_path, gc_point, gc_normal, gc_s_crit);
    return run(case_path, out_dir, quiet, run_cmd->remaining());
  } catch (const perimorph::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const perimorph::SolverError& e) {
    fmt::print(stderr, "solver error: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 4;
  }
}
