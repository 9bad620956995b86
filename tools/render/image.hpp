#pragma once
/// An RGB8 image and its PNG file (libpng).
#include <cstdint>
#include <string>
#include <vector>

namespace canopy::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first
  Image() = default;
  Image(int w, int h)
      : width(w), height(h), rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0) {}
  std::uint8_t* at(int x, int y) {
    return &rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x)) *
                3];
  }
  const std::uint8_t* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x)) *
                3];
  }
  /// Copies `tile` with its top-left corner at (x, y).
  void paste(const Image& tile, int x, int y);
};

/// Writes `image` as an 8-bit RGB PNG; throws std::runtime_error naming the file on failure.
void write_png(const Image& image, const std::string& path);
/// Reads an 8-bit RGB PNG (for tests).
Image read_png(const std::string& path);

}  // namespace canopy::render
