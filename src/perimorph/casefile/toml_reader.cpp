#include "perimorph/casefile/toml_reader.hpp"

#include "perimorph/casefile/suggest.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

namespace perimorph::casefile::detail {

namespace {

/// `text`, cut to at most 60 characters.
std::string abridge(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

std::string index_path(std::string_view path, std::size_t i) {
  return fmt::format("{}[{}]", path, i + 1);
}

}  // namespace

std::string point(const Vec3& v, int n) {
  return fmt::format("[{}]", fmt::join(v.data(), v.data() + n, ", "));
}

std::string render(const toml::node& node) {
  std::ostringstream out;
  node.visit([&](const auto& n) { out << n; });  // floats keep their ".0"
  return abridge(out.str());
}

void fail(const SourceLocation& where, std::string_view message) {
  throw InputError(fmt::format("{}: {}", where.describe(), message));
}

SourceLocation locate(const std::string& file, const toml::node& node, std::string path) {
  const toml::source_position begin = node.source().begin;
  SourceLocation where{file, 1, 1, std::move(path)};
  if (begin) {
    where.line = static_cast<int>(begin.line);
    where.column = static_cast<int>(begin.column);
  }
  return where;
}

std::string show(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return fmt::format("a string {:?}", abridge(node.as_string()->get()));
    case toml::node_type::integer:
      return "an integer " + render(node);
    case toml::node_type::floating_point:
      return "a floating-point number " + render(node);
    case toml::node_type::boolean:
      return "a boolean " + render(node);
    case toml::node_type::array:
      return "an array " + render(node);
    case toml::node_type::table:
      return "a table " + render(node);
    default:
      return "a date/time " + render(node);
  }
}

// ---------------------------------------------------------------- Value

double Value::number() const {
  double v = 0.0;
  if (const auto* i = node_->as_integer())
    v = static_cast<double>(i->get());
  else if (const auto* f = node_->as_floating_point())
    v = f->get();
  else
    fail(fmt::format("expected a number, got {}", show(*node_)));
  if (!std::isfinite(v)) fail(fmt::format("expected a finite number, got {}", render(*node_)));
  return v;
}

int Value::integer(int lo, int hi) const {
  if (const auto* f = node_->as_floating_point()) {
    const double v = f->get();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15)
      fail(fmt::format("expected an integer, got the floating-point number {}; write {:.0f}", render(*node_),
                       v));
    fail(fmt::format("expected an integer, got {}", show(*node_)));
  }
  const auto* i = node_->as_integer();
  if (!i) fail(fmt::format("expected an integer, got {}", show(*node_)));
  const std::int64_t v = i->get();
  if (v < lo || v > hi) {
    if (hi == std::numeric_limits<int>::max())
      fail(v < lo ? fmt::format("must be an integer of at least {}, got {}", lo, v)
                  : fmt::format("is too large: at most {} is supported, got {}", hi, v));
    fail(fmt::format("must be an integer from {} to {}, got {}", lo, hi, v));
  }
  return static_cast<int>(v);
}

std::string Value::string() const {
  const auto* s = node_->as_string();
  if (!s) fail(fmt::format("expected a string, got {}", show(*node_)));
  return s->get();
}

std::string Value::name() const {
  std::string s = string();
  if (s.find_first_not_of(" \t") == std::string::npos)
    fail(fmt::format("expected a non-empty name, got {:?}", s));
  return s;
}

bool Value::boolean() const {
  const auto* b = node_->as_boolean();
  if (!b) fail(fmt::format("expected a boolean (true or false), got {}", show(*node_)));
  return b->get();
}

const toml::array& Value::array() const {
  const auto* a = node_->as_array();
  if (!a) fail(fmt::format("expected an array, got {}", show(*node_)));
  return *a;
}

