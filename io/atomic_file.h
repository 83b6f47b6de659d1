#pragma once
#include <functional>
#include <string>

namespace svgf::io {

// Calls write(tmp_path) with a temporary path in the destination's folder, then renames it over
// `path` (atomic on POSIX file systems). On any exception the temporary file is removed and the
// exception propagates: an interrupted or failed write never leaves a partial `path`.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace svgf::io
