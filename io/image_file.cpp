#include "io/image_file.h"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfVersion.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "io/atomic_file.h"
#include "io/printable.h"

namespace svgf::io {
namespace {

constexpr int kMaxSide = 1 << 16;  // larger claims are refused before any allocation

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_regular_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw IoError(path + ": file does not exist");
  if (!std::filesystem::is_regular_file(status)) throw IoError(path + ": not a regular file");
}

std::string read_bytes(const std::string& path) {
  check_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open file for reading");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError(path + ": read error");
  return bytes;
}

// A cursor over the bytes of a text-headed file; failures name the file.
class Bytes {
 public:
  Bytes(const char* data, size_t size, const std::string& name) : d_(data), n_(size), name_(name) {}
  [[noreturn]] void fail(const std::string& what) const { throw IoError(name_ + ": " + what); }
  size_t left() const { return n_ - pos_; }
  size_t pos() const { return pos_; }
  const unsigned char* here() const { return reinterpret_cast<const unsigned char*>(d_ + pos_); }
  unsigned char byte(const char* what) {
    if (pos_ >= n_) fail(std::string("truncated (file ends in ") + what + ")");
    return static_cast<unsigned char>(d_[pos_++]);
  }
  void skip(size_t k) { pos_ += k; }
  // Up to the next '\n' (not included), which is consumed; fails if there is none.
  std::string line(const char* what) {
    const void* nl = std::memchr(d_ + pos_, '\n', n_ - pos_);
    if (!nl) fail(std::string("truncated (no end of line in ") + what + ")");
    const size_t end = static_cast<size_t>(static_cast<const char*>(nl) - d_);
    std::string s(d_ + pos_, end - pos_);
    pos_ = end + 1;
    return s;
  }
  // A whitespace-delimited token (PFM headers).
  std::string token(const char* what) {
    while (pos_ < n_ && std::isspace(static_cast<unsigned char>(d_[pos_]))) ++pos_;
    const size_t start = pos_;
    while (pos_ < n_ && !std::isspace(static_cast<unsigned char>(d_[pos_]))) ++pos_;
    if (start == pos_) fail(std::string("truncated header (no ") + what + ")");
    return std::string(d_ + start, pos_ - start);
  }

 private:
  const char* d_;
  size_t n_;
  size_t pos_ = 0;
  const std::string& name_;
};

int parse_side(const Bytes& b, const std::string& s, const char* what) {
  if (s.empty() || s.size() > 6 || !std::all_of(s.begin(), s.end(), ::isdigit))
    b.fail(std::string("bad ") + what + " '" + printable(s) + "' in the header");
  const int v = std::stoi(s);
  if (v < 1 || v > kMaxSide)
    b.fail(std::string(what) + " " + s + " outside 1.." + std::to_string(kMaxSide));
  return v;
}

float rgbe_component(unsigned char c, unsigned char e) {
  return e == 0 ? 0.f : static_cast<float>(std::ldexp(c + 0.5, int(e) - 136));
}

// One new-style RLE scanline (after its 4-byte marker): four components, each a series of runs
// (count > 128: count - 128 copies of one byte) and literals (count <= 128 bytes).
void read_rle_scanline(Bytes& b, int width, int row, std::vector<unsigned char>& rgbe) {
  for (int c = 0; c < 4; ++c) {
    int x = 0;
    while (x < width) {
      int count = b.byte("an RLE scanline");
      const bool run = count > 128;
      if (run) count -= 128;
      if (count == 0 || x + count > width)
        b.fail("bad RLE run in scanline " + std::to_string(row) + " (count " +
               std::to_string(count) + " at x " + std::to_string(x) + " of " +
               std::to_string(width) + ")");
      if (run) {
        const unsigned char v = b.byte("an RLE scanline");
        for (int k = 0; k < count; ++k) rgbe[4 * (x + k) + c] = v;
      } else {
        if (b.left() < static_cast<size_t>(count)) b.fail("truncated (file ends in an RLE scanline)");
        for (int k = 0; k < count; ++k) rgbe[4 * (x + k) + c] = b.here()[k];
        b.skip(static_cast<size_t>(count));
      }
      x += count;
    }
  }
}

}  // namespace

