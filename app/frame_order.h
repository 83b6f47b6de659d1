#pragma once
// The order in which svgf denoise reads a sequence, and where the history starts anew
// (docs/frame-format.md, "Frame numbers").
#include <string>
#include <vector>

namespace svgf::app {

struct FrameInput {
  std::string file;  // path, named in errors
  int number = 0;    // svgf.frame, or the manifest position when the file has none
};

struct PlannedFrame {
  int position = 0;   // in the manifest's list
  int number = 0;     // the input's frame number, which is also the output's
  std::string reset;  // why the history restarts before this frame; empty when it carries on
};

// Orders the frames by number. Throws io::IoError for a negative number, for two files with
// the same number (naming both) and for a camera cut that names a number no file holds (naming
// `manifest`, where the cuts come from). The
// history restarts at the first frame, at each camera cut and after each gap in the numbering
// (frames 0, 1, 2, 5: frame 5 does not continue frame 2).
std::vector<PlannedFrame> plan_frames(const std::vector<FrameInput>& frames,
                                      const std::vector<int>& camera_cuts,
                                      const std::string& manifest);

}  // namespace svgf::app
