#pragma once
// Text that came from a file (a channel or attribute name, a path) made safe to print in an
// error message: control characters (C0, DEL, C1) and bytes that are not valid UTF-8 become
// \xNN, so a hostile file cannot drive the terminal (issue 15: a channel named
// "\x1b[31mPWN" was printed as is). Valid UTF-8 (an accented file name) is kept.
#include <cstdio>
#include <string>

namespace svgf::io {

inline std::string printable(const std::string& text) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const size_t len = c < 0x80           ? 1
                       : (c >> 5) == 0x6  ? 2
                       : (c >> 4) == 0xE  ? 3
                       : (c >> 3) == 0x1E ? 4
                                          : 0;  // a stray continuation or invalid lead byte
    bool ok = len > 0 && i + len <= text.size();
    for (size_t k = 1; ok && k < len; ++k)
      ok = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;  // continuation bytes
    if (ok && len == 1) ok = c >= 0x20 && c != 0x7f;               // C0 controls and DEL
    if (ok && len == 2 && c == 0xC2)                                // C1 controls U+0080..U+009F
      ok = static_cast<unsigned char>(text[i + 1]) >= 0xA0;
    if (ok) {
      out.append(text, i, len);
      i += len;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
      ++i;
    }
  }
  return out;
}

}  // namespace svgf::io
