#pragma once
// Internal to casefile/ (only parse_case.cpp, parse_material.cpp,
// parse_nonlocal.cpp and parse_sets.cpp include it; toml++ is a private dependency of the library):
// typed reads of TOML values that know where they came from. Every failure throws InputError with the message
//   FILE:LINE:COL: key 'PATH': what is wrong, the value given, what is allowed
// where PATH is the dotted key path with 1-based array indices
// ("material[2].nu", "mesh.cells[3]").

#include "perimorph/casefile/case_config.hpp"

#include <toml++/toml.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

/// "FILE:LINE:COL: key 'KEY': message" (or "FILE:LINE:COL: message" when the
/// key is empty), as an InputError.
[[noreturn]] void fail(const SourceLocation& where, std::string_view message);

/// The location of `node` in `file`, labelled `path`. toml++ gives every node
/// (implicit tables included) a position; a missing one reads as 1:1.
SourceLocation locate(const std::string& file, const toml::node& node, std::string path);

/// "[0, 24]": the first n components of v.
std::string point(const Vec3& v, int n);
/// Axis names for messages.
inline constexpr const char* kAxis[3] = {"x", "y", "z"};

/// toml++'s rendering of a value, cut to 60 characters: "[ 1, 2.0 ]".
std::string render(const toml::node& node);

/// A value for messages: "a string \"abc\"", "an integer 3",
/// "a floating-point number 48.0", "an array [ 1, 2 ]", "a table { a = 1 }".
std::string show(const toml::node& node);

/// One value of the case file: its node and its dotted path. Refers to the
/// file name and the parsed document, which must outlive it.
class Value {
 public:
  Value(const std::string& file, const toml::node& node, std::string path)
      : file_(&file), node_(&node), path_(std::move(path)) {}

  const toml::node& node() const { return *node_; }
  const std::string& path() const { return path_; }
  SourceLocation where() const { return locate(*file_, *node_, path_); }
  [[noreturn]] void fail(std::string_view message) const { detail::fail(where(), message); }

  /// An integer or a floating-point number (E = 200 is a number); must be finite.
  double number() const;
  /// An integer in [lo, hi]; a float such as 4.0 is rejected with a hint.
  int integer(int lo, int hi) const;
  std::string string() const;
  /// A string that is not empty.
  std::string name() const;
  bool boolean() const;
  /// The elements of an array (paths "PATH[1]", "PATH[2]", ...).
  std::vector<Value> elements() const;
  /// An array of exactly n numbers (n <= 3); the other components are 0.
  /// `reason` completes "needs n numbers ..." (e.g. "for dim = 2").
  Vec3 vector(int n, std::string_view reason) const;
  /// An array of n arrays of n numbers (n <= 3), row by row; the rest is 0.
  Mat3 matrix(int n, std::string_view reason) const;

 private:
  const toml::array& array() const;

  const std::string* file_;  ///< non-owning: the case file's text
  const toml::node* node_;   ///< non-owning: in the parsed document
  std::string path_;
};

/// A table of the case file: the root (path ""), a section ("mesh") or one
/// entry of an array of tables ("material[2]").
class Table {
 public:
  Table(const std::string& file, const toml::table& table, std::string path)
      : file_(&file), table_(&table), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  /// "PATH.key", or "key" for the root.
  std::string key_path(std::string_view key) const;
  SourceLocation where() const { return locate(*file_, *table_, path_); }
  [[noreturn]] void fail(std::string_view message) const { detail::fail(where(), message); }

  bool has(std::string_view key) const { return table_->get(key) != nullptr; }
  std::optional<Value> get(std::string_view key) const;
  /// The value of `key`; if absent, fails at the table's location with
  /// "missing required key; <what>" (what says what the key is for).
  Value require(std::string_view key, std::string_view what) const;
  /// A sub-table (e.g. [mesh]); fails if `key` holds something else.
  std::optional<Table> table(std::string_view key) const;
  /// An array of tables ([[material]]), in file order, paths "key[1]", ...;
  /// empty if absent. Fails for a plain table ([material]) or other values.
  std::vector<Table> tables(std::string_view key) const;

  /// Fails for the first key (in file order) that is not in `allowed`: with
  /// the hint from `hints` naming that key if any, else "did you mean" the
  /// closest allowed key, else the list of allowed keys.
  void check_keys(const std::vector<std::string>& allowed,
                  const std::vector<std::pair<std::string, std::string>>& hints = {}) const;

 private:
  const std::string* file_;   ///< non-owning: the case file's text
  const toml::table* table_;  ///< non-owning: in the parsed document
  std::string path_;
};

}  // namespace perimorph::casefile::detail
