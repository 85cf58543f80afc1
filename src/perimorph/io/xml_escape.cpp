#include "perimorph/io/xml_escape.hpp"

namespace perimorph::io {

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

}  // namespace perimorph::io
