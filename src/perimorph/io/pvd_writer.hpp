#pragma once
// ParaView collection (.pvd): an index of .vtu files with their times, so
// ParaView opens a whole run as one time series.

#include <string>
#include <vector>

namespace perimorph::io {

class PvdCollection {
 public:
  /// Creates (or truncates) `path` and writes an empty, valid collection.
  /// Throws perimorph::Error if the file cannot be written.
  explicit PvdCollection(std::string path);

  struct Entry {
    double time;
    std::string file;
  };
  /// A collection continued (a restarted run, run/checkpoint.hpp): rewrites
  /// `path` with `entries`, the ones the run had written up to its checkpoint.
  PvdCollection(std::string path, std::vector<Entry> entries);

  /// Appends a DataSet entry (timestep = time, file = vtu_relative_path) and
  /// rewrites the whole .pvd file, via a temporary file renamed into place, so
  /// an interrupted run still leaves a valid collection listing every step
  /// added so far. `vtu_relative_path` is relative to the .pvd's directory
  /// (ParaView resolves it that way); it is written verbatim (XML-escaped).
  /// Throws std::logic_error if time is not finite or the path is empty,
  /// perimorph::Error if the file cannot be written.
  void add(double time, const std::string& vtu_relative_path);

  const std::string& path() const { return path_; }
  std::size_t size() const { return entries_.size(); }

  const std::vector<Entry>& entries() const { return entries_; }

 private:
  void rewrite() const;

  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace perimorph::io
