#pragma once
// VTK XML UnstructuredGrid (.vtu) writer: file format version 1.0,
// header_type UInt64, byte_order LittleEndian, no compression. Readable by
// ParaView/VTK and by the independent checker python/read_vtu.py.

#include "perimorph/io/grid.hpp"

#include <cstdint>
#include <span>
#include <string>

namespace perimorph::io {

/// How DataArray contents are stored inline.
///  - ascii:  whitespace-separated decimal numbers, doubles in shortest
///            round-trip form (non-finite values appear as nan/inf);
///  - base64: format="binary": per array one base64 stream of a UInt64
///            little-endian byte count followed by the raw little-endian
///            values (VTK's layout for uncompressed inline binary data).
enum class VtuEncoding { ascii, base64 };

/// Writes `grid` to `path` (overwriting it). Arrays: Points Float64 x3,
/// connectivity Int64 (permuted into VTK node order), offsets Int64, types
/// UInt8, every point/cell Field as Float64 with its NumberOfComponents.
/// The file is written under a temporary name and renamed into place, so a
/// reader never sees a half-written file.
/// Throws std::logic_error if `grid` breaks the UnstructuredGrid contract
/// (sizes, index range, field names), perimorph::Error if the file cannot
/// be written.
void write_vtu(const std::string& path, const UnstructuredGrid& grid,
               VtuEncoding encoding = VtuEncoding::base64);

/// Standard base64 (RFC 4648, alphabet A-Z a-z 0-9 + /, '=' padding, no line
/// breaks) of `bytes`. Exposed for tests; write_vtu uses the same encoder.
std::string base64_encode(std::span<const std::uint8_t> bytes);

}  // namespace perimorph::io
