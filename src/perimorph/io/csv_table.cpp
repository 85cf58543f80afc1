#include "perimorph/io/csv_table.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
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

std::string header_line(const std::vector<std::string>& columns) {
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) header += ',';
    header += csv_quote(columns[i]);
  }
  header += '\n';
  return header;
}

}  // namespace

CsvTable::CsvTable(std::string path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::logic_error(fmt::format("CsvTable '{}': no columns", path_));
  file_.open(path_, std::ios::binary | std::ios::trunc);
  if (!file_) throw OutputError(fmt::format("cannot open '{}' for writing: {}", path_, std::strerror(errno)));
  const std::string header = header_line(columns_);
  file_.write(header.data(), static_cast<std::streamsize>(header.size()));
  file_.flush();
  if (!file_) throw OutputError(fmt::format("cannot write '{}': {}", path_, std::strerror(errno)));
  bytes_ = header.size();
}

CsvTable::CsvTable(std::string path, std::vector<std::string> columns, std::size_t keep_rows)
    : path_(std::move(path)), columns_(std::move(columns)), rows_(keep_rows) {
  if (columns_.empty()) throw std::logic_error(fmt::format("CsvTable '{}': no columns", path_));
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw OutputError(fmt::format("cannot continue '{}': {}", path_, std::strerror(errno)));
  const std::string header = header_line(columns_);
  std::string line;
  std::getline(in, line);
  if (line + '\n' != header)
    throw OutputError(
        fmt::format("cannot continue '{}': its columns are not this run's (a file of another case?)", path_));
  std::size_t end = header.size();
  for (std::size_t r = 0; r < keep_rows; ++r) {
    if (!std::getline(in, line) || in.eof())
      throw OutputError(fmt::format("cannot continue '{}': it has {} complete rows, the checkpoint needs {}",
                                    path_, r, keep_rows));
    end += line.size() + 1;
  }
  in.close();
  std::error_code ec;
  std::filesystem::resize_file(path_, end, ec);
  if (ec) throw OutputError(fmt::format("cannot continue '{}': {}", path_, ec.message()));
  bytes_ = end;
  file_.open(path_, std::ios::binary | std::ios::app);
  if (!file_) throw OutputError(fmt::format("cannot open '{}' for writing: {}", path_, std::strerror(errno)));
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
  if (!file_) {
    const int error = errno;
    truncate_to(bytes_);
    throw OutputError(fmt::format("cannot write '{}': {}", path_, std::strerror(error)));
  }
  last_row_at_ = bytes_;
  bytes_ += line.size();
  ++rows_;
}

void CsvTable::remove_last_row() {
  if (rows_ == 0 || last_row_at_ == bytes_)
    throw std::logic_error("CsvTable::remove_last_row: no row to remove");
  truncate_to(last_row_at_);
  --rows_;
}

void CsvTable::truncate_to(std::uintmax_t size) {
  file_.close();
  std::error_code ec;
  std::filesystem::resize_file(path_, size, ec);
  if (ec)
    throw OutputError(fmt::format("cannot cut '{}' back to its last complete row: {}", path_, ec.message()));
  bytes_ = size;
  file_.clear();
  file_.open(path_, std::ios::binary | std::ios::app);
  if (!file_) throw OutputError(fmt::format("cannot open '{}' for writing: {}", path_, std::strerror(errno)));
}

}  // namespace perimorph::io
