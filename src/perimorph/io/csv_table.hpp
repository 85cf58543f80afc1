#pragma once
// Append-only numeric CSV table (e.g. load-displacement history), written row
// by row and flushed after each row so a run that dies still leaves every
// completed row on disk.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace perimorph::io {

class CsvTable {
 public:
  /// Creates (or truncates) `path` and writes the header line once: the
  /// column names separated by ','; a name containing ',', '"' or a line
  /// break is quoted RFC 4180 style. Throws std::logic_error if `columns` is
  /// empty, perimorph::Error if the file cannot be opened.
  CsvTable(std::string path, std::vector<std::string> columns);
  /// Continues the table at `path` after its first `keep_rows` rows (a
  /// restarted run, run/checkpoint.hpp): the rows after them are cut off, and
  /// add_row appends. Throws perimorph::Error naming the file if it cannot be
  /// read, its header is not `columns`, or it has fewer rows.
  CsvTable(std::string path, std::vector<std::string> columns, std::size_t keep_rows);

  /// Appends one row and flushes it. Values are written in shortest
  /// round-trip form (parsing the text gives back the same double; non-finite
  /// values appear as nan, inf, -inf). Throws std::logic_error if
  /// row.size() != columns().size(), perimorph::OutputError on a write
  /// failure (a full disk), after cutting off what it wrote of the row.
  void add_row(const std::vector<double>& row);
  /// Cuts off the row the last add_row wrote (a caller's later step failed:
  /// the files stay in step); truncating needs no space. Once per add_row.
  /// Throws OutputError if it cannot.
  void remove_last_row();

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }

 private:
  /// Cuts the file to `size` bytes and reopens it for appending.
  void truncate_to(std::uintmax_t size);
  std::string path_;
  std::vector<std::string> columns_;
  std::ofstream file_;
  std::size_t rows_ = 0;
  std::uintmax_t bytes_ = 0;        ///< the file's size after the last complete row
  std::uintmax_t last_row_at_ = 0;  ///< where that row starts (remove_last_row, once)
};

}  // namespace perimorph::io
