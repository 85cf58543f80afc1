#include "perimorph/io/pvd_writer.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace perimorph::io {

namespace {

std::string xml_escape(std::string_view s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      case '\'':
        r += "&apos;";
        break;
      default:
        r.push_back(c);
    }
  }
  return r;
}

}  // namespace

PvdCollection::PvdCollection(std::string path) : path_(std::move(path)) {
  rewrite();
}

void PvdCollection::add(double time, const std::string& vtu_relative_path) {
  if (!std::isfinite(time))
    throw std::logic_error(fmt::format("PvdCollection::add: time {} is not finite", time));
  if (vtu_relative_path.empty()) throw std::logic_error("PvdCollection::add: empty file name");
  entries_.push_back({time, vtu_relative_path});
  rewrite();
}

void PvdCollection::rewrite() const {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (const Entry& e : entries_)
    fmt::format_to(std::back_inserter(out),
                   "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                   xml_escape(e.file));
  out += "  </Collection>\n";
  out += "</VTKFile>\n";

  const std::string tmp_path = path_ + ".tmp";
  {
    std::ofstream file(tmp_path, std::ios::binary | std::ios::trunc);
    if (!file) throw Error(fmt::format("cannot open '{}' for writing: {}", tmp_path, std::strerror(errno)));
    file.write(out.data(), static_cast<std::streamsize>(out.size()));
    file.close();
    if (!file) throw Error(fmt::format("error while writing '{}'", tmp_path));
  }
  std::error_code ec;
  std::filesystem::rename(tmp_path, path_, ec);
  if (ec) throw Error(fmt::format("cannot rename '{}' to '{}': {}", tmp_path, path_, ec.message()));
}

}  // namespace perimorph::io
