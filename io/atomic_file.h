#pragma once
#include <functional>
#include <string>

namespace svgf::io {

// Calls write(tmp_path) with a temporary path in the destination's folder, then renames it over
// `path` (atomic on POSIX file systems). On any exception the temporary file is removed and the
// exception propagates: an interrupted or failed write never leaves a partial `path`.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Writes `bytes` to `path` through write_atomically, checking the open, the write and the close:
// a full disk or a file size limit is an IoError naming `path` and the cause, never a short or
// empty file renamed into place.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace svgf::io
