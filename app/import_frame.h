#pragma once
// One frame of svgf import: per-buffer files read, checked and completed into a Frame
// (docs/import.md).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/frame.h"
#include "io/games202_matrices.h"

namespace svgf::app {

// The buffers svgf import reads, by the key used in flags (--depth-gradient), mapping files and
// the report: color, albedo, normal, depth, depth-gradient, position, motion, id, emission,
// reference, matrices.
const std::vector<std::string>& import_buffer_keys();

// `pattern` with its {N} (the frame number in decimal) or {N:W} (zero-padded to W digits)
// replaced; a pattern without one names the same file for every frame. Throws
// std::invalid_argument for a malformed or repeated placeholder.
std::string expand_pattern(const std::string& pattern, int frame);
bool has_placeholder(const std::string& pattern);

struct ImportSpec {
  std::string in_dir;
  std::map<std::string, std::string> patterns;  // key -> file pattern relative to in_dir
  int frame_count = 1;  // of the whole import: motion 0 is only worth a warning in a sequence
};

// What an import did beyond copying: each buffer's source ("file", "derived from ...",
// "absent: ...") and warnings (each once).
struct ImportNotes {
  std::map<std::string, std::string> sources;
  std::vector<std::string> warnings;
  void warn(const std::string& text);

 private:
  std::set<std::string> seen_;
};

// Reads frame `n`'s buffers, checks them (files, sizes against the color's and `expected_size`
// when non-zero, channel counts, finite guides, integral ids, surfaces with depth > 0) and
// derives the absent ones. `previous`: the matrices of frame n - 1 when it is imported (motion
// from matrices needs them; otherwise motion is 0 and the history restarts there anyway).
// `matrices_out` receives this frame's matrices when there are any. Throws io::IoError naming
// the frame, the buffer and the file.
Frame import_frame(const ImportSpec& spec, int n, int expected_width, int expected_height,
                   const io::SceneMatrices* previous, io::SceneMatrices* matrices_out,
                   ImportNotes& notes);

}  // namespace svgf::app