Image read_hdr_from_memory(const char* data, size_t size, const std::string& name) {
  Bytes b(data, size, name);
  const std::string magic = b.line("the signature");
  if (magic != "#?RADIANCE" && magic != "#?RGBE")
    b.fail("not a Radiance .hdr file (first line is not #?RADIANCE or #?RGBE)");
  double exposure = 1.0;
  for (;;) {
    const std::string l = b.line("the header");
    if (l.empty()) break;
    if (l.rfind("FORMAT=", 0) == 0 && l != "FORMAT=32-bit_rle_rgbe")
      b.fail("unsupported " + printable(l) + " (only 32-bit_rle_rgbe)");
    if (l.rfind("EXPOSURE=", 0) == 0) {
      const double e = std::atof(l.c_str() + 9);
      if (!(e > 0) || !std::isfinite(e)) b.fail("bad " + printable(l));
      exposure *= e;
    }
  }
  const std::string res = b.line("the resolution line");
  char ys[8] = {}, xs[8] = {};
  char hs[16] = {}, ws[16] = {};
  if (std::sscanf(res.c_str(), "%2s %15s %2s %15s", ys, hs, xs, ws) != 4 ||
      std::string(ys) != "-Y" || std::string(xs) != "+X")
    b.fail("unsupported resolution line '" + printable(res) +
           "' (only '-Y H +X W': rows top to bottom, left to right)");
  const int height = parse_side(b, hs, "height"), width = parse_side(b, ws, "width");
  // Every scanline takes at least 4 bytes (a flat pixel or an RLE marker): refuse a size the
  // file cannot hold before allocating it.
  if (b.left() / 4 < static_cast<size_t>(height))
    b.fail("truncated (" + std::to_string(height) + " scanlines cannot fit in " +
           std::to_string(b.left()) + " bytes)");
  Image im(width, height, 3);
  std::vector<unsigned char> rgbe(static_cast<size_t>(width) * 4);
  for (int y = 0; y < height; ++y) {
    const bool rle = width >= 8 && width <= 0x7fff && b.left() >= 4 && b.here()[0] == 2 &&
                     b.here()[1] == 2 && (b.here()[2] & 0x80) == 0;
    if (rle) {
      if ((b.here()[2] << 8 | b.here()[3]) != width)
        b.fail("RLE scanline " + std::to_string(y) + " says width " +
               std::to_string(b.here()[2] << 8 | b.here()[3]) + ", the header " +
               std::to_string(width));
      b.skip(4);
      read_rle_scanline(b, width, y, rgbe);
    } else {
      if (b.left() >= 4 && b.here()[0] == 1 && b.here()[1] == 1 && b.here()[2] == 1)
        b.fail("old-style RLE in scanline " + std::to_string(y) + " is not supported");
      if (b.left() < rgbe.size())
        b.fail("truncated (file ends in scanline " + std::to_string(y) + " of " +
               std::to_string(height) + ")");
      std::memcpy(rgbe.data(), b.here(), rgbe.size());
      b.skip(rgbe.size());
    }
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        im.at(x, y, c) = static_cast<float>(rgbe_component(rgbe[4 * x + c], rgbe[4 * x + 3]) / exposure);
  }
  if (b.left() != 0)
    b.fail(std::to_string(b.left()) + " bytes after the last scanline");
  return im;
}

Image read_pfm_from_memory(const char* data, size_t size, const std::string& name) {
  Bytes b(data, size, name);
  const std::string magic = b.token("signature");
  if (magic != "PF" && magic != "Pf") b.fail("not a PFM file (signature is not PF or Pf)");
  const int channels = magic == "PF" ? 3 : 1;
  const int width = parse_side(b, b.token("width"), "width");
  const int height = parse_side(b, b.token("height"), "height");
  const std::string scale_text = b.token("scale");
  char* end = nullptr;
  const double scale = std::strtod(scale_text.c_str(), &end);
  if (*end != '\0' || scale == 0 || !std::isfinite(scale))
    b.fail("bad scale '" + printable(scale_text) + "' (its sign gives the byte order; 0 is none)");
  if (!std::isspace(b.byte("the header")))
    b.fail("no whitespace between the scale and the pixels");
  const size_t need = static_cast<size_t>(width) * height * channels * 4;
  if (b.left() != need)
    b.fail("pixel data is " + std::to_string(b.left()) + " bytes, " + std::to_string(width) + "x" +
           std::to_string(height) + "x" + std::to_string(channels) + " floats need " +
           std::to_string(need));
  const bool little = scale < 0;
  Image im(width, height, channels);
  const unsigned char* p = b.here();
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) {
        const unsigned char* q = p + 4 * ((static_cast<size_t>(row) * width + x) * channels + c);
        const uint32_t bits = little ? (uint32_t(q[0]) | uint32_t(q[1]) << 8 |
                                        uint32_t(q[2]) << 16 | uint32_t(q[3]) << 24)
                                     : (uint32_t(q[3]) | uint32_t(q[2]) << 8 |
                                        uint32_t(q[1]) << 16 | uint32_t(q[0]) << 24);
        float v;
        std::memcpy(&v, &bits, 4);
        im.at(x, height - 1 - row, c) = v;  // stored bottom to top
      }
  return im;
}

