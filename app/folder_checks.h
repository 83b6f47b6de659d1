#pragma once
// Checks shared by the commands that read one folder and write another (denoise, import).
#include <string>

namespace svgf::app {

// Throws UsageError when OUT_DIR is IN_DIR, lies inside it or holds it, or when IN_DIR lies in
// a staging leftover of a run into OUT_DIR (OUT_DIR.tmp-PID, OUT_DIR.old-PID) that the next run
// would clear: the output would overwrite or mix with the input.
void check_folders_apart(const std::string& in_dir, const std::string& out_dir);

}  // namespace svgf::app
