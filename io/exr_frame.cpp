#include "io/exr_frame.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfVersion.h>
#include <Imath/half.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "io/atomic_file.h"

namespace svgf::io {
namespace {

constexpr const char* kAttrFormatVersion = "svgf.format_version";
constexpr const char* kAttrFrame = "svgf.frame";
constexpr const char* kAttrWorldToView = "svgf.world_to_view";
constexpr const char* kAttrViewToClip = "svgf.view_to_clip";
constexpr int kFormatVersion = 1;

static_assert(sizeof(unsigned int) == sizeof(uint32_t), "OpenEXR UINT is unsigned int");

const char* type_name(Imf::PixelType t) {
  switch (t) {
    case Imf::UINT: return "UINT";
    case Imf::HALF: return "HALF";
    case Imf::FLOAT: return "FLOAT";
    default: return "unknown";
  }
}

Imath::M44f to_m44f(const std::array<float, 16>& a) {
  Imath::M44f m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = a[r * 4 + c];
  return m;
}

std::array<float, 16> from_m44f(const Imath::M44f& m) {
  std::array<float, 16> a{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a[r * 4 + c] = m[r][c];
  return a;
}

// Header channels plus the frame buffer that feeds them. OutputFile does not convert pixel types,
// so HALF channels get a converted copy that lives here until the file is written.
class ExrWriter {
 public:
  ExrWriter(int width, int height) : width_(width), height_(height), header_(width, height) {
    header_.compression() = Imf::ZIP_COMPRESSION;
  }
  Imf::Header& header() { return header_; }

  void add_float(const char* name, const float* plane, PixelStorage storage) {
    if (storage == PixelStorage::Float) {
      add(name, Imf::FLOAT, const_cast<float*>(plane), sizeof(float));
      return;
    }
    const size_t n = static_cast<size_t>(width_) * height_;
    halves_.emplace_back(n);
    std::vector<Imath::half>& h = halves_.back();
    for (size_t i = 0; i < n; ++i) h[i] = Imath::half(plane[i]);  // round to nearest even
    add(name, Imf::HALF, h.data(), sizeof(Imath::half));
  }

  template <size_t N>
  void add_group(const char* const (&names)[N], const Image& im, PixelStorage storage) {
    for (size_t c = 0; c < N; ++c) add_float(names[c], im.plane(static_cast<int>(c)), storage);
  }

  void add_uint(const char* name, const uint32_t* data) {
    add(name, Imf::UINT, const_cast<uint32_t*>(data), sizeof(uint32_t));
  }

  void write(const std::string& file_path) {
    Imf::OutputFile file(file_path.c_str(), header_);
    file.setFrameBuffer(frame_buffer_);
    file.writePixels(height_);
  }

 private:
  void add(const char* name, Imf::PixelType type, void* base, size_t elem) {
    header_.channels().insert(name, Imf::Channel(type));
    frame_buffer_.insert(name, Imf::Slice(type, static_cast<char*>(base), elem,
                                          elem * static_cast<size_t>(width_)));
  }

  int width_, height_;
  Imf::Header header_;
  Imf::FrameBuffer frame_buffer_;
  std::vector<std::vector<Imath::half>> halves_;  // moving the outer vector keeps the buffers
};

// Writes through write_atomically; any library failure becomes an IoError naming `path`.
void write_exr(const std::string& path, ExrWriter& writer) {
  write_atomically(path, [&](const std::string& tmp) {
    try {
      writer.write(tmp);
    } catch (const IoError&) {
      throw;
    } catch (const std::exception& e) {
      throw IoError(path + ": cannot write: " + one_line(e.what()));
    }
  });
}

// Missing file and wrong magic get clear messages before OpenEXR sees the file.
void check_exr_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw IoError(path + ": file does not exist");
  if (!std::filesystem::is_regular_file(status)) throw IoError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open file for reading");
  char magic[4] = {};
  in.read(magic, 4);
  if (in.gcount() != 4 || !Imf::isImfMagic(magic))
    throw IoError(path + ": not an OpenEXR file (bad magic number)");
}

// Checks channels against the header and binds them to freshly allocated planes.
class ExrReader {
 public:
  ExrReader(const std::string& path, const Imf::Header& header) : path_(path), header_(header) {
    const Imath::Box2i dw = header.dataWindow();
    if (dw.min.x != 0 || dw.min.y != 0 || dw.max.x < dw.min.x || dw.max.y < dw.min.y)
      throw IoError(path + ": data window (" + std::to_string(dw.min.x) + "," +
                    std::to_string(dw.min.y) + ")-(" + std::to_string(dw.max.x) + "," +
                    std::to_string(dw.max.y) + ") does not start at 0,0");
    width_ = dw.max.x + 1;
    height_ = dw.max.y + 1;
  }
  int width() const { return width_; }
  int height() const { return height_; }

