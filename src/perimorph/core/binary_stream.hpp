#pragma once
// A byte buffer for checkpoints (run/checkpoint.hpp): plain values, vectors
// and strings written in the machine's representation, read back exactly
// (a double's bits are kept). The reader checks every length against what is
// left and throws Error naming its source on a short or corrupt buffer.

#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace perimorph::core {

class BinaryWriter {
 public:
  /// Bytes go to `sink` in pieces of a few MB (and at flush), so that a
  /// checkpoint of a large run is never held in memory whole.
  explicit BinaryWriter(std::function<void(std::string_view)> sink) : sink_(std::move(sink)) {}

  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  /// The values alone (put_vector = their count, then put_values).
  template <class T>
  void put_values(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& values) {
    put<std::uint64_t>(values.size());
    put_values(std::span<const T>(values));
  }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    append(s.data(), s.size());
  }
  /// A section tag, checked by BinaryReader::expect: a reader that drifts
  /// out of step with the writer stops at the next tag.
  void tag(std::string_view name) { put_string(name); }
  /// Hands what is buffered to the sink.
  void flush() {
    if (!buffer_.empty()) sink_(buffer_);
    buffer_.clear();
  }

 private:
  void append(const char* p, std::size_t n) {
    buffer_.append(p, n);
    if (buffer_.size() >= (std::size_t{1} << 22)) flush();
  }
  std::function<void(std::string_view)> sink_;
  std::string buffer_;
};

/// n values of T as BinaryWriter stored them, in a reader's bytes (not
/// copied, maybe unaligned): read one by one, so that a reader of a large
/// checkpoint takes only what it needs (a mapped file: the pages it touches).
template <class T>
class StoredArray {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  StoredArray() = default;
  StoredArray(const char* data, std::size_t n) : data_(data), n_(n) {}
  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  T operator[](std::size_t i) const {
    T value;
    std::memcpy(&value, data_ + i * sizeof(T), sizeof(T));
    return value;
  }
  /// Values first … first + count − 1 appended to `out` (in range: the caller checks).
  void append_to(std::vector<T>& out, std::size_t first, std::size_t count) const {
    const std::size_t at = out.size();
    out.resize(at + count);
    if (count > 0) std::memcpy(out.data() + at, data_ + first * sizeof(T), count * sizeof(T));
  }

 private:
  const char* data_ = nullptr;
  std::size_t n_ = 0;
};

class BinaryReader {
 public:
  /// Reads `bytes` (not copied: it must outlive the reader); `source` names
  /// it in errors.
  BinaryReader(std::string_view bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> get_vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - pos_) / sizeof(T)) fail("a list longer than the file");
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
    return values;
  }
  /// A vector as get_vector reads it, left where it is (StoredArray).
  template <class T>
  StoredArray<T> get_stored() {
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - pos_) / sizeof(T)) fail("a list longer than the file");
    return StoredArray<T>(take(n * sizeof(T)), n);
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    if (n > bytes_.size() - pos_) fail("a text longer than the file");
    return std::string(take(n), n);
  }
  /// Reads a tag written by BinaryWriter::tag and checks it is `name`.
  void expect(std::string_view name);
  bool at_end() const { return pos_ == bytes_.size(); }
  const std::string& source() const { return source_; }
  /// Throws InputError: "SOURCE: corrupt or truncated checkpoint (WHAT)".
  [[noreturn]] void fail(std::string_view what) const;

 private:
  const char* take(std::size_t n) {
    if (n > bytes_.size() - pos_) fail("it ends early");
    const char* p = bytes_.data() + pos_;
    pos_ += n;
    return p;
  }
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::string source_;
};

}  // namespace perimorph::core
