#include "collision/contacts.hpp"

#include <fmt/format.h>

namespace canopy {

std::string contacts_csv(const Contacts& c) {
  std::string out = "organ_a,organ_b,plant_a,plant_b,level\n";
  const std::string_view level = name_of(c.level);
  for (const Contact& k : c.pairs) out += fmt::format("{},{},{},{},{}\n", k.organ_a, k.organ_b, k.plant_a, k.plant_b, level);
  return out;
}

}  // namespace canopy
