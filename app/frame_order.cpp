#include "app/frame_order.h"

#include <algorithm>
#include <map>

#include "io/io_error.h"

namespace svgf::app {

std::vector<PlannedFrame> plan_frames(const std::vector<FrameInput>& frames,
                                      const std::vector<int>& camera_cuts,
                                      const std::string& manifest) {
  std::map<int, int> position_of;  // number -> manifest position, ordered by number
  for (int k = 0; k < static_cast<int>(frames.size()); ++k) {
    const FrameInput& f = frames[static_cast<size_t>(k)];
    // Outputs are named by number: a negative one has no file name.
    if (f.number < 0)
      throw io::IoError(f.file + ": frame number " + std::to_string(f.number) + " is negative");
    const auto [it, added] = position_of.emplace(f.number, k);
    if (!added)
      throw io::IoError(frames[static_cast<size_t>(it->second)].file + " and " + f.file +
                        " are both frame " + std::to_string(f.number));
  }
  for (int cut : camera_cuts)
    if (!position_of.count(cut))
      throw io::IoError(manifest + ": camera cut at frame " + std::to_string(cut) +
                        ", which no file holds");

  std::vector<PlannedFrame> plan;
  int previous = -1;
  for (const auto& [number, position] : position_of) {
    PlannedFrame p{position, number, ""};
    if (plan.empty())
      p.reset = "first frame";
    else if (number != previous + 1)
      p.reset = number == previous + 2
                    ? "gap: frame " + std::to_string(previous + 1) + " missing"
                    : "gap: frames " + std::to_string(previous + 1) + " to " +
                          std::to_string(number - 1) + " missing";
    else if (std::find(camera_cuts.begin(), camera_cuts.end(), number) != camera_cuts.end())
      p.reset = "camera cut";
    plan.push_back(p);
    previous = number;
  }
  return plan;
}

}  // namespace svgf::app
