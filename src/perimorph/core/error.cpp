#include "perimorph/core/error.hpp"

#include <fmt/format.h>

namespace perimorph {

void assertion_failed(const char* expr, const char* file, int line, const std::string& message) {
  throw std::logic_error(
      fmt::format("internal error (please report): {} failed at {}:{}: {}", expr, file, line, message));
}

}  // namespace perimorph