Image read_exr_image(const std::string& path) {
  check_regular_file(path);
  {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    if (in.gcount() != 4 || !Imf::isImfMagic(magic))
      throw IoError(path + ": not an OpenEXR file (bad magic number)");
  }
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    const Imath::Box2i dw = h.dataWindow();
    if (dw.min.x != 0 || dw.min.y != 0)
      throw IoError(path + ": data window does not start at 0,0");
    const int width = dw.max.x + 1, height = dw.max.y + 1;
    const Imf::ChannelList& list = h.channels();
    std::vector<std::string> names;
    const std::vector<std::vector<std::string>> groups = {{"R", "G", "B"}, {"X", "Y", "Z"}, {"Y"}, {"Z"}};
    for (const auto& group : groups) {
      for (const std::string& n : group)
        if (list.findChannel(n)) names.push_back(n);
      if (!names.empty()) break;
    }
    if (names.empty()) {
      std::vector<std::string> all;
      for (auto it = list.begin(); it != list.end(); ++it) all.emplace_back(it.name());
      if (all.size() != 1) {
        std::string listed;
        for (const auto& n : all) listed += (listed.empty() ? "" : ", ") + printable(n);
        throw IoError(path + ": no R/G/B, X/Y/Z or single channel to read (channels: " + listed + ")");
      }
      names = all;
    }
    Image im(width, height, static_cast<int>(names.size()));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
      const Imf::Channel* ch = list.findChannel(names[c]);
      if (ch->xSampling != 1 || ch->ySampling != 1)
        throw IoError(path + ": channel '" + printable(names[c]) + "' is subsampled");
      if (ch->type == Imf::UINT)
        throw IoError(path + ": channel '" + printable(names[c]) + "' is UINT, expected HALF or FLOAT");
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(im.plane(static_cast<int>(c))),
                                     sizeof(float), sizeof(float) * static_cast<size_t>(width)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(0, height - 1);
    return im;
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(path + ": " + one_line(e.what()));
  }
}

Image read_image(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return read_exr_image(path);
  if (ext == ".hdr" || ext == ".pic") {
    const std::string bytes = read_bytes(path);
    return read_hdr_from_memory(bytes.data(), bytes.size(), path);
  }
  if (ext == ".pfm") {
    const std::string bytes = read_bytes(path);
    return read_pfm_from_memory(bytes.data(), bytes.size(), path);
  }
  throw IoError(path + ": unknown image type '" + printable(ext) + "' (.exr, .hdr, .pic or .pfm)");
}

void write_image_exr(const std::string& path, const Image& im) {
  static const char* const kNames[4][3] = {{}, {"Y"}, {"R", "G"}, {"R", "G", "B"}};
  if (im.empty() || im.channels() < 1 || im.channels() > 3)
    throw std::invalid_argument(path + ": write_image_exr takes 1 to 3 channels, got " +
                                std::to_string(im.channels()));
  write_atomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(im.width(), im.height());
      header.compression() = Imf::ZIP_COMPRESSION;
      Imf::FrameBuffer fb;
      for (int c = 0; c < im.channels(); ++c) {
        header.channels().insert(kNames[im.channels()][c], Imf::Channel(Imf::FLOAT));
        fb.insert(kNames[im.channels()][c],
                  Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(im.plane(c))),
                             sizeof(float), sizeof(float) * static_cast<size_t>(im.width())));
      }
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(im.height());
    } catch (const std::exception& e) {
      throw IoError(path + ": cannot write: " + one_line(e.what()));
    }
  });
}

}  // namespace svgf::io
