#pragma once
// Internal to casefile/: a string key that names one of a fixed set of
// options (kernel = "gaussian", profile = "cubic", ...), with "did you mean"
// and the list of what is allowed when it names none.

#include "perimorph/casefile/suggest.hpp"
#include "perimorph/casefile/toml_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

template <class Enum>
using Options = std::vector<std::pair<std::string, Enum>>;

/// The option named by the string `v`; otherwise fails with "did you mean"
/// the closest option (if any) and the list of options.
template <class Enum>
Enum choose(const Value& v, const Options<Enum>& options, std::string_view what) {
  const std::string given = v.string();
  std::vector<std::string> names, quoted;
  for (const auto& [name, option] : options) {
    if (name == given) return option;
    names.push_back(name);
    quoted.push_back(fmt::format("{:?}", name));
  }
  const std::string close = closest_match(given, names);
  v.fail(fmt::format("unknown {} {:?}; {}allowed: {}", what, given,
                     close.empty() ? "" : fmt::format("did you mean {:?}? ", close),
                     fmt::join(quoted, ", ")));
}

/// The α profiles of THEORY §3.1, by name.
inline const Options<AlphaProfile>& profile_options() {
  static const Options<AlphaProfile> profiles{{"heaviside", AlphaProfile::heaviside},
                                              {"linear", AlphaProfile::linear},
                                              {"cubic", AlphaProfile::cubic}};
  return profiles;
}

}  // namespace perimorph::casefile::detail
