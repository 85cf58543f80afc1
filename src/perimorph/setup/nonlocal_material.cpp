#include "perimorph/setup/nonlocal_material.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/peridynamics/anisotropy.hpp"

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <cmath>
#include <limits>

namespace perimorph::setup {

namespace {

using casefile::MaterialSpec;
using peridynamics::AngularKind;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Shear entry s = 0, 1, 2 ↔ Voigt 3, 4, 5 ↔ the material axes pair (1,2), (0,2), (0,1).
constexpr int shear_pair[3][2] = {{1, 2}, {0, 2}, {0, 1}};

int shear_index(const std::string& tensor_name) {
  if (tensor_name == "C2323") return 0;
  if (tensor_name == "C1313") return 1;
  return 2;
}

/// The case-file key that sets shear entry s.
std::string shear_key(const MaterialSpec& m, int s) {
  if (m.by_stiffness) return s == 0 ? "C2323" : s == 1 ? "C1313" : "C1212";
  if (m.kind == casefile::MaterialKind::transversely_isotropic) return s == 2 ? "nu_in" : "G_axial";
  return s == 0 ? "G23" : s == 1 ? "G13" : "G12";
}

const casefile::SourceLocation& shear_where(const MaterialSpec& m, int s) {
  const auto& w = m.shear_where[static_cast<std::size_t>(s)];
  return w.line > 0 ? w : m.where;
}

/// The 3D stiffness in material axes; shear entries NaN where left out.
Voigt6 material_axes_stiffness(MaterialSpec& m, std::vector<std::string>& notes) {
  if (m.by_stiffness) return m.stiffness;
  if (m.kind == casefile::MaterialKind::transversely_isotropic && std::isnan(m.nu12)) {
    // C1122 = C1111/3 (eq. 2.88) with S = [[a, b, c], [b, a, c], [c, c, d]]:
    // 3 (c² − b d) = a d − c², hence nu_in = (1 − 4 nu_axial² E_axis / E_in) / 3.
    m.nu12 = (1.0 - 4.0 * m.nu13 * m.nu13 * m.E3 / m.E1) / 3.0;
    if (!(m.nu12 > -1.0))
      throw InputError(fmt::format(
          "{}: material '{}': central forces fix the in-plane Poisson ratio nu_in = (1 - 4 nu_axial^2 "
          "E_axis / E_in) / 3 = {:.6g}, which is not above -1 (an unstable material): lower nu_axial or "
          "E_axis / E_in",
          m.where.describe(), m.name, m.nu12));
    m.G12 = m.E1 / (2.0 * (1.0 + m.nu12));
    notes.push_back(fmt::format("nu_in = {:.6g} (central forces: C1122 = C1111/3, eq. 2.88)", m.nu12));
  }
  Eigen::Matrix3d S;
  S << 1 / m.E1, -m.nu12 / m.E1, -m.nu13 / m.E1,  //
      -m.nu12 / m.E1, 1 / m.E2, -m.nu23 / m.E2,   //
      -m.nu13 / m.E1, -m.nu23 / m.E2, 1 / m.E3;
  Voigt6 C = Voigt6::Zero();
  C.topLeftCorner<3, 3>() = S.inverse();
  C(3, 3) = m.G23;
  C(4, 4) = m.G13;
  C(5, 5) = m.G12;
  return C;
}

std::string nearest_listing(const Eigen::MatrixXd& C, int dim) {
  if (dim == 2)
    return fmt::format("C1111 = {:.6g}, C2222 = {:.6g}, C1122 = C1212 = {:.6g}", C(0, 0), C(1, 1), C(0, 1));
  return fmt::format("C1122 = C1212 = {:.6g}, C1133 = C1313 = {:.6g}, C2233 = C2323 = {:.6g}", C(0, 1),
                     C(0, 2), C(1, 2));
}

[[noreturn]] void cauchy_error(const MaterialSpec& m, const peridynamics::CauchyViolation& v, int s,
                               const std::string& context, const Eigen::MatrixXd& nearest, int dim) {
  const std::string key = shear_key(m, s);
  const double off = 100.0 * (v.shear_value - v.normal_value) / std::abs(v.normal_value);
  std::string fix = fmt::format("leave {} out to have it set from the relation", key);
  if (key == "nu_in") fix = "leave nu_in out to have it set from the relation (C1122 = C1111/3, eq. 2.88)";
  throw InputError(fmt::format(
      "{}: material '{}': bond-based (central-force) peridynamics imposes the Cauchy relation {}{} (THEORY "
      "§2.1), but this material has {} = {:.6g} and {} = {:.6g} ({} off by {:+.3g} %). Either {}, or set "
      "cauchy = \"nearest\" in this material to use the nearest central-force material, its totally "
      "symmetric part ({})",
      shear_where(m, s).describe(), m.name, v.relation, context, v.shear, v.shear_value, v.normal,
      v.normal_value, v.shear, off, fix, nearest_listing(nearest, dim)));
}

void check_positive_definite(const MaterialSpec& m, const Eigen::MatrixXd& C0) {
  if (Eigen::LLT<Eigen::MatrixXd>(C0).info() != Eigen::Success)
    throw InputError(fmt::format(
        "{}: material '{}': with its shear moduli set by the Cauchy relations (central forces), the "
        "stiffness is not positive definite (a shear modulus C1122, C1133 or C2233 is zero or negative); "
        "bond-based peridynamics cannot represent this material",
        m.where.describe(), m.name));
}

void resolve_isotropic(const casefile::CaseConfig& config, NonlocalMaterial& out) {
  const MaterialSpec& m = out.spec;
  const int dim = config.dim();
  const PlaneMode mode = config.model.plane;
  out.E = m.E;
  if (dim == 1) {
    out.nu = 0.0;
  } else if (std::isnan(m.nu)) {
    out.nu = peridynamics::cauchy_poisson_ratio(dim, mode);
  } else if (auto problem = peridynamics::cauchy_problem(dim, mode, m.nu); !problem.empty()) {
    if (m.cauchy != casefile::CauchyRule::nearest)
      throw InputError(
          fmt::format("{}: material '{}': {}; or set cauchy = \"nearest\" to use the nearest "
                      "central-force material",
                      m.nu_where.line > 0 ? m.nu_where.describe() : m.where.describe(), m.name, problem));
    const Eigen::MatrixXd given =
        fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{m.E, m.nu}), dim, mode);
    const double mu = peridynamics::nearest_central_force(given, dim)(0, 1);
    out.nu = peridynamics::cauchy_poisson_ratio(dim, mode);
    // λ = μ: E = 5μ/2 (3D, plane strain) or 8μ/3 (plane stress, reduced tensor).
    out.E = dim == 2 && mode == PlaneMode::stress ? 8.0 * mu / 3.0 : 2.5 * mu;
    out.notes.push_back(fmt::format("cauchy = \"nearest\": E = {:.6g}, nu = {:.6g} (lambda = mu = {:.6g})",
                                    out.E, out.nu, mu));
  } else {
    out.nu = m.nu;
  }
  out.C0 = fem::reduce_stiffness(fem::stiffness_voigt(fem::IsotropicElasticity{out.E, out.nu}), dim, mode);
}

