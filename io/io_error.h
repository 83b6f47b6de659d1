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

// A library's message (OpenEXR's Iex, libpng's) as one line of an IoError: line breaks become
// spaces, trailing spaces go.
inline std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace svgf::io
