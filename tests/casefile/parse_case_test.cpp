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
#include <limits>
#include <regex>
#include <string>
#include <utility>
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
  const CaseConfig c =
      parse_case_string(std::string(kMinimal2D) + "\n[loading]\nfactors = [0.5, 1, 0.25]\n", "f.toml");
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
  const CaseConfig c =
      parse_case_string(std::string(kMinimal2D) + "\n[[dirichlet]]\nset = \"xmin\"\nux = 0\n", "loc.toml");
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

// ------------------------------------------------------------ [nonlocal], [alpha]

constexpr const char* kMinimal3D = R"(
[mesh]
dim = 3
lower = [0, 0, 0]
upper = [4, 4, 4]
cells = [4, 4, 4]

[[material]]
name = "steel"
E = 200
nu = 0.25
)";

constexpr const char* kMinimal1D = R"(
[mesh]
dim = 1
lower = [0]
upper = [10]
cells = [10]

[[material]]
name = "bar"
E = 1
nu = 0.25
)";

TEST(CaseFileNonlocal, AbsentSectionsGiveLocalDefaults) {
  const CaseConfig c = parse_case_string(kMinimal2D, "local.toml");
  EXPECT_FALSE(c.nonlocal.enabled);
  EXPECT_EQ(c.alpha.value, 0.0);
  EXPECT_TRUE(c.alpha.regions.empty());
  EXPECT_EQ(c.materials[0].nu_where.key, "material[1].nu");
  EXPECT_EQ(c.materials[0].nu_where.line, 11);
  EXPECT_EQ(c.materials[0].nu_where.column, 6);
}

TEST(CaseFileNonlocal, FullSectionAndConstantAlpha) {
  const CaseConfig c = parse_case_string(std::string(kMinimal2D) + R"(
[nonlocal]
kernel = "exponential"
horizon = 2.625
length = 0.525
quadrature = 3
discretization = "discontinuous-constant"
coupling = "partition"

[alpha]
value = 1.0
)",
                                         "nl.toml");
  const NonlocalSpec& n = c.nonlocal;
  EXPECT_TRUE(n.enabled);
  EXPECT_EQ(n.kernel, KernelKind::exponential);
  EXPECT_EQ(n.horizon, 2.625);
  EXPECT_EQ(n.length, 0.525);
  EXPECT_EQ(n.quadrature, 3);
  EXPECT_EQ(n.discretization, Discretization::discontinuous_constant);
  EXPECT_EQ(n.coupling, Coupling::partition);
  EXPECT_EQ(n.where.key, "nonlocal");
  EXPECT_EQ(n.where.line, 13);
  EXPECT_EQ(c.alpha.value, 1.0);
  EXPECT_TRUE(c.alpha.regions.empty());
  EXPECT_EQ(c.alpha.where.key, "alpha");
  EXPECT_EQ(c.alpha.where.line, 21);
  EXPECT_EQ(c.materials[0].nu, 0.3);  // a given nu is kept (checked later by the physics layer)
  EXPECT_EQ(c.materials[0].nu_where.describe(), "nl.toml:11:6: key 'material[1].nu'");
}

TEST(CaseFileNonlocal, DefaultsAndOptionalNu) {
  const CaseConfig c = parse_case_string(R"(
[mesh]
dim = 2
lower = [0, 0]
upper = [4, 2]
cells = [4, 2]

[[material]]
name = "ceramic"
E = 251300

[nonlocal]
kernel = "constant"
horizon = 3
)",
                                         "d.toml");
  const NonlocalSpec& n = c.nonlocal;
  EXPECT_TRUE(n.enabled);
  EXPECT_EQ(n.kernel, KernelKind::constant);
  EXPECT_EQ(n.horizon, 3.0);
  EXPECT_EQ(n.length, 0.0);
  EXPECT_EQ(n.quadrature, 4);
  EXPECT_EQ(n.discretization, Discretization::continuous);
  EXPECT_EQ(n.coupling, Coupling::morphing);
  EXPECT_EQ(c.alpha.value, 0.0);  // no [alpha]: purely local everywhere
  EXPECT_TRUE(c.alpha.regions.empty());
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].E, 251300.0);
  EXPECT_TRUE(std::isnan(c.materials[0].nu));
  // nu left out: its location is the material's header, with the key nu.
  EXPECT_EQ(c.materials[0].nu_where.describe(), "d.toml:8:1: key 'material[1].nu'");
}