void resolve_anisotropic(const casefile::CaseConfig& config, NonlocalMaterial& out) {
  MaterialSpec& m = out.spec;
  const int dim = config.dim();
  const PlaneMode mode = config.model.plane;
  Voigt6 C = material_axes_stiffness(m, out.notes);
  // In 2D the in-plane pair is the two material axes not along z; its shear
  // obeys Cauchy on the reduced (plane strain or plane stress) tensor.
  int normal_axis = 2;
  if (dim == 2) m.axes.row(2).cwiseAbs().maxCoeff(&normal_axis);
  for (int s = 0; s < 3; ++s) {
    if (!std::isnan(C(3 + s, 3 + s))) continue;
    const int i = shear_pair[s][0], j = shear_pair[s][1];
    double value = C(i, j);
    if (dim == 2 && mode == PlaneMode::stress && i != normal_axis && j != normal_axis)
      value -= C(i, normal_axis) * C(j, normal_axis) / C(normal_axis, normal_axis);
    C(3 + s, 3 + s) = value;
    const std::string note = fmt::format("{} = {:.6g} (Cauchy relation)", shear_key(m, s), value);
    if ((dim == 3 || (i != normal_axis && j != normal_axis)) &&
        (out.notes.empty() || out.notes.back() != note))
      out.notes.push_back(note);
  }
  if (dim == 1) {  // uniaxial stress: an isotropic bar with E = C0
    out.C_material = C;
    out.C0 = fem::reduce_stiffness(fem::rotate_stiffness(C, m.axes), 1, mode);
    out.kind = AngularKind::isotropic;
    out.E = out.C0(0, 0);
  } else if (dim == 3) {
    const auto violations = peridynamics::cauchy_violations(C, 3);
    if (!violations.empty()) {
      const Eigen::MatrixXd nearest = peridynamics::nearest_central_force(C, 3);
      if (m.cauchy != casefile::CauchyRule::nearest)
        cauchy_error(m, violations.front(), shear_index(violations.front().shear), "", nearest, 3);
      C = nearest;
      out.notes.push_back("cauchy = \"nearest\": " + nearest_listing(nearest, 3));
    }
    out.C_material = C;
    out.C0 = fem::rotate_stiffness(C, m.axes);
    const bool ti = m.kind == casefile::MaterialKind::transversely_isotropic &&
                    std::abs(C(0, 1) - C(0, 0) / 3.0) <= 1e-9 * C(0, 0);
    out.kind = ti ? AngularKind::transversely_isotropic : AngularKind::orthotropic;
    if (m.kind == casefile::MaterialKind::transversely_isotropic && !ti)
      out.notes.push_back("C1122 != C1111/3 after cauchy = \"nearest\": orthotropic micromodulus used");
  } else {
    out.C_material = C;
    out.C0 = fem::reduce_stiffness(fem::rotate_stiffness(C, m.axes), dim, mode);
    const auto violations = peridynamics::cauchy_violations(out.C0, 2);
    if (!violations.empty()) {
      const Eigen::MatrixXd nearest = peridynamics::nearest_central_force(out.C0, 2);
      const int s = normal_axis == 0 ? 0 : normal_axis == 1 ? 1 : 2;  // the in-plane pair
      if (m.cauchy != casefile::CauchyRule::nearest)
        cauchy_error(
            m, violations.front(), s,
            mode == PlaneMode::stress ? " on the plane-stress tensor" : " on the plane-strain tensor",
            nearest, 2);
      out.C0 = nearest;
      out.notes.push_back("cauchy = \"nearest\": " + nearest_listing(nearest, 2));
    }
    out.kind = AngularKind::planar;
  }
  check_positive_definite(m, out.C0);
}

}  // namespace

