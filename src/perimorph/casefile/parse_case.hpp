#pragma once
// Reading a case file (TOML, format in docs/case-file.md) into a validated
// CaseConfig. This is the only place that knows the input format.

#include "perimorph/casefile/case_config.hpp"

#include <string>
#include <string_view>

namespace perimorph::casefile {

/// Reads and validates the case file at `path`. Throws perimorph::InputError
/// if the file cannot be read ("cannot open case file 'PATH' (reason)") or on
/// the first problem found, with a message "PATH:LINE:COL: key 'KEY': ..."
/// that names the key, shows the value and says what is allowed.
CaseConfig parse_case_file(const std::string& path);

/// As parse_case_file, for a case given as text; `pretend_path` stands for the
/// file name in messages, in CaseConfig::path and for the default
/// output.basename (its stem).
CaseConfig parse_case_string(std::string_view toml_text, const std::string& pretend_path);

}  // namespace perimorph::casefile
