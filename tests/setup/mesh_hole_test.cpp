// [[mesh.hole]] at model build time: the hole is cut from the box before the
// regions and cuts (which see the holed mesh), an empty or total hole is an
// error naming the case-file entry, and a holed plate solves (local and
// non-local) with the structured-mesh features degrading as documented.
// Cases are parsed from case-file text, as the CLI does.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace perimorph {
namespace {

/// A 48 × 24 plate with 16 × 8 cells (spacing 3): 17 × 9 nodes.
const std::string kPlate = R"(
[mesh]
dim = 2
lower = [0, 0]
upper = [48, 24]
cells = [16, 8]

[[material]]
name = "steel"
E = 200
nu = 0.3

[output]
vtu = false
)";

/// A disk of radius 5 at the centre: the centroids (24 ± 1.5, 12 ± 1.5),
/// (24 ± 4.5, 12 ± 1.5) and (24 ± 1.5, 12 ± 4.5), 12 cells; 5 nodes are no
/// longer used: (24, 9), (24, 12), (24, 15), (21, 12), (27, 12).
const std::string kHole = "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [24, 12]\nradius = 5\n";

mesh::Mesh mesh_of(const std::string& text) {
  return setup::build_mesh(casefile::parse_case_string(text, "holes.toml"));
}

std::string build_error(const std::string& text) {
  try {
    mesh_of(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(DriverMeshHole, DiskIsCutBeforeRegionsAndCuts) {
  const auto m = mesh_of(kPlate + kHole);
  EXPECT_EQ(m.num_cells(), 128 - 12);
  EXPECT_EQ(m.num_nodes(), 153 - 5);
  EXPECT_FALSE(m.structure.has_value());
  EXPECT_EQ(m.node_sets.at("xmin").size(), 9u);
  EXPECT_EQ(m.cell_sets.at("all").size(), 116u);

  // A region around the hole holds only the cells left: 16 - 12.
  const auto r =
      mesh_of(kPlate + kHole + "\n[[region]]\nname = \"ring\"\nlower = [18, 6]\nupper = [30, 18]\n");
  ASSERT_EQ(r.cell_sets.at("ring").size(), 4u);
  for (Index c : r.cell_sets.at("ring")) EXPECT_EQ(r.cell_region[static_cast<std::size_t>(c)], 1);

  // An edge crack from the left edge to the hole opens all the way: its 7
  // nodes (x = 0, 3, ..., 18 on y = 12) are split, the one at x = 18 too
  // because the hole is on its other side.
  const auto k = mesh_of(kPlate + kHole + "\n[[mesh.cut]]\nfrom = [0, 12]\nto = [18, 12]\n");
  EXPECT_EQ(k.num_nodes(), 153 - 5 + 7);
}

TEST(DriverMeshHole, EmptyOrTotalHoleIsAnErrorNamingTheEntry) {
  std::string msg =
      build_error(kPlate + "\n[[mesh.hole]]\nshape = \"disk\"\ncenter = [100, 12]\nradius = 5\n");
  EXPECT_TRUE(
      contains(msg,
               "holes.toml:16:1: key 'mesh.hole[1]': the hole (disk of radius 5 centred at [100, 12]) "
               "contains no cell centroid"))
      << msg;
  msg =
      build_error(kPlate + kHole + "\n[[mesh.hole]]\nshape = \"box\"\nlower = [-1, -1]\nupper = [49, 25]\n");
  EXPECT_TRUE(contains(msg,
                       "key 'mesh.hole[2]': the hole (box [-1, -1] to [49, 25]) contains the centroid of "
                       "every cell (116)"))
      << msg;
  // Between the centroids (1.5 + 3 i): nothing removed.
  msg = build_error(kPlate + "\n[[mesh.hole]]\nshape = \"box\"\nlower = [2, 2]\nupper = [4, 4]\n");
  EXPECT_TRUE(contains(msg, "the hole (box [2, 2] to [4, 4]) contains no cell centroid")) << msg;
}

TEST(DriverMeshHole, HoledPlateSolvesAndIsInEquilibrium) {
  // Bottom edge on rollers, its middle node pinned in x, the top pulled by a
  // unit traction: the bottom reaction balances the load 48 whatever the hole,
  // and the plate with the hole is softer (more work done by the same load).
  const std::string load =
      "\n[[node_set]]\nname = \"pin\"\nlower = [24, 0]\nupper = [24, 0]\n"
      "\n[[dirichlet]]\nset = \"ymin\"\nuy = 0\n"
      "\n[[dirichlet]]\nset = \"pin\"\nux = 0\n"
      "\n[[traction]]\nset = \"ymax\"\nvalue = [0, 1]\n"
      "\n[solver]\nrtol = 1e-12\n";
  const auto dir = std::filesystem::temp_directory_path() / "perimorph_test_mesh_hole_local";
  std::filesystem::remove_all(dir);
  const auto plain =
      run::run_static(setup::build_discretization(casefile::parse_case_string(kPlate + load, "plain.toml")),
                      {dir.string(), true});
  const auto model =
      setup::build_discretization(casefile::parse_case_string(kPlate + kHole + load, "hole.toml"));
  const auto run = run::run_static(model, {dir.string(), true});
  ASSERT_EQ(run.reaction_names.size(), 2u);
  EXPECT_NEAR(std::abs(run.reactions[0].y()), 48.0, 1e-8);
  EXPECT_NEAR(run.reactions[1].x(), 0.0, 1e-8);
  // Uniaxial stress without the hole: energy ½ · 48 · 24 (1 − ν²)/E (plane strain).
  EXPECT_NEAR(plain.strain_energy, 0.5 * 48 * 24 * (1 - 0.09) / 200, 1e-9);
  EXPECT_GT(run.strain_energy, 1.01 * plain.strain_energy);
  EXPECT_NEAR(run.strain_energy, run.external_work, 1e-9);
  std::filesystem::remove_all(dir);
}

TEST(DriverMeshHole, NonlocalRunReportsNoCrackAreaAndDiscreteCalibrationIsRefused) {
  std::string nonlocal = kPlate + kHole +
                         "\n[nonlocal]\nkernel = \"constant\"\nhorizon = 6\n"
                         "\n[alpha]\nvalue = 1\n"
                         "\n[fracture]\ns_crit = 1\n"
                         "\n[[dirichlet]]\nset = \"ymin\"\nux = 0\nuy = 0\n"
                         "\n[[dirichlet]]\nset = \"ymax\"\nux = 0\nuy = 0.01\n";
  nonlocal.replace(nonlocal.find("nu = 0.3"), 8, "nu = 0.25");  // bond-based
  const auto model = setup::build_discretization(casefile::parse_case_string(nonlocal, "nl.toml"));
  const auto dir = std::filesystem::temp_directory_path() / "perimorph_test_mesh_hole_nonlocal";
  std::filesystem::remove_all(dir);
  const auto run = run::run_static(model, {dir.string(), true});
  ASSERT_EQ(run.history.size(), 1u);
  EXPECT_TRUE(std::isnan(run.history[0].crack_area));  // needs a structured mesh
  EXPECT_GT(run.strain_energy, 0.0);
  std::filesystem::remove_all(dir);

  std::string discrete = nonlocal;
  discrete.replace(discrete.find("horizon = 6"), 11, "horizon = 6\ncalibration = \"discrete\"");
  try {
    setup::build_discretization(casefile::parse_case_string(discrete, "nl.toml"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "calibration = \"discrete\" needs a structured box mesh")) << e.what();
  }
}

}  // namespace
}  // namespace perimorph
