#include "resolution/joints.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace canopy {

Mat3d axis_angle(Vec3d k, double angle) { return axis_angle(k, std::cos(angle), std::sin(angle)); }

double rotation_angle_deg(const Mat3d& r) {
  const double c = std::clamp((r.m[0] + r.m[4] + r.m[8] - 1) / 2, -1.0, 1.0);
  return std::acos(c) * 180 / std::numbers::pi;
}

Joints::Joints(const Stand& s, int threads) {
  const std::size_t n = s.organ_count();
  grown_.resize(n), parent_.resize(n), subtree_end_.resize(n), slot_.resize(n);
  // Every entry written here, on all threads (the allocator leaves them unwritten).
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) {
    grown_[i] = s.transforms[i];
    parent_[i] = s.organs[i].parent;  // a global id in the stand
    subtree_end_[i] = static_cast<std::uint32_t>(i + 1);
    slot_[i] = -1;
  }
  // Subtree ends over organs [first, end), from the last back, so that a subtree's end reaches
  // its root; false when a parent lies outside the run.
  const auto ends = [&](std::size_t first, std::size_t end) {
    bool inside = true;
    for (std::size_t i = end; i-- > first;)
      if (parent_[i] >= 0) {
        const auto q = static_cast<std::size_t>(parent_[i]);
        if (q < first || q >= end) inside = false;
        else subtree_end_[q] = std::max(subtree_end_[q], subtree_end_[i]);
      }
    return inside;
  };
  // Plant by plant on all threads (a plant's organs are a contiguous run, its structure tree
  // inside it); a stand whose trees or runs are not per plant, as one run.
  bool per_plant = true;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) reduction(&& : per_plant)
  for (std::size_t p = 0; p < s.plant_count(); ++p)
    per_plant = ends(s.plants[p].first_organ, s.plants[p].first_organ + s.plants[p].organ_count) && per_plant;
  std::size_t covered = 0;
  for (const PlantRecord& p : s.plants) covered += p.organ_count;
  if (!per_plant || covered != n) {
    for (std::size_t i = 0; i < n; ++i) subtree_end_[i] = static_cast<std::uint32_t>(i + 1);
    ends(0, n);
  }
}

double Joints::angle_deg(std::uint32_t k) const {
  return slot_[k] < 0 ? 0.0 : rotation_angle_deg(local_[static_cast<std::size_t>(slot_[k])]);
}

Motion Joints::motion(std::uint32_t k) const {
  // Turned joints on the path to the root, applied root first.
  std::uint32_t chain[512];
  int n = 0;
  for (std::int32_t a = static_cast<std::int32_t>(k); a >= 0; a = parent_[static_cast<std::size_t>(a)])
    if (slot_[static_cast<std::size_t>(a)] >= 0 && n < 512) chain[n++] = static_cast<std::uint32_t>(a);
  Motion d;
  while (n-- > 0) {
    const std::uint32_t a = chain[n];
    d = compose(d, rotation_about(to_double(grown_[a].t), local_[static_cast<std::size_t>(slot_[a])]));
  }
  return d;
}

Joints::JointFrame Joints::joint_frame(std::uint32_t k) const {
  const std::int32_t p = parent_[k];
  JointFrame f;
  f.parent = p >= 0 ? motion(static_cast<std::uint32_t>(p)).r : Mat3d{};
  f.parent_t = transpose(f.parent);
  f.local = slot_[k] >= 0 ? local_[static_cast<std::size_t>(slot_[k])] : Mat3d{};
  return f;
}

Mat3d Joints::local_after(std::uint32_t k, const Mat3d& turn) const {
  return local_after(joint_frame(k), turn);
}

void Joints::set_local(std::uint32_t k, const Mat3d& q) {
  if (slot_[k] < 0) {
    slot_[k] = static_cast<std::int32_t>(local_.size());
    local_.push_back(q);
    turned_ids_.push_back(k);
  } else {
    local_[static_cast<std::size_t>(slot_[k])] = q;
  }
}

std::vector<std::uint32_t> Joints::update(Stand& s, const std::vector<std::uint32_t>& turned,
                                          int threads) const {
  std::vector<std::uint32_t> roots = turned;
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  // Keep the outermost turned organs: a subtree inside another one is rewritten with it.
  std::vector<std::uint32_t> outer;
  for (std::uint32_t k : roots)
    if (outer.empty() || k >= subtree_end_[outer.back()]) outer.push_back(k);
      // The subtrees are disjoint: each is rewritten on its own (on all threads, tens of thousands
      // per resolution round), the same transforms in any order.
#pragma omp parallel num_threads(threads > 0 ? threads : omp_get_max_threads())
  {
    std::vector<Motion> d;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t o = 0; o < outer.size(); ++o) {
      const std::uint32_t k = outer[o], end = subtree_end_[k];
      d.assign(end - k, Motion{});
      d[0] = motion(k);
      for (std::uint32_t i = k; i < end; ++i) {
        if (i > k) {
          const Motion& up = d[static_cast<std::size_t>(parent_[i]) - k];
          d[i - k] = slot_[i] >= 0 ? compose(up, rotation_about(to_double(grown_[i].t),
                                                                local_[static_cast<std::size_t>(slot_[i])]))
                                   : up;
        }
        s.transforms[i] = apply(d[i - k], grown_[i]);
      }
    }
  }
  std::vector<std::uint32_t> written;
  for (std::uint32_t k : outer)
    for (std::uint32_t i = k; i < subtree_end_[k]; ++i) written.push_back(i);
  return written;
}

}  // namespace canopy
