// libFuzzer target: any bytes as a stand folder's plants.csv and organs.csv (cut at the first NUL
// byte), read as canopy detect, canopy render and Python's Stand.read read them. The reader's
// errors are the expected way out; a stand it accepts must be one canopy could have written:
// consistent where detection indexes, and written out again and read back, the same stand, bit
// for bit.
#include "fuzz_files.hpp"
#include "geometry/export.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace {

/// A ChunkWriter into a string, one plant after another.
class StringChunks final : public canopy::ChunkWriter {
 public:
  void fixed(std::string_view text) override { s += text; }
  void plants(std::size_t n, std::size_t,
              const std::function<void(std::size_t, std::string&)>& make) override {
    for (std::size_t i = 0; i < n; ++i) make(i, s);
  }
  std::uint64_t offset() const override { return s.size(); }
  void patch(std::uint64_t at, std::string_view bytes) override { s.replace(at, bytes.size(), bytes); }
  std::string s;
};

bool same(const canopy::Stand& a, const canopy::Stand& b) {
  const auto bytes_equal = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  if (a.plants.size() != b.plants.size() || a.grammars != b.grammars) return false;
  for (std::size_t p = 0; p < a.plants.size(); ++p) {
    const canopy::PlantRecord &x = a.plants[p], &y = b.plants[p];
    if (std::memcmp(&x.x, &y.x, sizeof x.x) || std::memcmp(&x.y, &y.y, sizeof x.y) ||
        std::memcmp(&x.rotation_deg, &y.rotation_deg, sizeof x.rotation_deg) || x.seed != y.seed ||
        x.grammar != y.grammar || x.steps != y.steps || x.first_organ != y.first_organ ||
        x.organ_count != y.organ_count || x.first_leaf != y.first_leaf || x.leaf_count != y.leaf_count)
      return false;
  }
  return bytes_equal(a.transforms, b.transforms) && bytes_equal(a.organs, b.organs) &&
         bytes_equal(a.params, b.params) && bytes_equal(a.joint_limit_deg, b.joint_limit_deg);
}

/// What detection, resolution and the exports index by: every organ in its plant's range, a parent
/// earlier in the same plant, a compound leaf inside its plant's leaf range, arrays of one length,
/// numbers finite.
bool consistent(const canopy::Stand& s) {
  const std::size_t n = s.organ_count();
  if (s.transforms.size() != n || s.params.size() != n || s.joint_limit_deg.size() != n) return false;
  std::uint64_t organs = 0;
  for (std::size_t p = 0; p < s.plant_count(); ++p) {
    const canopy::PlantRecord& pr = s.plants[p];
    if (!std::isfinite(pr.x) || !std::isfinite(pr.y) || !std::isfinite(pr.rotation_deg)) return false;
    if (pr.grammar < 0 || static_cast<std::size_t>(pr.grammar) >= s.grammars.size()) return false;
    if (pr.organ_count > 0 && pr.first_organ != organs) return false;
    if (p + 1 < s.plant_count() && s.plants[p + 1].first_leaf != pr.first_leaf + pr.leaf_count) return false;
    organs += pr.organ_count;
    for (std::uint64_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      if (id >= n) return false;
      const canopy::OrganRecord& r = s.organs[id];
      if (r.plant != static_cast<std::int32_t>(p)) return false;
      if (r.parent != -1 &&
          (r.parent < static_cast<std::int32_t>(pr.first_organ) || r.parent >= static_cast<std::int32_t>(id)))
        return false;
      if (r.leaf != -1 && (r.leaf < static_cast<std::int32_t>(pr.first_leaf) ||
                           r.leaf >= static_cast<std::int32_t>(pr.first_leaf + pr.leaf_count)))
        return false;
      const float* t = &s.transforms[id].c0.x;
      for (int k = 0; k < 12; ++k)
        if (!std::isfinite(t[k])) return false;
      if (!std::isfinite(s.params[id][0]) || !std::isfinite(s.params[id][1]) ||
          !std::isfinite(s.joint_limit_deg[id]))
        return false;
    }
  }
  return organs == n;
}

canopy::Stand read_back(const canopy::Stand& s) {
  canopy::PrototypeLibrary lib;
  StringChunks plants, organs;
  canopy::write_plants_csv(canopy::ExportScope::whole(s), plants);
  canopy::write_organs_csv(canopy::ExportScope::whole(s), lib, organs);
  std::filesystem::create_directories(canopy::fuzz::scratch() + "/again");
  canopy::fuzz::put("again/plants.csv", plants.s);
  canopy::fuzz::put("again/organs.csv", organs.s);
  return canopy::read_stand(canopy::fuzz::scratch() + "/again");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [plants, organs] = canopy::fuzz::two_parts(data, size);
  canopy::fuzz::put("plants.csv", plants);
  canopy::fuzz::put("organs.csv", organs);
  canopy::Stand s;
  try {
    s = canopy::read_stand(canopy::fuzz::scratch());
  } catch (const std::runtime_error&) {
    return 0;
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (!consistent(s)) std::abort();          // a stand detection would index out of bounds
  if (!same(s, read_back(s))) std::abort();  // what it accepted, written and read again, differs
  return 0;
}
