#pragma once
// Append-only numeric CSV table (e.g. load-displacement history), written row
// by row and flushed after each row so a run that dies still leaves every
// completed row on disk.

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
  /// row.size() != columns().size(), perimorph::Error on a write failure.
  void add_row(const std::vector<double>& row);

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::ofstream file_;
  std::size_t rows_ = 0;
};

}  // namespace perimorph::io
