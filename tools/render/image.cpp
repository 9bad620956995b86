#include "tools/render/image.hpp"

#include "geometry/atomic_file.hpp"

#include <fmt/format.h>
#include <png.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace canopy::render {

void Image::paste(const Image& tile, int x0, int y0) {
  for (int y = 0; y < tile.height && y0 + y < height; ++y)
    for (int x = 0; x < tile.width && x0 + x < width; ++x) {
      const std::uint8_t* s = tile.at(x, y);
      std::uint8_t* d = at(x0 + x, y0 + y);
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    }
}

void write_png(const Image& img, const std::string& path) {
  // Made in memory, then written whole (AtomicFile: a temporary name, synced, renamed into place;
  // a device or FIFO written in place): the PNG it replaces stays whole until the new one is, and
  // a full disk or a kill leaves no cut-off file that reads as a picture.
  std::string bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error(fmt::format("cannot write {}: libpng failed", path));
  }
  png_set_write_fn(
      png, &bytes,
      [](png_structp p, png_bytep data, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(data), n);
      },
      [](png_structp) {});
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < img.height; ++y) png_write_row(png, const_cast<png_bytep>(img.at(0, y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  AtomicFile out(path);
  out.write(bytes);
  out.commit();
}

Image read_png(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw std::runtime_error(fmt::format("cannot read {}", path));
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::runtime_error(fmt::format("cannot read {}: not an 8-bit RGB PNG", path));
  }
  png_init_io(png, f.get());
  png_read_info(png, info);
  Image img(static_cast<int>(png_get_image_width(png, info)),
            static_cast<int>(png_get_image_height(png, info)));
  if (png_get_bit_depth(png, info) != 8 || png_get_color_type(png, info) != PNG_COLOR_TYPE_RGB) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::runtime_error(fmt::format("cannot read {}: not an 8-bit RGB PNG", path));
  }
  for (int y = 0; y < img.height; ++y) png_read_row(png, img.at(0, y), nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return img;
}

}  // namespace canopy::render