  // A group of float channels. Optional groups absent altogether read as an empty Image;
  // a group that is partly there names its first missing channel.
  template <size_t N>
  Image read_group(const char* const (&names)[N], bool optional) {
    if (!check_group(names, optional)) return Image();
    Image im(width_, height_, static_cast<int>(N));
    for (size_t c = 0; c < N; ++c) bind_float(names[c], im.plane(static_cast<int>(c)));
    return im;
  }

  // The checks of read_group without allocating; false for an optional group absent altogether.
  template <size_t N>
  bool check_group(const char* const (&names)[N], bool optional) const {
    if (optional) {
      bool any = false;
      for (const char* name : names) any = any || header_.channels().findChannel(name);
      if (!any) return false;
    }
    for (const char* name : names) check_float(name);
    return true;
  }

  void check_float(const char* name) const {
    const Imf::PixelType t = check_channel(name);
    if (t != Imf::HALF && t != Imf::FLOAT)
      throw IoError(path_ + ": channel '" + name + "' has pixel type " + type_name(t) +
                    ", expected HALF or FLOAT");
  }

  void check_uint(const char* name) const {
    const Imf::PixelType t = check_channel(name);
    if (t != Imf::UINT)
      throw IoError(path_ + ": channel '" + name + "' has pixel type " + type_name(t) +
                    ", expected UINT");
  }

  void bind_float(const char* name, float* plane) {
    check_float(name);
    bind(name, Imf::FLOAT, plane, sizeof(float));  // OpenEXR converts HALF to float
  }

  void bind_uint(const char* name, uint32_t* data) {
    check_uint(name);
    bind(name, Imf::UINT, data, sizeof(uint32_t));
  }

  void read(Imf::InputFile& file) {
    file.setFrameBuffer(frame_buffer_);
    file.readPixels(0, height_ - 1);
  }

  // An attribute of type A, nullptr when absent; present with another type is an error.
  template <class A>
  const A* attribute(const char* name) const {
    auto it = header_.find(name);
    if (it == header_.end()) return nullptr;
    const A* a = dynamic_cast<const A*>(&it.attribute());
    if (!a)
      throw IoError(path_ + ": attribute '" + name + "' has type " + it.attribute().typeName() +
                    ", expected " + A::staticTypeName());
    return a;
  }

 private:
  Imf::PixelType check_channel(const char* name) const {
    const Imf::Channel* ch = header_.channels().findChannel(name);
    if (!ch) throw IoError(path_ + ": channel '" + name + "' is missing");
    if (ch->xSampling != 1 || ch->ySampling != 1)
      throw IoError(path_ + ": channel '" + name + "' is subsampled");
    return ch->type;
  }

  void bind(const char* name, Imf::PixelType type, void* base, size_t elem) {
    frame_buffer_.insert(name, Imf::Slice(type, static_cast<char*>(base), elem,
                                          elem * static_cast<size_t>(width_)));
  }

