#pragma once
// Files for the geometry tests: a fresh folder under /tmp and a whole file read back.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace canopy::testing {

/// A new, empty folder /tmp/canopy-<tag>-XXXXXX.
inline std::string temp_dir(const std::string& tag) {
  std::string name = "/tmp/canopy-" + tag + "-XXXXXX";
  REQUIRE(mkdtemp(name.data()) != nullptr);
  return name;
}

/// The whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace canopy::testing
