#include "perimorph/io/csv_table.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace perimorph::io {

namespace {

std::string csv_quote(std::string_view s) {
  if (s.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(s);
  std::string r = "\"";
  for (char c : s) {
    if (c == '"') r += '"';
    r += c;
  }
  r += '"';
  return r;
}

}  // namespace

CsvTable::CsvTable(std::string path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::logic_error(fmt::format("CsvTable '{}': no columns", path_));
  file_.open(path_, std::ios::binary | std::ios::trunc);
  if (!file_) throw Error(fmt::format("cannot open '{}' for writing: {}", path_, std::strerror(errno)));
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) header += ',';
    header += csv_quote(columns_[i]);
  }
  header += '\n';
  file_.write(header.data(), static_cast<std::streamsize>(header.size()));
  file_.flush();
  if (!file_) throw Error(fmt::format("error while writing '{}'", path_));
}

void CsvTable::add_row(const std::vector<double>& row) {
  if (row.size() != columns_.size())
    throw std::logic_error(fmt::format("CsvTable '{}': row has {} values, table has {} columns", path_,
                                       row.size(), columns_.size()));
  std::string line;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) line += ',';
    fmt::format_to(std::back_inserter(line), "{}", row[i]);
  }
  line += '\n';
  file_.write(line.data(), static_cast<std::streamsize>(line.size()));
  file_.flush();
  if (!file_) throw Error(fmt::format("error while writing '{}'", path_));
  ++rows_;
}

}  // namespace perimorph::io
