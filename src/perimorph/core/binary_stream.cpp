#include "perimorph/core/binary_stream.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

namespace perimorph::core {

void BinaryReader::expect(std::string_view name) {
  const auto n = get<std::uint64_t>();
  if (n != name.size() || n > bytes_.size() - pos_ || std::string_view(take(n), n) != name)
    fail(fmt::format("section '{}' not where expected", name));
}

void BinaryReader::fail(std::string_view what) const {
  throw InputError(fmt::format("{}: corrupt or truncated checkpoint ({}, at byte {} of {})", source_, what,
                               pos_, bytes_.size()));
}

}  // namespace perimorph::core
