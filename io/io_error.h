#pragma once
#include <stdexcept>
#include <string>

namespace svgf::io {

// Every I/O failure: the message names the file and, where it applies, the frame and channel,
// in one line, e.g. "fixtures/x/frame_0003.exr: channel 'albedo.G' is missing".
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace svgf::io
