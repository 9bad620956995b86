// What the ranks of a tiled run trade: per-level contact counts, turns of border plants, the
// contacts left unresolved; and the export scope of a rank's own plants.
#include "tools/tile_trade.hpp"

#include "distributed/mpi_comm.hpp"

#include <algorithm>
#include <cstring>

namespace canopy::cli {

ExportScope owned_scope(const Tile& t, const PlantScan& scan) {
  ExportScope e{
      t.stand, {}, {}, {}, {}, t.first_organ.size() - 1, static_cast<std::uint64_t>(t.first_organ.back()),
      &scan};
  for (std::size_t p = 0; p < t.region.size(); ++p) {
    const std::uint32_t g = t.region[p];
    if (t.owned[p]) e.plants.push_back(static_cast<std::uint32_t>(p));
    e.plant_id.push_back(g);
    e.organ_shift.push_back(t.first_organ[g] - static_cast<std::int64_t>(t.stand.plants[p].first_organ));
    e.leaf_shift.push_back(t.first_leaf[g] - static_cast<std::int64_t>(t.stand.plants[p].first_leaf));
  }
  return e;
}

Contacts detect_owned(DetectionBackend& backend, const Tile& t, DetectRequest req, ContactLevel level,
                      bool lower_levels, Contacts* all) {
  Contacts out;
  out.level = level;
  std::vector<std::int64_t> counts;
  for (int l = lower_levels ? 0 : static_cast<int>(level); l <= static_cast<int>(level); ++l) {
    req.level = static_cast<ContactLevel>(l);
    Contacts c = backend.detect(t.stand, req);
    if (all && l == static_cast<int>(level))
      *all = c;  // the full list; the backend's tree is left at this level
    std::erase_if(c.pairs, [&](const Contact& k) { return !t.owned[static_cast<std::size_t>(k.plant_a)]; });
    const LevelCount n = count_pairs(c.pairs);
    counts.push_back(static_cast<std::int64_t>(n.between));
    counts.push_back(static_cast<std::int64_t>(n.within));
    out.seconds[static_cast<std::size_t>(l)] = c.seconds[static_cast<std::size_t>(l)];
    out.build_s += c.build_s;
    if (l == static_cast<int>(level)) out.pairs = std::move(c.pairs);
  }
  counts = mpi::sum(counts);
  const std::size_t first = static_cast<std::size_t>(level) + 1 - counts.size() / 2;
  for (std::size_t l = 0; l * 2 < counts.size(); ++l)
    out.counts[first + l] =
        LevelCount{static_cast<std::size_t>(counts[2 * l]), static_cast<std::size_t>(counts[2 * l + 1])};
  return out;
}

namespace {

/// One turn on the wire: the global organ id, the joint's local rotation and the angle.
struct WireTurn {
  std::int64_t organ;
  double local[9];
  double angle_deg;
};

}  // namespace

std::vector<Turn> exchange_turns(const Tile& t, const std::vector<Turn>& mine) {
  std::vector<std::vector<char>> out(static_cast<std::size_t>(mpi::size()));
  for (const Turn& turn : mine) {
    const auto p = static_cast<std::size_t>(t.stand.organs[turn.organ].plant);
    WireTurn w{
        static_cast<std::int64_t>(turn.organ) - t.stand.plants[p].first_organ + t.first_organ[t.region[p]],
        {},
        turn.angle_deg};
    std::memcpy(w.local, turn.local.m, sizeof w.local);
    for (int r : t.holders[p]) {
      auto& b = out[static_cast<std::size_t>(r)];
      b.insert(b.end(), reinterpret_cast<const char*>(&w), reinterpret_cast<const char*>(&w) + sizeof w);
    }
  }
  std::vector<Turn> in;
  for (const std::vector<char>& b : mpi::alltoall_bytes(out))
    for (std::size_t at = 0; at + sizeof(WireTurn) <= b.size(); at += sizeof(WireTurn)) {
      WireTurn w;
      std::memcpy(&w, b.data() + at, sizeof w);
      const auto g =
          static_cast<std::size_t>(std::upper_bound(t.first_organ.begin(), t.first_organ.end(), w.organ) -
                                   t.first_organ.begin()) -
          1;
      const std::size_t p = t.local_of(static_cast<std::int64_t>(g));
      Turn turn;
      turn.organ = static_cast<std::uint32_t>(w.organ - t.first_organ[g] + t.stand.plants[p].first_organ);
      std::memcpy(turn.local.m, w.local, sizeof w.local);
      turn.angle_deg = w.angle_deg;
      in.push_back(turn);
    }
  return in;
}

/// The unresolved contacts of every rank on rank 0, in global ids and order.
std::vector<UnresolvedContact> gather_unresolved(const ExportScope& e,
                                                 const std::vector<UnresolvedContact>& mine) {
  std::vector<char> blob;
  const auto put = [&](std::int64_t v) {
    blob.insert(blob.end(), reinterpret_cast<const char*>(&v), reinterpret_cast<const char*>(&v) + 8);
  };
  for (const UnresolvedContact& u : mine) {
    put(e.organ(u.contact.organ_a)), put(e.organ(u.contact.organ_b));
    put(e.plant(static_cast<std::size_t>(u.contact.plant_a))),
        put(e.plant(static_cast<std::size_t>(u.contact.plant_b)));
    put(static_cast<std::int64_t>(u.reason.size()));
    blob.insert(blob.end(), u.reason.begin(), u.reason.end());
  }
  const std::vector<char> all = mpi::allgather_bytes(blob.data(), blob.size());
  std::vector<UnresolvedContact> out;
  std::size_t at = 0;
  const auto get = [&] {
    std::int64_t v;
    std::memcpy(&v, all.data() + at, 8);
    at += 8;
    return v;
  };
  while (at < all.size()) {
    UnresolvedContact u;
    u.contact.organ_a = static_cast<std::int32_t>(get()),
    u.contact.organ_b = static_cast<std::int32_t>(get());
    u.contact.plant_a = static_cast<std::int32_t>(get()),
    u.contact.plant_b = static_cast<std::int32_t>(get());
    const auto n = static_cast<std::size_t>(get());
    u.reason.assign(all.data() + at, n);
    at += n;
    out.push_back(std::move(u));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.contact < b.contact; });
  return out;
}

}  // namespace canopy::cli
