#pragma once
// Shared by the reader fuzz targets: the readers take paths, so each input is written to files in
// a folder of this process (made once, removed at exit) and read back from there.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace canopy::fuzz {

/// This process's scratch folder. Its name is never destroyed: the exit handler that removes the
/// folder runs after static objects made before it are gone.
inline const std::string& scratch() {
  static const std::string* dir = [] {
    auto* t = new std::string((std::filesystem::temp_directory_path() / "canopy-fuzz-XXXXXX").string());
    if (!mkdtemp(t->data())) std::abort();
    std::atexit([] { std::filesystem::remove_all(scratch()); });
    return t;
  }();
  return *dir;
}

/// Writes `bytes` to scratch()/name and returns its path.
inline std::string put(const std::string& name, std::string_view bytes) {
  const std::string path = scratch() + "/" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

/// The input cut at its first NUL byte: two files' contents (the second empty when there is none).
inline std::pair<std::string_view, std::string_view> two_parts(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const std::size_t cut = all.find('\0');
  if (cut == std::string_view::npos) return {all, {}};
  return {all.substr(0, cut), all.substr(cut + 1)};
}

}  // namespace canopy::fuzz
