#pragma once
// XML attribute escaping shared by the VTU and PVD writers.

#include <string>
#include <string_view>

namespace perimorph::io {

/// s with & < > " ' replaced by their XML entities.
std::string xml_escape(std::string_view s);

}  // namespace perimorph::io
