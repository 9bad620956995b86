#include "collision/contacts.hpp"

#include <fmt/format.h>

namespace canopy {

void write_contacts_csv(const Stand& stand, const Contacts& c, AtomicFile& out) {
  ChunkFile f(out);
  write_contacts_csv(ExportScope::whole(stand), c.pairs, c.level, f);
}

void write_contacts_csv(const ExportScope& e, const std::vector<Contact>& pairs, ContactLevel level,
                        ChunkWriter& out) {
  out.fixed(std::string(kContactsCsvHeader) + "\n");
  // Rows grouped by their first plant: sorted pairs keep each plant's rows together.
  std::vector<std::size_t> first(e.stand.plant_count() + 1, 0);
  for (const Contact& k : pairs) ++first[static_cast<std::size_t>(k.plant_a) + 1];
  for (std::size_t p = 0; p < e.stand.plant_count(); ++p) first[p + 1] += first[p];
  std::vector<const Contact*> rows(pairs.size());
  {
    std::vector<std::size_t> at(first.begin(), first.end() - 1);
    for (const Contact& k : pairs) rows[at[static_cast<std::size_t>(k.plant_a)]++] = &k;
  }
  const std::string_view name = name_of(level);
  out.plants(e.plants.size(), 64, [&](std::size_t i, std::string& t) {
    const std::size_t p = e.plants[i];
    for (std::size_t r = first[p]; r < first[p + 1]; ++r) {
      const Contact& k = *rows[r];
      t += fmt::format("{},{},{},{},{}\n", e.organ(k.organ_a), e.organ(k.organ_b),
                       e.plant(static_cast<std::size_t>(k.plant_a)),
                       e.plant(static_cast<std::size_t>(k.plant_b)), name);
    }
  });
}

}  // namespace canopy
