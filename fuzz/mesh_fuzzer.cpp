// Fuzz target: the mesh reader — the case file, then the mesh it describes
// (setup::build_mesh: the box, its holes and pre-crack cuts). Cases with more
// than 20 000 cells are only parsed: a large valid mesh is a cost, not a
// finding.

#include "fuzz_target.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/setup/discretization.hpp"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto config = perimorph::casefile::parse_case_string(text, "fuzz.toml");
    double cells = 1.0;
    for (int d = 0; d < config.mesh.box.dim; ++d) cells *= static_cast<double>(config.mesh.box.cells[d]);
    if (cells <= 20000.0) (void)perimorph::setup::build_mesh(config);
  } catch (const perimorph::Error&) {
    // A located message: the expected answer to a bad case.
  }
  return 0;
}
