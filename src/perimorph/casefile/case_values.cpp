#include "perimorph/casefile/case_values.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <map>
#include <sstream>

namespace perimorph::casefile {

namespace {

using Values = std::vector<std::pair<std::string, std::string>>;

void flatten(const toml::node& node, const std::string& path, Values& out) {
  if (const auto* t = node.as_table()) {
    for (const auto& [key, child] : *t)
      flatten(child, path.empty() ? std::string(key.str()) : path + "." + std::string(key.str()), out);
  } else if (const auto* a = node.as_array()) {
    if (a->empty()) out.emplace_back(path, "[]");
    for (std::size_t k = 0; k < a->size(); ++k) flatten((*a)[k], fmt::format("{}[{}]", path, k + 1), out);
  } else {
    std::ostringstream s;
    if (const auto* f = node.as_floating_point())
      s << fmt::format("{}", f->get());  // shortest round trip: 0.005, not 0.0050000000000000001
    else
      node.visit([&](const auto& v) { s << v; });
    out.emplace_back(path, s.str());
  }
}

}  // namespace

Values case_values(std::string_view text, const std::string& path) {
  Values out;
  try {
    const toml::table doc = toml::parse(text, std::string_view(path));
    flatten(doc, "", out);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}: {}", path, e.description()));
  }
  return out;
}

std::vector<std::string> differing_keys(const Values& a, const Values& b) {
  const std::map<std::string, std::string> ma(a.begin(), a.end()), mb(b.begin(), b.end());
  std::vector<std::string> out;
  for (const auto& [k, v] : ma) {
    const auto it = mb.find(k);
    if (it == mb.end() || it->second != v) out.push_back(k);
  }
  for (const auto& [k, v] : mb)
    if (!ma.contains(k)) out.push_back(k);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace perimorph::casefile
