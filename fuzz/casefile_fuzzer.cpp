// Fuzz target: the case-file reader (casefile::parse_case_string), every
// check `perimorph check` makes on the text alone.

#include "fuzz_target.hpp"
#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)perimorph::casefile::parse_case_string(text, "fuzz.toml");
  } catch (const perimorph::Error&) {
    // A located message: the expected answer to a bad case.
  }
  return 0;
}
