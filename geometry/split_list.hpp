#pragma once
/// The items of a comma-separated list as the command line and the benchmarks take them
/// (`--formats glb,obj`, `--collide leaflet,petiole`, `--sizes 200,1000`): split at every
/// separator, each item exactly as written, so that a caller can name an empty or unknown item in
/// its refusal. n separators make n + 1 items; an empty text is one empty item.
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

inline std::vector<std::string> split_list(std::string_view text, char separator = ',') {
  std::vector<std::string> items;
  for (std::size_t i = 0;;) {
    const std::size_t j = text.find(separator, i);
    items.emplace_back(text.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i));
    if (j == std::string_view::npos) return items;
    i = j + 1;
  }
}

}  // namespace canopy
