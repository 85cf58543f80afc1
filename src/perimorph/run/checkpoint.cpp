#include "perimorph/run/checkpoint.hpp"

#include "perimorph/casefile/case_values.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

namespace perimorph::run {

namespace {

constexpr std::string_view kTag = "perimorph-checkpoint";

std::vector<std::pair<std::string, std::string>> compared_values(const casefile::CaseConfig& config) {
  auto values = casefile::case_values(config.text, config.path);
  std::erase_if(values, [](const auto& kv) { return kv.first == "output.checkpoint_every"; });
  return values;
}

}  // namespace

std::string checkpoint_path(const std::string& directory, const std::string& basename) {
  return (std::filesystem::path(directory) / (basename + ".checkpoint")).string();
}

std::string find_checkpoint(const std::string& given, const std::string& basename) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(given, ec)) return given;
  if (fs::is_directory(given, ec)) {
    const std::string p = checkpoint_path(given, basename);
    if (fs::is_regular_file(p, ec)) return p;
    throw InputError(
        fmt::format("--restart {}: no checkpoint {} there (a run writes it with [output] "
                    "checkpoint_every = N, or when stopped by SIGINT/SIGTERM between increments)",
                    given, p));
  }
  throw InputError(fmt::format("--restart {}: no such file or directory", given));
}

core::MappedFile read_checkpoint_file(const std::string& path) {
  return core::MappedFile(path, "checkpoint");
}

void write_header(core::BinaryWriter& out, const casefile::CaseConfig& config) {
  out.tag(kTag);
  out.put<std::uint32_t>(kCheckpointVersion);
  const auto values = compared_values(config);
  out.put<std::uint64_t>(values.size());
  for (const auto& [k, v] : values) {
    out.put_string(k);
    out.put_string(v);
  }
}

void check_header(core::BinaryReader& in, const casefile::CaseConfig& config) {
  try {
    in.expect(kTag);
  } catch (const Error&) {
    throw InputError(fmt::format("{}: not a perimorph checkpoint", in.source()));
  }
  const auto version = in.get<std::uint32_t>();
  if (version != kCheckpointVersion)
    throw InputError(
        fmt::format("{}: checkpoint format version {}, this perimorph reads version {}: "
                    "continue it with the perimorph that wrote it, or start the run again",
                    in.source(), version, kCheckpointVersion));
  std::vector<std::pair<std::string, std::string>> saved;
  const auto n = in.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < n; ++k) {
    std::string key = in.get_string();
    saved.emplace_back(std::move(key), in.get_string());
  }
  const auto now = compared_values(config);
  const auto keys = casefile::differing_keys(saved, now);
  if (keys.empty()) return;
  std::vector<std::string> lines;
  for (const auto& key : keys) {
    auto value = [&](const auto& list) -> std::string {
      for (const auto& [k, v] : list)
        if (k == key) return v;
      return "(absent)";
    };
    lines.push_back(fmt::format("  {}: {} in the checkpoint, {} now", key, value(saved), value(now)));
  }
  throw InputError(
      fmt::format("{}: the case {} has changed since this checkpoint was written; a restart "
                  "continues the same case only ([output] checkpoint_every may change). "
                  "Differing keys:\n{}",
                  in.source(), config.path, fmt::join(lines, "\n")));
}

}  // namespace perimorph::run