  const std::string& path_;
  const Imf::Header& header_;
  int width_ = 0, height_ = 0;
  Imf::FrameBuffer frame_buffer_;
};

// Runs `open_and_read()`; library exceptions become IoErrors naming `name`.
template <class OpenAndRead>
auto translate_errors(const std::string& name, OpenAndRead open_and_read) {
  try {
    return open_and_read();
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(name + ": " + one_line(e.what()));
  }
}

// Opens `path` and runs `body(file)`; library exceptions become IoErrors naming the file.
template <class Body>
auto with_input_file(const std::string& path, Body body) {
  check_exr_file(path);
  return translate_errors(path, [&] {
    Imf::InputFile file(path.c_str());
    return body(file);
  });
}

// The bytes of an OpenEXR file held by the caller, read in place. Reads past the end throw,
// as IStream requires (OpenEXR turns a truncated file into an exception, never a short read).
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const char* data, size_t size, const std::string& name)
      : Imf::IStream(name.c_str()), data_(data), size_(size) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ > size_ || static_cast<uint64_t>(n) > size_ - pos_)
      throw Iex::InputExc("unexpected end of file");
    if (n > 0) std::memcpy(c, data_ + pos_, static_cast<size_t>(n));
    pos_ += static_cast<uint64_t>(n);
    return pos_ < size_;
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }  // past the end: the next read throws

 private:
  const char* data_;
  uint64_t size_;
  uint64_t pos_ = 0;
};

// with_input_file for the bytes of a file; `name` stands for the file in messages.
template <class Body>
auto with_input_bytes(const char* data, size_t size, const std::string& name, Body body) {
  if (size < 4 || !Imf::isImfMagic(data))
    throw IoError(name + ": not an OpenEXR file (bad magic number)");
  return translate_errors(name, [&] {
    MemoryIStream stream(data, size, name);
    Imf::InputFile file(stream);
    return body(file);
  });
}

// Everything read_frame checks before touching pixels, in the order it binds the channels, so
// that a file passing here fails later only for its pixel data.
FrameHeader inspect_header(const std::string& path, const ExrReader& r,
                           const detail::ExpectedSize& expected) {
  if (expected.width > 0 && (r.width() != expected.width || r.height() != expected.height))
    throw IoError(path + ": frame is " + std::to_string(r.width()) + "x" +
                  std::to_string(r.height()) + ", " + expected.source + " says " +
                  std::to_string(expected.width) + "x" + std::to_string(expected.height));
  if (const auto* v = r.attribute<Imf::IntAttribute>(kAttrFormatVersion);
      v && v->value() != kFormatVersion)
    throw IoError(path + ": unsupported " + kAttrFormatVersion + " " +
                  std::to_string(v->value()) + " (this reader knows " +
                  std::to_string(kFormatVersion) + ")");
  FrameHeader h;
  h.width = r.width();
  h.height = r.height();
  if (const auto* index = r.attribute<Imf::IntAttribute>(kAttrFrame)) {
    h.has_index = true;
    h.index = index->value();
  }
  r.attribute<Imf::M44fAttribute>(kAttrWorldToView);  // type checked here, read by read_frame
  r.attribute<Imf::M44fAttribute>(kAttrViewToClip);
  r.check_group(channel::kColor, false);
  r.check_group(channel::kAlbedo, false);
  r.check_group(channel::kNormal, false);
  r.check_group(channel::kPosition, true);
  r.check_float(channel::kDepth);
  r.check_group(channel::kDepthGradient, false);
  r.check_group(channel::kMotion, false);
  r.check_uint(channel::kMeshId);
  r.check_group(channel::kEmission, true);
  r.check_group(channel::kReference, true);
  h.has_direct = r.check_group(channel::kDirect, true);
  h.has_indirect = r.check_group(channel::kIndirect, true);
  r.check_group(channel::kGradient, true);
  return h;
}

}  // namespace

