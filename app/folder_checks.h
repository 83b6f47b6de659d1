#pragma once
// Checks shared by the commands that read one folder and write another (denoise, import).
#include <string>

namespace svgf::app {

// Throws UsageError when OUT_DIR is IN_DIR, lies inside it or holds it, or when IN_DIR lies in
// a staging leftover of a run into OUT_DIR (OUT_DIR.tmp-PID, OUT_DIR.old-PID) that the next run
// would clear: the output would overwrite or mix with the input.
void check_folders_apart(const std::string& in_dir, const std::string& out_dir);

// OUT_DIR normalized and checked for replacement up front: a command replaces it as a whole,
// so it must be absent, empty or an earlier output of that command (one holding `marker`); a
// wrong path such as a home folder is refused before anything is read. UsageError otherwise.
std::string output_folder(const std::string& out_arg, const std::string& marker);

}  // namespace svgf::app
