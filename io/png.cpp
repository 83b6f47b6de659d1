#include "io/png.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "io/atomic_file.h"
#include "io/io_error.h"

namespace svgf::io {
namespace {

struct PngErrorState {
  char message[256];
};

void on_png_error(png_structp png, png_const_charp msg) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof(state->message), "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp, so this function holds no objects with destructors: the
// jump must not skip any. Returns false with `state->message` set on failure.
bool write_png_file(const char* path, const uint8_t* rgb, int width, int height,
                    PngErrorState* state) {
  std::FILE* fp = std::fopen(path, "wb");
  if (!fp) {
    std::snprintf(state->message, sizeof(state->message), "cannot open for writing: %s",
                  std::strerror(errno));
    return false;
  }
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, state, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    std::fclose(fp);
    std::snprintf(state->message, sizeof(state->message), "out of memory");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const size_t row_bytes = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, rgb + static_cast<size_t>(y) * row_bytes);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(fp) != 0) {
    std::snprintf(state->message, sizeof(state->message), "write error: %s",
                  std::strerror(errno));
    return false;
  }
  return true;
}

}  // namespace

void write_png_rgb8(const std::string& path, const uint8_t* rgb, int width, int height) {
  if (width <= 0 || height <= 0 || !rgb)
    throw IoError(path + ": invalid PNG image " + std::to_string(width) + "x" +
                  std::to_string(height));
  write_atomically(path, [&](const std::string& tmp) {
    PngErrorState state{};
    if (!write_png_file(tmp.c_str(), rgb, width, height, &state))
      throw IoError(path + ": " + state.message);
  });
}

std::string encode_png_rgb8(const uint8_t* rgb, int width, int height) {
  if (width <= 0 || height <= 0 || !rgb)
    throw IoError("invalid PNG image " + std::to_string(width) + "x" + std::to_string(height));
  // libpng's simplified API: no longjmp to guard against, errors in image.message.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgb, 0, nullptr))
    throw IoError(std::string("PNG encoding failed: ") + image.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb, 0, nullptr))
    throw IoError(std::string("PNG encoding failed: ") + image.message);
  bytes.resize(size);
  return bytes;
}

Rgb8Image decode_png_rgb8(const std::string& bytes, const std::string& what) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw IoError(what + ": not a readable PNG (" + image.message + ")");
  image.format = PNG_FORMAT_RGB;
  Rgb8Image out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  png_color black{0, 0, 0};
  if (!png_image_finish_read(&image, &black, out.rgb.data(), 0, nullptr)) {
    png_image_free(&image);
    throw IoError(what + ": PNG decoding failed (" + image.message + ")");
  }
  return out;
}

}  // namespace svgf::io