void write_frame(const std::string& path, const Frame& frame, const FrameStorage& storage) {
  try {
    check_frame_consistent(frame);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
  ExrWriter w(frame.width(), frame.height());
  Imf::Header& h = w.header();
  h.insert(kAttrFormatVersion, Imf::IntAttribute(kFormatVersion));
  h.insert(kAttrFrame, Imf::IntAttribute(frame.index));
  h.insert(kAttrWorldToView, Imf::M44fAttribute(to_m44f(frame.camera.world_to_view)));
  h.insert(kAttrViewToClip, Imf::M44fAttribute(to_m44f(frame.camera.view_to_clip)));

  w.add_group(channel::kColor, frame.color, storage.color);
  w.add_group(channel::kAlbedo, frame.albedo, storage.albedo);
  w.add_group(channel::kNormal, frame.normal, storage.normal);
  if (!frame.position.empty()) w.add_group(channel::kPosition, frame.position, storage.position);
  w.add_float(channel::kDepth, frame.depth.plane(0), storage.depth);
  w.add_group(channel::kDepthGradient, frame.depth_gradient, storage.depth);
  w.add_group(channel::kMotion, frame.motion, storage.motion);
  w.add_uint(channel::kMeshId, frame.mesh_id.data());
  if (!frame.emission.empty()) w.add_group(channel::kEmission, frame.emission, storage.color);
  if (!frame.reference.empty())
    w.add_group(channel::kReference, frame.reference, storage.reference);
  if (!frame.direct.empty()) w.add_group(channel::kDirect, frame.direct, storage.color);
  if (!frame.indirect.empty()) w.add_group(channel::kIndirect, frame.indirect, storage.color);
  if (!frame.gradient.empty())
    w.add_group(channel::kGradient, frame.gradient, PixelStorage::Float);
  write_exr(path, w);
}

namespace {

// The frame in `file`, checked as read_frame documents; `path` names the file in messages.
Frame read_frame_from(Imf::InputFile& file, const std::string& path, bool* has_index,
                      const detail::ExpectedSize& expected) {
  ExrReader r(path, file.header());
  const FrameHeader header = inspect_header(path, r, expected);
  Frame f;
  if (has_index) *has_index = header.has_index;
  f.index = header.index;
  if (const auto* m = r.attribute<Imf::M44fAttribute>(kAttrWorldToView))
    f.camera.world_to_view = from_m44f(m->value());
  if (const auto* m = r.attribute<Imf::M44fAttribute>(kAttrViewToClip))
    f.camera.view_to_clip = from_m44f(m->value());

  const int w = r.width(), h = r.height();
  f.color = r.read_group(channel::kColor, false);
  f.albedo = r.read_group(channel::kAlbedo, false);
  f.normal = r.read_group(channel::kNormal, false);
  f.position = r.read_group(channel::kPosition, true);
  f.depth = Image(w, h, 1);
  r.bind_float(channel::kDepth, f.depth.plane(0));
  f.depth_gradient = r.read_group(channel::kDepthGradient, false);
  f.motion = r.read_group(channel::kMotion, false);
  f.mesh_id.assign(static_cast<size_t>(w) * h, 0u);
  r.bind_uint(channel::kMeshId, f.mesh_id.data());
  f.emission = r.read_group(channel::kEmission, true);
  f.reference = r.read_group(channel::kReference, true);
  f.direct = r.read_group(channel::kDirect, true);
  f.indirect = r.read_group(channel::kIndirect, true);
  f.gradient = r.read_group(channel::kGradient, true);
  r.read(file);
  return f;
}

}  // namespace

Frame detail::read_frame(const std::string& path, bool* has_index, const ExpectedSize& expected) {
  return with_input_file(path, [&](Imf::InputFile& file) {
    return read_frame_from(file, path, has_index, expected);
  });
}

Frame read_frame(const std::string& path) { return detail::read_frame(path, nullptr); }

FrameHeader read_frame_header(const std::string& path, const detail::ExpectedSize& expected) {
  return with_input_file(path, [&](Imf::InputFile& file) {
    return inspect_header(path, ExrReader(path, file.header()), expected);
  });
}

Frame read_frame_from_memory(const char* data, size_t size, const std::string& name) {
  return with_input_bytes(data, size, name, [&](Imf::InputFile& file) {
    return read_frame_from(file, name, nullptr, {});
  });
}

void write_rgb_exr(const std::string& path, const Image& rgb) {
  if (rgb.empty() || rgb.channels() != 3)
    throw std::invalid_argument(path + ": write_rgb_exr needs a non-empty 3-channel image, got " +
                                std::to_string(rgb.width()) + "x" + std::to_string(rgb.height()) +
                                "x" + std::to_string(rgb.channels()));
  static const char* const kRgb[3] = {"R", "G", "B"};
  ExrWriter w(rgb.width(), rgb.height());
  w.add_group(kRgb, rgb, PixelStorage::Float);
  write_exr(path, w);
}

Image read_rgb_exr(const std::string& path) {
  return with_input_file(path, [&](Imf::InputFile& file) {
    static const char* const kRgb[3] = {"R", "G", "B"};
    ExrReader r(path, file.header());
    Image im = r.read_group(kRgb, false);
    r.read(file);
    return im;
  });
}

}  // namespace svgf::io
