#include "resolution/resolve_policy.hpp"

#include "collision/backend.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace canopy {

void ResolveConfig::check() const {
  const auto positive = [](const char* what, double v) {
    if (!std::isfinite(v) || v <= 0)
      throw std::invalid_argument(
          fmt::format("resolution: {} must be a finite number above 0 (got {})", what, v));
  };
  if (!std::isfinite(clearance) || clearance < 0 || clearance > kMaxClearance)
    throw std::invalid_argument(
        fmt::format("resolution: the clearance must be a finite number of metres from 0 to {} (got {})",
                    kMaxClearance, clearance));
  positive("the angle tolerance (degrees)", angle_tolerance_deg);
  positive("the scan step (degrees)", scan_step_deg);
  positive("the bend step (degrees)", bend_step_deg);
  if (bend_joints < 1)
    throw std::invalid_argument(
        fmt::format("resolution: bend joints must be at least 1 (got {})", bend_joints));
  for (std::size_t k = 0; k < kind_weight.size(); ++k)
    if (movable[k]) positive(fmt::format("the {} weight", kOrganKindNames[k]).c_str(), kind_weight[k]);
  if (max_rounds < 1 || candidates < 1 || axis_fan < 0 || stall_rounds < 1)
    throw std::invalid_argument(
        fmt::format("resolution: rounds ({}), candidates ({}) and stall rounds ({}) must be at least 1, "
                    "axes ({}) at least 0",
                    max_rounds, candidates, stall_rounds, axis_fan));
}

KindMask ResolveConfig::default_movable_kinds() {
  KindMask k{};
  for (OrganKind o : {OrganKind::leaflet, OrganKind::rachis, OrganKind::petiole, OrganKind::peduncle})
    k[static_cast<std::size_t>(o)] = true;
  return k;
}

std::array<int, 7> ResolveConfig::default_kind_rank() {
  std::array<int, 7> r{};
  r.fill(9);
  r[static_cast<std::size_t>(OrganKind::leaflet)] = 0;
  r[static_cast<std::size_t>(OrganKind::peduncle)] = 1;
  r[static_cast<std::size_t>(OrganKind::rachis)] = 2;
  r[static_cast<std::size_t>(OrganKind::petiole)] = 3;
  return r;
}

std::array<double, 7> ResolveConfig::default_kind_weight() {
  std::array<double, 7> w{};
  w.fill(1);
  w[static_cast<std::size_t>(OrganKind::rachis)] = 1.5;
  w[static_cast<std::size_t>(OrganKind::petiole)] = 2;
  return w;
}

namespace {

bool carried(OrganKind k) { return k == OrganKind::fruit || k == OrganKind::flower; }

/// The organ and its ancestors that may turn, nearest first.
void chain(const Stand& s, std::int32_t organ, const ResolveConfig& cfg, std::vector<std::uint32_t>& out) {
  for (std::int32_t k = organ; k >= 0; k = s.organs[static_cast<std::size_t>(k)].parent) {
    const OrganKind kind = s.organs[static_cast<std::size_t>(k)].kind;
    if (cfg.movable[static_cast<std::size_t>(kind)]) out.push_back(static_cast<std::uint32_t>(k));
    else if (!carried(kind)) break;  // an internode (or any kind that may not turn) holds the rest
  }
}

}  // namespace

std::vector<std::uint32_t> candidate_movers(const Stand& s, const Joints& j, const Contact& c,
                                            const ResolveConfig& cfg, std::string& why) {
  std::vector<std::uint32_t> all;
  chain(s, c.organ_a, cfg, all);
  chain(s, c.organ_b, cfg, all);
  const std::size_t before = all.size();
  std::erase_if(all, [&](std::uint32_t k) { return j.holds(k, c.organ_a) && j.holds(k, c.organ_b); });
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  if (all.empty()) {
    const OrganKind ka = s.organs[static_cast<std::size_t>(c.organ_a)].kind,
                    kb = s.organs[static_cast<std::size_t>(c.organ_b)].kind;
    why = before > 0 ? "the two organs turn only together (one subtree holds both)"
                     : fmt::format("neither organ may turn ({} and {}, and no turnable organ carries them)",
                                   name_of(ka), name_of(kb));
    return all;
  }
  const bool between = c.plant_a != c.plant_b;
  const auto key = [&](std::uint32_t k) {
    const Affine3f& t = s.transforms[k];
    const float out = between && cfg.outer_first ? std::sqrt(t.t.x * t.t.x + t.t.y * t.t.y) : 0.0f;
    return std::make_tuple(cfg.kind_rank[static_cast<std::size_t>(s.organs[k].kind)], -out,
                           j.subtree_end(k) - k, ~k);
  };
  std::sort(all.begin(), all.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  return all;
}

}  // namespace canopy
