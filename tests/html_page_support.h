#pragma once
// Reading report.html in tests: tags, attributes, embedded images (app/html_report.h).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/png.h"

namespace svgf::test {

// Every start tag `<name ...>` of `html`, whole (attributes included), in order. No regex: tags
// carry images of a megabyte as base64.
inline std::vector<std::string> tags(const std::string& html, const std::string& name) {
  std::vector<std::string> found;
  const std::string open = "<" + name;
  for (size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
    const char next = at + open.size() < html.size() ? html[at + open.size()] : '\0';
    if (next != ' ' && next != '>' && next != '/') continue;
    const size_t end = html.find('>', at);
    if (end == std::string::npos) break;
    found.push_back(html.substr(at, end + 1 - at));
  }
  return found;
}

// The page's frame images: <img> tags with a data-name, in order (the wipe's have none).
inline std::vector<std::string> frame_images(const std::string& html) {
  std::vector<std::string> found;
  for (std::string& tag : tags(html, "img"))
    if (tag.find(" data-name=\"") != std::string::npos) found.push_back(std::move(tag));
  return found;
}

// The value of attribute `name` in a start tag; `missing` when absent.
inline std::string attribute(const std::string& tag, const std::string& name,
                             const std::string& missing = "<absent>") {
  const std::string key = " " + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return missing;
  const size_t from = at + key.size(), end = tag.find('"', from);
  return tag.substr(from, end - from);
}

inline bool has_attribute(const std::string& tag, const std::string& name) {
  return tag.find(" " + name + "=\"") != std::string::npos ||
         tag.find(" " + name + ">") != std::string::npos ||
         tag.find(" " + name + " ") != std::string::npos;
}

inline size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
    ++n;
  return n;
}

// RFC 4648 base64 (no line breaks); throws on a character outside the alphabet.
inline std::string base64_decode(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    throw std::invalid_argument(std::string("base64: bad character '") + c + "'");
  };
  std::string out;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = bits << 6 | static_cast<uint32_t>(value(c));
    if ((count += 6) >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xff);
    }
  }
  return out;
}

// The image a data:image/png;base64 src holds.
inline io::Rgb8Image image_of_src(const std::string& src) {
  const std::string prefix = "data:image/png;base64,";
  if (src.rfind(prefix, 0) != 0)
    throw std::invalid_argument("not a data: PNG: " + src.substr(0, 40));
  return io::decode_png_rgb8(base64_decode(src.substr(prefix.size())), "embedded image");
}

}  // namespace svgf::test
