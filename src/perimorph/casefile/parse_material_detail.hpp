#pragma once
// Internal to the [[material]] reader: what parse_material.cpp (type, keys,
// isotropic, cauchy, the list of materials) and parse_material_anisotropic.cpp
// (orthotropic, transversely isotropic, material axes) share.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/casefile/toml_reader.hpp"

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace perimorph::casefile::detail::material {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline const std::vector<std::string> kIsotropicKeys{"E", "nu"};
/// Engineering constants; the last three are the shear moduli.
inline const std::vector<std::string> kEngineeringKeys{"E1",   "E2",  "E3",  "nu12", "nu13",
                                                       "nu23", "G12", "G13", "G23"};
/// Stiffness components: C1111, C2222, C3333, C1122, C1133, C2233, then the
/// shear ones in the order of MaterialSpec::shear_where (C2323, C1313, C1212).
inline const std::vector<std::string> kStiffnessKeys{"C1111", "C2222", "C3333", "C1122", "C1133",
                                                     "C2233", "C2323", "C1313", "C1212"};
inline const std::vector<std::string> kTransverseKeys{"E_in", "E_axis", "nu_axial", "nu_in", "G_axial"};

inline constexpr const char* kEngineeringList = "E1, E2, E3, nu12, nu13, nu23, G12, G13, G23";
inline constexpr const char* kStiffnessList = "C1111, C2222, C3333, C1122, C1133, C2233, C2323, C1313, C1212";
inline constexpr const char* kCentralForces = "with [nonlocal], where central forces determine them";

// ------------------------------------------------------------ shared helpers (parse_material.cpp)

double positive(const Value& v, std::string_view what);

/// The location of `key` in `t`: where it is given, else t's header labelled
/// with the key's path.
SourceLocation location_of(const Table& t, std::string_view key);

/// A value that [nonlocal] makes optional (one that central forces determine):
/// required without [nonlocal] (failing with `needs`), NaN when left out.
std::optional<Value> optional_in_nonlocal(const Table& t, const std::string& key, bool nonlocal,
                                          std::string_view needs);

// ------------------------------------------------------------ anisotropic (parse_material_anisotropic.cpp)

/// Orthotropic by engineering constants or by stiffness components (one form).
void read_orthotropic(const Table& t, MaterialSpec& m, bool nonlocal);

/// Transversely isotropic about the material axis e3.
void read_transverse(const Table& t, MaterialSpec& m, bool nonlocal);

/// Material axes from `rotation` (rows e1, e2, e3 in mesh coordinates):
/// checked to be a proper rotation within 1e-6, then made exactly orthonormal.
Mat3 read_rotation(const Value& v, int dim);

}  // namespace perimorph::casefile::detail::material