TEST(CaseFileNonlocal, EveryKernel) {
  const std::pair<const char*, KernelKind> kernels[] = {{"constant", KernelKind::constant},
                                                        {"conical", KernelKind::conical},
                                                        {"exponential", KernelKind::exponential},
                                                        {"gaussian", KernelKind::gaussian},
                                                        {"pmb", KernelKind::pmb}};
  for (const auto& [name, kind] : kernels) {
    SCOPED_TRACE(name);
    const bool scaled = kind == KernelKind::exponential || kind == KernelKind::gaussian;
    const CaseConfig c = parse_case_string(std::string(kMinimal2D) + "\n[nonlocal]\nkernel = \"" + name +
                                               "\"\nhorizon = 1.5\n" + (scaled ? "length = 0.25\n" : ""),
                                           "k.toml");
    EXPECT_EQ(c.nonlocal.kernel, kind);
    EXPECT_EQ(c.nonlocal.length, scaled ? 0.25 : 0.0);
  }
  const CaseConfig c = parse_case_string(
      std::string(kMinimal2D) +
          "\n[nonlocal]\nkernel = \"conical\"\nhorizon = 1\ndiscretization = \"discontinuous\"\n",
      "dg.toml");
  EXPECT_EQ(c.nonlocal.discretization, Discretization::discontinuous);
}

TEST(CaseFileAlpha, BallAndSlabIn2D) {
  const CaseConfig c = parse_case_string(std::string(kMinimal2D) + R"(
[nonlocal]
kernel = "conical"
horizon = 1

[alpha]
[[alpha.region]]
shape = "ball"
center = [2, 1]
radius = 0.5
transition = 6.0
profile = "linear"

[[alpha.region]]
shape = "slab"
point = [2, 0]
normal = [3, 4]
half_width = 0
)",
                                         "a.toml");
  ASSERT_EQ(c.alpha.regions.size(), 2u);
  EXPECT_EQ(c.alpha.value, 0.0);
  EXPECT_EQ(c.alpha.where.line, 17);
  const AlphaRegionSpec& ball = c.alpha.regions[0];
  EXPECT_EQ(ball.shape, AlphaShapeKind::ball);
  EXPECT_EQ(ball.point, Vec3(2, 1, 0));
  EXPECT_EQ(ball.radius, 0.5);
  EXPECT_EQ(ball.transition, 6.0);
  EXPECT_EQ(ball.profile, AlphaProfile::linear);
  EXPECT_EQ(ball.where.key, "alpha.region[1]");
  EXPECT_EQ(ball.where.line, 18);
  const AlphaRegionSpec& slab = c.alpha.regions[1];
  EXPECT_EQ(slab.shape, AlphaShapeKind::slab);
  EXPECT_EQ(slab.point, Vec3(2, 0, 0));
  EXPECT_NEAR((slab.direction - Vec3(0.6, 0.8, 0)).norm(), 0.0, 1e-15);  // normalized
  EXPECT_EQ(slab.half_width, 0.0);
  EXPECT_EQ(slab.transition, 0.0);  // defaults
  EXPECT_EQ(slab.profile, AlphaProfile::cubic);
  EXPECT_EQ(slab.where.key, "alpha.region[2]");
  EXPECT_EQ(slab.where.line, 25);
}

TEST(CaseFileAlpha, IntervalIn1D) {
  const CaseConfig c = parse_case_string(std::string(kMinimal1D) + R"(
[nonlocal]
kernel = "gaussian"
horizon = 1
length = 0.2

[[alpha.region]]
shape = "interval"
lower = 4
upper = 6.5
profile = "heaviside"
transition = 1
)",
                                         "i.toml");
  ASSERT_EQ(c.alpha.regions.size(), 1u);
  const AlphaRegionSpec& r = c.alpha.regions[0];
  EXPECT_EQ(r.shape, AlphaShapeKind::interval);
  EXPECT_EQ(r.lower.x(), 4.0);
  EXPECT_EQ(r.upper.x(), 6.5);
  EXPECT_EQ(r.profile, AlphaProfile::heaviside);
  EXPECT_EQ(r.transition, 1.0);
  EXPECT_EQ(r.where.key, "alpha.region[1]");
  EXPECT_EQ(c.alpha.where.key, "alpha");  // implicit [alpha] table
}

