#include "perimorph/io/pvd_writer.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/atomic_file.hpp"
#include "perimorph/io/xml_escape.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace perimorph::io {

PvdCollection::PvdCollection(std::string path) : path_(std::move(path)) {
  rewrite();
}

PvdCollection::PvdCollection(std::string path, std::vector<Entry> entries)
    : path_(std::move(path)), entries_(std::move(entries)) {
  rewrite();
}

void PvdCollection::add(double time, const std::string& vtu_relative_path) {
  if (!std::isfinite(time))
    throw std::logic_error(fmt::format("PvdCollection::add: time {} is not finite", time));
  if (vtu_relative_path.empty()) throw std::logic_error("PvdCollection::add: empty file name");
  entries_.push_back({time, vtu_relative_path});
  try {
    rewrite();
  } catch (...) {
    entries_.pop_back();  // the file on disk is still the previous collection
    throw;
  }
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

  AtomicFile file(path_);
  file.write(out);
  file.commit();
}

}  // namespace perimorph::io