std::vector<Value> Value::elements() const {
  const toml::array& a = array();
  std::vector<Value> out;
  out.reserve(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out.emplace_back(*file_, a[i], index_path(path_, i));
  return out;
}

Vec3 Value::vector(int n, std::string_view reason) const {
  if (!node_->is_array())
    fail(fmt::format("expected an array of {} numbers {}, got {}", n, reason, show(*node_)));
  const std::vector<Value> items = elements();
  if (items.size() != static_cast<std::size_t>(n))
    fail(fmt::format("needs {} numbers {}, got {}: {}", n, reason, items.size(), render(*node_)));
  Vec3 v = Vec3::Zero();
  for (int i = 0; i < n; ++i) v[i] = items[static_cast<std::size_t>(i)].number();
  return v;
}

Mat3 Value::matrix(int n, std::string_view reason) const {
  if (!node_->is_array())
    fail(fmt::format("expected {} rows of {} numbers {}, e.g. [[1, 0], [0, 1]] for 2 x 2; got {}", n, n,
                     reason, show(*node_)));
  const std::vector<Value> rows = elements();
  if (rows.size() != static_cast<std::size_t>(n))
    fail(fmt::format("needs {} rows of {} numbers {}, got {} rows: {}", n, n, reason, rows.size(),
                     render(*node_)));
  Mat3 m = Mat3::Zero();
  for (int r = 0; r < n; ++r) m.row(r) = rows[static_cast<std::size_t>(r)].vector(n, reason).transpose();
  return m;
}

// ---------------------------------------------------------------- Table

std::string Table::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

std::optional<Value> Table::get(std::string_view key) const {
  const toml::node* node = table_->get(key);
  if (!node) return std::nullopt;
  return Value(*file_, *node, key_path(key));
}

Value Table::require(std::string_view key, std::string_view what) const {
  if (auto v = get(key)) return *v;
  SourceLocation at = where();
  at.key = key_path(key);
  detail::fail(at, fmt::format("missing required key; {}", what));
}

std::optional<Table> Table::table(std::string_view key) const {
  const std::optional<Value> v = get(key);
  if (!v) return std::nullopt;
  const toml::table* t = v->node().as_table();
  if (!t) v->fail(fmt::format("expected a table [{}], got {}", v->path(), show(v->node())));
  return Table(*file_, *t, v->path());
}

std::vector<Table> Table::tables(std::string_view key) const {
  const std::optional<Value> v = get(key);
  if (!v) return {};
  const std::string& path = v->path();
  if (v->node().is_table())
    v->fail(
        fmt::format("expected an array of tables, got a single table; write [[{}]] (double brackets) for "
                    "each entry",
                    path));
  const toml::array* a = v->node().as_array();
  if (!a) v->fail(fmt::format("expected an array of tables [[{}]], got {}", path, show(v->node())));
  std::vector<Table> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table* t = (*a)[i].as_table();
    const std::string item = index_path(path, i);
    if (!t)
      detail::fail(locate(*file_, (*a)[i], item), fmt::format("expected a table, got {}", show((*a)[i])));
    out.emplace_back(*file_, *t, item);
  }
  return out;
}

void Table::check_keys(const std::vector<std::string>& allowed,
                       const std::vector<std::pair<std::string, std::string>>& hints) const {
  // toml::table iterates in key order; report the unknown key that comes first in the file.
  const toml::key* first = nullptr;
  for (auto&& [k, node] : *table_) {
    (void)node;
    if (std::find(allowed.begin(), allowed.end(), k.str()) != allowed.end()) continue;
    const auto pos = [](const toml::key& x) {
      return std::tuple(x.source().begin.line, x.source().begin.column);
    };
    if (!first || pos(k) < pos(*first)) first = &k;
  }
  if (!first) return;
  const std::string key(first->str());
  SourceLocation at = locate(*file_, *table_->get(key), "");
  if (first->source().begin) {
    at.line = static_cast<int>(first->source().begin.line);
    at.column = static_cast<int>(first->source().begin.column);
  }
  const std::string full = key_path(key);
  for (const auto& [name, hint] : hints)
    if (name == key) detail::fail(at, fmt::format("key '{}' is not allowed here: {}", full, hint));
  const std::string where_in = path_.empty() ? "at the top level" : fmt::format("in [{}]", path_);
  const std::string close = closest_match(key, allowed);
  if (!close.empty())
    detail::fail(at, fmt::format("unknown key '{}'; did you mean '{}'?", full, key_path(close)));
  detail::fail(at, fmt::format("unknown key '{}'; allowed {}: {}", full, where_in, fmt::join(allowed, ", ")));
}

}  // namespace perimorph::casefile::detail