TEST(CaseFileAlpha, CylinderAndInfiniteBoxIn3D) {
  const CaseConfig c = parse_case_string(std::string(kMinimal3D) + R"(
[nonlocal]
kernel = "constant"
horizon = 1

[[alpha.region]]
shape = "cylinder"
point = [2, 2, 0]
axis = [0, 0, 2]
radius = 1.25

[[alpha.region]]
shape = "box"
lower = [-inf, 1, 2]
upper = [inf, 3, +inf]
transition = 0.5
)",
                                         "c.toml");
  ASSERT_EQ(c.alpha.regions.size(), 2u);
  const AlphaRegionSpec& cyl = c.alpha.regions[0];
  EXPECT_EQ(cyl.shape, AlphaShapeKind::cylinder);
  EXPECT_EQ(cyl.point, Vec3(2, 2, 0));
  EXPECT_EQ(cyl.direction, Vec3(0, 0, 1));
  EXPECT_EQ(cyl.radius, 1.25);
  const AlphaRegionSpec& box = c.alpha.regions[1];
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(box.shape, AlphaShapeKind::box);
  EXPECT_EQ(box.lower, Vec3(-inf, 1, 2));
  EXPECT_EQ(box.upper, Vec3(inf, 3, inf));
  EXPECT_EQ(box.transition, 0.5);
}

TEST(CaseFileAlpha, ErrorsNameKeyAndAlternatives) {
  const std::string nl = std::string(kMinimal2D) + "\n[nonlocal]\nkernel = \"constant\"\nhorizon = 1\n";
  // A key of another shape names what this shape takes.
  std::string msg = error_of(
      nl + "[[alpha.region]]\nshape = \"ball\"\ncenter = [1, 1]\nradius = 1\nnormal = [1, 0]\n", "s.toml");
  EXPECT_EQ(msg.rfind("s.toml:20:1: key 'alpha.region[1].normal' is not allowed here: a ball takes center = "
                      "[x, y] and radius",
                      0),
            0u)
      << msg;
  // A misspelt key is caught before the shape is read.
  msg = error_of(nl + "[[alpha.region]]\nshap = \"ball\"\n", "s.toml");
  EXPECT_TRUE(contains(msg, "unknown key 'alpha.region[1].shap'; did you mean 'alpha.region[1].shape'?"))
      << msg;
  // An unknown shape lists the shapes.
  msg = error_of(nl + "[[alpha.region]]\nshape = \"sphere\"\n", "s.toml");
  EXPECT_TRUE(contains(msg, "key 'alpha.region[1].shape': unknown shape \"sphere\"")) << msg;
  EXPECT_TRUE(contains(msg, "\"interval\", \"slab\", \"ball\", \"cylinder\", \"box\"")) << msg;
  // nan is no bound of a box.
  msg = error_of(nl + "[[alpha.region]]\nshape = \"box\"\nlower = [nan, 0]\nupper = [1, 1]\n", "s.toml");
  EXPECT_TRUE(
      contains(msg, "key 'alpha.region[1].lower[1]': expected a number (inf and -inf are allowed here)"))
      << msg;
  // Without [nonlocal], nu stays required and says when it is not.
  std::string local = kMinimal2D;
  local.erase(local.find("nu = 0.3"), 8);
  msg = error_of(local, "s.toml");
  EXPECT_TRUE(contains(msg, "key 'material[1].nu': missing required key")) << msg;
  EXPECT_TRUE(contains(msg, "[nonlocal]")) << msg;
  // With [nonlocal], a given nu is still range-checked.
  std::string bad_nu = nl;
  bad_nu.replace(bad_nu.find("nu = 0.3"), 8, "nu = 0.5");
  EXPECT_TRUE(contains(error_of(bad_nu), "key 'material[1].nu': nu = 0.5 is out of range"));
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
    const std::regex located(
        std::regex_replace(file.string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
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
