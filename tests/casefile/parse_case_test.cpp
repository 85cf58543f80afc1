// Case-file parser: good cases give the documented values and defaults; every
// file in tests/data/bad_cases fails with a located, actionable message.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/casefile/suggest.hpp"
#include "perimorph/core/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace perimorph::casefile {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMinimal2D = R"(
[mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]

[[material]]
name = "steel"
E = 200
nu = 0.3
)";

/// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const std::string& path = "inline.toml") {
  try {
    parse_case_string(text, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(CaseFileParse, MinimalCaseTakesDefaults) {
  const CaseConfig c = parse_case_string(kMinimal2D, "runs/minimal.toml");
  EXPECT_EQ(c.path, "runs/minimal.toml");
  EXPECT_EQ(c.title, "");
  EXPECT_EQ(c.dim(), 2);
  EXPECT_EQ(c.mesh.box.lower, Vec3(0, 0, 0));
  EXPECT_EQ(c.mesh.box.upper, Vec3(4, 2, 0));
  EXPECT_EQ(c.mesh.box.cells[0], 4);
  EXPECT_EQ(c.mesh.box.cells[1], 2);
  EXPECT_EQ(c.mesh.box.cells[2], 1);
  EXPECT_TRUE(c.mesh.cuts.empty());
  EXPECT_TRUE(c.regions.empty());
  EXPECT_EQ(c.model.plane, PlaneMode::strain);
  EXPECT_EQ(c.model.thickness, 1.0);
  EXPECT_EQ(c.model.local_quadrature, 2);
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "steel");
  EXPECT_EQ(c.materials[0].region, "all");
  EXPECT_EQ(c.materials[0].kind, MaterialKind::isotropic);
  EXPECT_EQ(c.materials[0].E, 200.0);  // an integer where a number is expected
  EXPECT_EQ(c.materials[0].nu, 0.3);
  EXPECT_TRUE(c.dirichlet.empty());
  EXPECT_TRUE(c.tractions.empty());
  EXPECT_EQ(c.loading.factors, std::vector<double>{1.0});
  EXPECT_EQ(c.loading.body_force, Vec3::Zero());
  EXPECT_EQ(c.solver.petsc_options, "");
  EXPECT_EQ(c.solver.rtol, 1e-10);
  EXPECT_EQ(c.solver.max_iterations, 10000);
  EXPECT_EQ(c.output.directory, "output");
  EXPECT_EQ(c.output.basename, "minimal");
  EXPECT_TRUE(c.output.vtu);
  EXPECT_EQ(c.output.every, 1);
}

TEST(CaseFileParse, FullTwoDimensionalCase) {
  const std::string text = R"(
[case]
title = "everything"

[mesh]
type = "box"
dim = 2
lower = [-1.0, 0]
upper = [3, 2.5]
cells = [8, 5]

[[mesh.cut]]
from = [-1, 1]
to = [1, 1]

[[region]]
name = "left"
lower = [-1, 0]
upper = [1, 2.5]

[[region]]
name = "right"
lower = [1, 0]
upper = [3, 2.5]

[model]
plane = "stress"
thickness = 0.5
local_quadrature = 3

[[material]]
name = "matrix"
E = 1000.5
nu = -0.2

[[material]]
name = "ply"
region = "right"
type = "orthotropic"
E1 = 100
E2 = 50
E3 = 50
nu12 = 0.25
nu13 = 0.25
nu23 = 0.3
G12 = 20
G13 = 20
G23 = 19
rotation = [[0.8660254037844387, 0.5, 0], [-0.5, 0.8660254037844387, 0], [0, 0, 1]]

[[dirichlet]]
set = "xmin"
ux = 0
uy = -0.25

[[dirichlet]]
set = "boundary"
gradient = [[0.001, 0.002], [0.003, 0.004]]
offset = [0.5, 0.6]
components = ["y"]

[[traction]]
set = "ymax"
value = [0, 7.5]

[loading]
increments = 4
body_force = [0, -9.81]

[solver]
petsc_options = "-ksp_type cg -pc_type gamg"
rtol = 1e-8
max_iterations = 500

[output]
directory = "/tmp/out"
basename = "full"
vtu = false
every = 2
)";
  const CaseConfig c = parse_case_string(text, "full_case.toml");
  EXPECT_EQ(c.title, "everything");
  EXPECT_EQ(c.mesh.box.lower, Vec3(-1, 0, 0));
  EXPECT_EQ(c.mesh.box.upper, Vec3(3, 2.5, 0));
  EXPECT_EQ(c.mesh.box.cells[0], 8);
  EXPECT_EQ(c.mesh.box.cells[1], 5);
  ASSERT_EQ(c.mesh.cuts.size(), 1u);
  EXPECT_EQ(c.mesh.cuts[0].origin, Vec3(-1, 1, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge1, Vec3(2, 0, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge2, Vec3::Zero());
  EXPECT_EQ(c.mesh.cuts[0].where.key, "mesh.cut[1]");
  EXPECT_EQ(c.mesh.cuts[0].where.line, 12);

  ASSERT_EQ(c.regions.size(), 2u);
  EXPECT_EQ(c.regions[0].name, "left");
  EXPECT_EQ(c.regions[0].id, 1);
  EXPECT_EQ(c.regions[1].name, "right");
  EXPECT_EQ(c.regions[1].id, 2);
  EXPECT_EQ(c.regions[1].lower, Vec3(1, 0, 0));
  EXPECT_EQ(c.regions[1].upper, Vec3(3, 2.5, 0));

  EXPECT_EQ(c.model.plane, PlaneMode::stress);
  EXPECT_EQ(c.model.thickness, 0.5);
  EXPECT_EQ(c.model.local_quadrature, 3);

  ASSERT_EQ(c.materials.size(), 2u);
  EXPECT_EQ(c.materials[0].E, 1000.5);
  EXPECT_EQ(c.materials[0].nu, -0.2);
  const MaterialSpec& ply = c.materials[1];
  EXPECT_EQ(ply.kind, MaterialKind::orthotropic);
  EXPECT_EQ(ply.region, "right");
  EXPECT_EQ(ply.E1, 100.0);
  EXPECT_EQ(ply.E2, 50.0);
  EXPECT_EQ(ply.nu23, 0.3);
  EXPECT_EQ(ply.G23, 19.0);
  // The columns of `axes` are the material axes (the rows of `rotation`).
  const double s = std::sqrt(3.0) / 2;
  EXPECT_NEAR((ply.axes.col(0) - Vec3(s, 0.5, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((ply.axes.col(1) - Vec3(-0.5, s, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((ply.axes.col(2) - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_EQ(ply.where.key, "material[2]");

  ASSERT_EQ(c.dirichlet.size(), 2u);
  const DirichletSpec& fixed = c.dirichlet[0];
  EXPECT_EQ(fixed.set, "xmin");
  EXPECT_TRUE(fixed.constrained[0]);
  EXPECT_TRUE(fixed.constrained[1]);
  EXPECT_FALSE(fixed.constrained[2]);
  EXPECT_EQ(fixed.value, Vec3(0, -0.25, 0));
  EXPECT_EQ(fixed.gradient, Mat3::Zero());
  const DirichletSpec& affine = c.dirichlet[1];
  EXPECT_EQ(affine.set, "boundary");
  EXPECT_FALSE(affine.constrained[0]);  // components = ["y"]
  EXPECT_TRUE(affine.constrained[1]);
  EXPECT_FALSE(affine.constrained[2]);
  EXPECT_EQ(affine.value, Vec3(0, 0.6, 0));  // unconstrained components are zeroed
  Mat3 g = Mat3::Zero();
  g(1, 0) = 0.003;
  g(1, 1) = 0.004;
  EXPECT_EQ(affine.gradient, g);

  ASSERT_EQ(c.tractions.size(), 1u);
  EXPECT_EQ(c.tractions[0].set, "ymax");
  EXPECT_EQ(c.tractions[0].value, Vec3(0, 7.5, 0));

  EXPECT_EQ(c.loading.factors, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(c.loading.body_force, Vec3(0, -9.81, 0));
  EXPECT_EQ(c.solver.petsc_options, "-ksp_type cg -pc_type gamg");
  EXPECT_EQ(c.solver.rtol, 1e-8);
  EXPECT_EQ(c.solver.max_iterations, 500);
  EXPECT_EQ(c.output.directory, "/tmp/out");
  EXPECT_EQ(c.output.basename, "full");
  EXPECT_FALSE(c.output.vtu);
  EXPECT_EQ(c.output.every, 2);
}

TEST(CaseFileParse, GradientDefaultsToAllComponentsAndZeroOffset) {
  const CaseConfig c = parse_case_string(std::string(kMinimal2D) + R"(
[[dirichlet]]
set = "boundary"
gradient = [[1, 2], [3, 4]]
)",
                                         "g.toml");
  ASSERT_EQ(c.dirichlet.size(), 1u);
  const DirichletSpec& d = c.dirichlet[0];
  EXPECT_TRUE(d.constrained[0]);
  EXPECT_TRUE(d.constrained[1]);
  EXPECT_FALSE(d.constrained[2]);
  EXPECT_EQ(d.value, Vec3::Zero());
  Mat3 g = Mat3::Zero();
  g << 1, 2, 0, 3, 4, 0, 0, 0, 0;
  EXPECT_EQ(d.gradient, g);
}

TEST(CaseFileParse, ExplicitLoadFactors) {
  const CaseConfig c = parse_case_string(std::string(kMinimal2D) + "\n[loading]\nfactors = [0.5, 1, 0.25]\n", "f.toml");
  EXPECT_EQ(c.loading.factors, (std::vector<double>{0.5, 1.0, 0.25}));
}

TEST(CaseFileParse, OneDimensionalCaseWithCut) {
  const CaseConfig c = parse_case_string(R"(
[mesh]
dim = 1
lower = [0]
upper = [10]
cells = [10]
[[mesh.cut]]
at = 4
[model]
thickness = 2.5
[[material]]
name = "bar"
E = 1
nu = 0
[[dirichlet]]
set = "xmin"
ux = 0
)",
                                         "bar.toml");
  EXPECT_EQ(c.dim(), 1);
  EXPECT_EQ(c.mesh.box.cells[0], 10);
  ASSERT_EQ(c.mesh.cuts.size(), 1u);
  EXPECT_EQ(c.mesh.cuts[0].origin, Vec3(4, 0, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge1, Vec3::Zero());
  EXPECT_EQ(c.model.thickness, 2.5);
  EXPECT_EQ(c.output.basename, "bar");
}

TEST(CaseFileParse, ThreeDimensionalCut) {
  const CaseConfig c = parse_case_string(R"(
[mesh]
dim = 3
lower = [0, 0, 0]
upper = [2, 2, 2]
cells = [2, 2, 2]
[[mesh.cut]]
origin = [0, 1, 0]
edge1 = [1, 0, 0]
edge2 = [0, 0, 2]
[[material]]
name = "m"
E = 1
nu = 0.25
[[dirichlet]]
set = "zmin"
uz = 0
)",
                                         "cube.toml");
  ASSERT_EQ(c.mesh.cuts.size(), 1u);
  EXPECT_EQ(c.mesh.cuts[0].origin, Vec3(0, 1, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge1, Vec3(1, 0, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge2, Vec3(0, 0, 2));
  ASSERT_EQ(c.dirichlet.size(), 1u);
  EXPECT_FALSE(c.dirichlet[0].constrained[0]);
  EXPECT_TRUE(c.dirichlet[0].constrained[2]);
}

TEST(CaseFileParse, LocationsAndDescribe) {
  const CaseConfig c = parse_case_string(std::string(kMinimal2D) + "\n[[dirichlet]]\nset = \"xmin\"\nux = 0\n",
                                         "loc.toml");
  EXPECT_EQ(c.materials[0].where.file, "loc.toml");
  EXPECT_EQ(c.materials[0].where.line, 8);
  EXPECT_EQ(c.materials[0].where.key, "material[1]");
  EXPECT_EQ(c.dirichlet[0].where.line, 13);
  EXPECT_EQ(c.dirichlet[0].where.describe(), "loc.toml:13:1: key 'dirichlet[1]'");
  const SourceLocation set{"case.toml", 12, 5, "dirichlet[2].set"};
  EXPECT_EQ(set.describe(), "case.toml:12:5: key 'dirichlet[2].set'");
}

TEST(CaseFileParse, ExampleCaseIsValid) {
  const CaseConfig c = parse_case_file(PERIMORPH_SOURCE_DIR "/examples/plate_tension/case.toml");
  EXPECT_EQ(c.dim(), 2);
  EXPECT_EQ(c.model.plane, PlaneMode::strain);
  EXPECT_EQ(c.mesh.box.upper, Vec3(48, 48, 0));
  EXPECT_EQ(c.mesh.box.cells[0], 48);
  EXPECT_EQ(c.mesh.box.cells[1], 48);
  ASSERT_EQ(c.mesh.cuts.size(), 1u);
  EXPECT_EQ(c.mesh.cuts[0].origin, Vec3(0, 24, 0));
  EXPECT_EQ(c.mesh.cuts[0].edge1, Vec3(24, 0, 0));
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].E, 251300.0);
  EXPECT_EQ(c.materials[0].nu, 0.25);
  ASSERT_EQ(c.dirichlet.size(), 2u);
  EXPECT_EQ(c.dirichlet[1].set, "ymax");
  EXPECT_EQ(c.dirichlet[1].value[1], 0.048);
  EXPECT_EQ(c.loading.factors.size(), 4u);
  EXPECT_EQ(c.solver.petsc_options, "-ksp_type cg -pc_type gamg");
}

TEST(CaseFileErrors, MissingFileIsReported) {
  try {
    parse_case_file("/nonexistent/dir/x.toml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "cannot open case file '/nonexistent/dir/x.toml'")) << e.what();
  }
}

TEST(CaseFileErrors, MessageNamesKeyValueAndRange) {
  std::string text = kMinimal2D;
  text.replace(text.find("nu = 0.3"), 8, "nu = 0.7");
  const std::string msg = error_of(text, "m.toml");
  EXPECT_EQ(msg.rfind("m.toml:11:6: key 'material[1].nu': ", 0), 0u) << msg;
  EXPECT_TRUE(contains(msg, "nu = 0.7")) << msg;
  EXPECT_TRUE(contains(msg, "-1 < nu < 0.5")) << msg;
}

TEST(CaseFileErrors, MissingKeyPointsAtItsTable) {
  std::string text = kMinimal2D;
  text.erase(text.find("cells = [4, 2]"), 14);
  EXPECT_EQ(error_of(text, "m.toml").rfind("m.toml:2:1: key 'mesh.cells': missing required key", 0), 0u);
}

TEST(CaseFileErrors, EveryBadCaseFailsWithALocatedMessage) {
  const fs::path folder = PERIMORPH_TEST_DATA "/bad_cases";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 20u) << "bad cases in " << folder;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    std::ifstream in(file);
    std::string first_line;
    std::getline(in, first_line);
    const std::string tag = "# expect: ";
    ASSERT_EQ(first_line.rfind(tag, 0), 0u) << "first line must be '" << tag << "<substring>'";
    const std::string expected = first_line.substr(tag.size());
    std::string message;
    try {
      parse_case_file(file.string());
      ADD_FAILURE() << "parsed without error";
      continue;
    } catch (const InputError& e) {
      message = e.what();
    }
    const std::regex located(std::regex_replace(file.string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                             R"(:[0-9]+:[0-9]+: .+)");
    EXPECT_TRUE(std::regex_match(message, located)) << "not 'FILE:LINE:COL: ...': " << message;
    EXPECT_TRUE(contains(message, expected)) << "expected '" << expected << "' in: " << message;
  }
}

TEST(CaseFileSuggest, ClosestMatch) {
  const std::vector<std::string> keys{"mesh", "material", "model", "dirichlet", "traction"};
  EXPECT_EQ(closest_match("matrial", keys), "material");
  EXPECT_EQ(closest_match("Mesh", keys), "mesh");
  EXPECT_EQ(closest_match("dirchlet", keys), "dirichlet");
  EXPECT_EQ(closest_match("zzzzzz", keys), "");
  EXPECT_EQ(closest_match("x", {"E", "nu"}), "");
  EXPECT_EQ(closest_match("e1", {"E1", "E2"}), "E1");
  EXPECT_EQ(closest_match("dir", {"directory", "vtu"}), "directory");
  EXPECT_EQ(closest_match("anything", {}), "");
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
}

}  // namespace
}  // namespace perimorph::casefile
