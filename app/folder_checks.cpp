#include "app/folder_checks.h"

#include <filesystem>
#include <stdexcept>

#include "app/usage_error.h"
#include "io/staged_folder.h"

namespace fs = std::filesystem;

namespace svgf::app {
namespace {

// True when `inner` is `outer` or lies inside it, after resolving ., .. and symbolic links
// (weakly: the output folder need not exist yet).
bool same_or_inside(const fs::path& inner, const fs::path& outer) {
  const fs::path a = fs::weakly_canonical(fs::absolute(inner));
  const fs::path b = fs::weakly_canonical(fs::absolute(outer));
  auto ia = a.begin();
  for (auto ib = b.begin(); ib != b.end(); ++ib, ++ia) {
    if (ib->empty()) continue;  // the trailing "" of a path ending in a separator
    if (ia == a.end() || *ia != *ib) return false;
  }
  return true;
}

}  // namespace

// The output is written frame by frame: an output folder that is the input folder or holds it,
// or lies inside it, would overwrite or mix with the input (issue 15: `svgf denoise X X`
// replaced every input frame). Refused before anything is read or written.
void check_folders_apart(const std::string& in_dir, const std::string& out_dir) {
  if (same_or_inside(out_dir, in_dir))
    throw UsageError("OUT_DIR '" + out_dir + "' is IN_DIR '" + in_dir +
                     "' or inside it: the output would overwrite or mix with the input");
  if (same_or_inside(in_dir, out_dir))
    throw UsageError("IN_DIR '" + in_dir + "' is inside OUT_DIR '" + out_dir +
                     "': the output would mix with the input");
  // OUT_DIR.tmp-PID and OUT_DIR.old-PID are what a killed run leaves, and the next run into
  // OUT_DIR removes or moves them (io::clean_stale_staging): they cannot be the input.
  const fs::path in = fs::weakly_canonical(fs::absolute(in_dir));
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir));
  for (fs::path p = in; p.has_relative_path(); p = p.parent_path())
    if (p.parent_path() == out.parent_path() &&
        io::is_staging_leftover(p.filename().string(), out.filename().string()))
      throw UsageError("IN_DIR '" + in_dir + "' is in " + p.filename().string() +
                       ", a leftover of a run into OUT_DIR '" + out_dir +
                       "' that the next run would clear");
}

std::string output_folder(const std::string& out_arg, const std::string& marker) {
  std::string out_dir;
  try {
    out_dir = io::normalized_folder(out_arg);
  } catch (const std::invalid_argument& e) {
    throw UsageError("OUT_DIR: " + std::string(e.what()));
  }
  if (const std::string why = io::why_not_replaceable(out_dir, marker); !why.empty())
    throw UsageError(why + " (OUT_DIR is replaced as a whole)");
  return out_dir;
}

}  // namespace svgf::app
