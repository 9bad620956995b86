#pragma once
/// Contact levels and detection backends (docs/design.md "Contact levels", "Command line").
#include <array>
#include <optional>
#include <string_view>

namespace canopy {

/// Each level's set of organ pairs contains the next level's.
enum class ContactLevel { plant, leaf, organ, exact };
inline constexpr std::array<std::string_view, 4> kContactLevelNames{"plant", "leaf", "organ", "exact"};

enum class BackendKind { cpu, cuda, automatic };
inline constexpr std::array<std::string_view, 3> kBackendNames{"cpu", "cuda", "auto"};

inline std::string_view name_of(ContactLevel l) { return kContactLevelNames[static_cast<int>(l)]; }
inline std::string_view name_of(BackendKind b) { return kBackendNames[static_cast<int>(b)]; }

inline std::optional<ContactLevel> parse_contact_level(std::string_view s) {
  for (std::size_t i = 0; i < kContactLevelNames.size(); ++i)
    if (kContactLevelNames[i] == s) return static_cast<ContactLevel>(i);
  return std::nullopt;
}
inline std::optional<BackendKind> parse_backend(std::string_view s) {
  for (std::size_t i = 0; i < kBackendNames.size(); ++i)
    if (kBackendNames[i] == s) return static_cast<BackendKind>(i);
  return std::nullopt;
}

}  // namespace canopy