NonlocalMaterial nonlocal_material(const casefile::CaseConfig& config) {
  if (config.materials.size() != 1)
    throw InputError(
        fmt::format("{}: a case with [nonlocal] needs exactly one material (the micromodulus is "
                    "calibrated from it); this case has {}",
                    config.nonlocal.where.describe(), config.materials.size()));
  NonlocalMaterial out;
  out.spec = config.materials.front();
  if (out.spec.kind == casefile::MaterialKind::isotropic)
    resolve_isotropic(config, out);
  else
    resolve_anisotropic(config, out);
  return out;
}

peridynamics::Calibration calibrate_kernel(peridynamics::Micromodulus& kernel,
                                           const NonlocalMaterial& material, int dim, PlaneMode mode) {
  kernel.angular = {};
  if (material.kind == AngularKind::isotropic)
    return peridynamics::calibrate_isotropic(kernel, dim, mode, material.E);
  kernel.angular = peridynamics::calibrate_angular(
      kernel, dim, dim == 3 ? Eigen::MatrixXd(material.C_material) : material.C0, material.spec.axes,
      material.kind);
  peridynamics::Calibration cal;
  cal.scale = 1.0;
  cal.lame = cal.E = cal.nu = cal.gc_factor = nan;
  return cal;
}

}  // namespace perimorph::setup
