#pragma once
// The reports of `perimorph info` and `perimorph gc`: figures computed from a
// set-up without running it, as text (the CLI prints them; tests read them).

#include "perimorph/core/types.hpp"

#include <optional>
#include <string>

namespace perimorph::setup {
struct Discretization;
}

namespace perimorph::diagnostics {

/// `info`: mesh and dofs; with [nonlocal] the kernel and its calibration
/// (isotropic: ĉ, the equivalent λ = μ, E, ν and the G_c factor of THEORY §5;
/// anisotropic: the coefficients of Y, its range and how closely c
/// reproduces C0, THEORY §2.1), the α zones, the bond count and the horizon
/// edge rule. `path` names the case in the first line.
std::string info_report(const setup::Discretization& disc, const std::string& path);

/// `gc`: the critical energy release rate of the crack plane through `point`
/// with normal `normal` (any length; effective_gc.hpp): the bulk closed form,
/// the actual geometry and the bulk window, with s_crit from `s_option`, the
/// case's [fracture], or per s_crit² (setup/critical_stretch.hpp). Throws
/// InputError for a case without [nonlocal].
std::string gc_report(const setup::Discretization& disc, const std::string& path, const Vec3& point,
                      const Vec3& normal, std::optional<double> s_option);

}  // namespace perimorph::diagnostics
