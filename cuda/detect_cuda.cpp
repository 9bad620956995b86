#include "cuda/detect_cuda.hpp"

#include "collision/broad_phase.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/device.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/event_timer.hpp"
#include "cuda/stand_on_device.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>

namespace canopy::cuda {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// Runs `launch` into `out` with room for `capacity` items, at most `limit`; when more were
/// found and they fit the limit, grows the buffer and runs again. Returns the items found, which
/// exceed `limit` when they do not fit (then nothing usable is in `out`).
template <typename T, typename Launch>
std::size_t collect(DeviceBuffer<T>& out, DeviceBuffer<Counters>& counters, Counters& host, std::size_t capacity, std::size_t limit,
                    EventTimer& timer, Launch&& launch) {
  capacity = std::max<std::size_t>(std::min(capacity, limit), 1);
  for (;;) {
    out.resize(capacity);
    const Counters zero{};
    CANOPY_CUDA_CHECK(cudaMemcpy(counters.get(), &zero, sizeof zero, cudaMemcpyHostToDevice));
    timer.start();
    launch(out.get(), static_cast<unsigned long long>(out.size()));
    timer.stop();
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters.get(), sizeof host, cudaMemcpyDeviceToHost));
    const auto found = static_cast<std::size_t>(host.appended);
    if (found <= out.size() || found > limit) return found;
    capacity = found;
  }
}

class CudaBackend : public DetectionBackend {
 public:
  explicit CudaBackend(int device) : device_(device) {
    const DeviceReport r = query_devices();
    if (device < 0 || static_cast<std::size_t>(device) >= r.devices.size())
      throw CudaError(fmt::format("no CUDA device {} ({})", device, r.devices.empty() ? r.unavailable_reason : "out of range"));
    name_ = r.devices[static_cast<std::size_t>(device)].name;
    CANOPY_CUDA_CHECK(cudaSetDevice(device));
  }
  std::string name() const override { return "cuda"; }
  std::string device() const override { return name_; }

  Contacts detect(const Stand& s, const DetectRequest& req) override {
    const double t = now();
    lib_ = std::make_unique<PrototypeLibrary>();
    tree_ = build_mbvt(s, *lib_, mbvt_config(req));
    dev_.load(s, *tree_, *lib_);
    counters_.resize(1);
    return run(s, req, now() - t);
  }

  Contacts redetect(const Stand& s, const DetectRequest& req, const std::vector<std::uint32_t>& moved) override {
    if (!tree_ || tree_->obbs.size() != s.organ_count())
      throw std::logic_error("redetect: no tree of this stand from an earlier detect()");
    const double t = now();
    dev_.refit(s, *tree_, moved);  // on the device; the host keeps only the plant bounds current
    return run(s, req, now() - t);
  }

 private:
  /// Device bytes the stage lists may use: the request's budget (or what is free now, with the
  /// lists already held counted as free) less what the stand holds.
  std::size_t stage_budget(const DetectRequest& req, std::size_t work_bytes) {
    const std::size_t held = dev_.bytes() + work_bytes + sizeof(Counters);
    std::size_t budget = req.max_device_bytes;
    if (!budget) {
      std::size_t free = 0, total = 0;
      CANOPY_CUDA_CHECK(cudaMemGetInfo(&free, &total));
      free += cluster_pairs_.size() * sizeof(ClusterPair) + organ_pairs_.size() * sizeof(OrganPair) + hit_.size();
      budget = held + free / 10 * 9;
    }
    if (budget <= held + 4096)
      throw CudaError(fmt::format("the stand needs {:.1f} MB on the device, more than the {:.1f} MB allowed{}",
                                  static_cast<double>(held) / 1e6, static_cast<double>(budget) / 1e6,
                                  req.max_device_bytes ? " (--max-device-memory)" : " (free device memory)"));
    return budget - held;
  }

  Contacts run(const Stand& s, const DetectRequest& req, double build_s) {
    Contacts out;
    out.level = req.level;
    out.build_s = build_s;
    const Mbvt& m = *tree_;
    // Plant level on the host, exactly as the CPU backend: grid pairs and plants with themselves.
    double t = now();
    LevelCount plants;
    std::vector<WorkItem> work;
    for (const auto& [p, q] : plant_level(s, m, plants, req.active_plants))
      work.push_back({p, q, p == q ? Vec3f{0, 0, 0} : plant_offset(s, p, q)});
    out.counts[0] = plants;
    out.seconds[0] = now() - t;
    if (req.level == ContactLevel::plant) {
      for (const WorkItem& w : work) out.pairs.push_back({-1, -1, w.p, w.q, -1, -1});
      return out;
    }

    // Leaf and organ levels, in batches of plant pairs whose lists fit the budget: a batch that
    // does not fit is halved.
    t = now();
    work_.upload(work);
    const std::size_t budget = stage_budget(req, work.size() * sizeof(WorkItem));
    LevelCount leaves;
    std::vector<OrganPair> organ;
    EventTimer leaf_timer, organ_timer, exact_timer;
    std::size_t batches = 0;
    double t_leaf = 0;
    for (std::size_t lo = 0, size = work.size(); lo < work.size();) {
      const std::size_t hi = std::min(work.size(), lo + size);
      const auto n = static_cast<std::uint32_t>(hi - lo);
      const WorkItem* batch = work_.get() + lo;
      cluster_pairs_.resize(0), organ_pairs_.resize(0), hit_.resize(0);  // the budget is for this batch alone
      Counters host{};
      const std::size_t nc = collect(cluster_pairs_, counters_, host, 64 * std::size_t{n}, budget / sizeof(ClusterPair), leaf_timer,
                                     [&](ClusterPair* o, unsigned long long cap) {
                                       launch_cluster_pairs(dev_.view(), batch, n, o, cap, counters_.get());
                                     });
      std::size_t no = 0;
      bool fits = nc * sizeof(ClusterPair) <= budget;
      const Counters leaf_counts = host;
      if (fits && req.level != ContactLevel::leaf) {
        const std::size_t room = (budget - nc * sizeof(ClusterPair)) / sizeof(OrganPair);
        no = collect(organ_pairs_, counters_, host, 4 * nc + 1024, room, organ_timer, [&](OrganPair* o, unsigned long long cap) {
          launch_organ_pairs(dev_.view(), batch, cluster_pairs_.get(), static_cast<std::uint32_t>(nc), o, cap, counters_.get());
        });
        fits = no <= room;
      }
      if (!fits) {
        if (n == 1)
          throw CudaError(fmt::format("plants {} and {} alone need more device memory than the {:.1f} MB allowed for lists",
                                      work[lo].p, work[lo].q, static_cast<double>(budget) / 1e6));
        size = std::max<std::size_t>(1, (hi - lo) / 2);
        continue;
      }
      ++batches;
      leaves.between += static_cast<std::size_t>(leaf_counts.between);
      leaves.within += static_cast<std::size_t>(leaf_counts.within);
      if (req.level == ContactLevel::leaf) {
        for (const ClusterPair& c : cluster_pairs_.download(nc))
          out.pairs.push_back({-1, -1, work[lo + c.work].p, work[lo + c.work].q, static_cast<std::int32_t>(c.a),
                               static_cast<std::int32_t>(c.b)});
      } else {
        std::vector<OrganPair> part = organ_pairs_.download(no);
        for (OrganPair& p : part) p.work += static_cast<std::uint32_t>(lo);  // into the whole work list
        organ.insert(organ.end(), part.begin(), part.end());
      }
      lo = hi;
    }
    out.batches = std::max<std::size_t>(batches, 1);
    out.counts[1] = leaves;
    out.device_seconds[1] = leaf_timer.seconds();
    out.device_seconds[2] = organ_timer.seconds();
    t_leaf = now() - t;
    out.seconds[1] = t_leaf;
    if (req.level == ContactLevel::leaf) {
      std::sort(out.pairs.begin(), out.pairs.end());
      return out;
    }
    t = now();
    std::sort(organ.begin(), organ.end(), [](const OrganPair& a, const OrganPair& b) { return a.a != b.a ? a.a < b.a : a.b < b.b; });
    organ.erase(std::unique(organ.begin(), organ.end(), [](const OrganPair& a, const OrganPair& b) { return a.a == b.a && a.b == b.b; }),
                organ.end());
    std::vector<Contact> organ_contacts;
    organ_contacts.reserve(organ.size());
    for (const OrganPair& p : organ)
      organ_contacts.push_back({p.a, p.b, s.organs[static_cast<std::size_t>(p.a)].plant, s.organs[static_cast<std::size_t>(p.b)].plant, -1, -1});
    out.counts[2] = count_pairs(organ_contacts);
    out.seconds[2] = now() - t;
    if (req.level == ContactLevel::organ) {
      out.pairs = std::move(organ_contacts);
      return out;
    }

    // Exact level, in batches of organ pairs that fit (a pair and its flag each).
    t = now();
    cluster_pairs_.resize(0);
    std::vector<std::uint8_t> hit(organ.size(), 0);
    const std::size_t per = std::max<std::size_t>(1, budget / (sizeof(OrganPair) + 1));
    for (std::size_t lo = 0; lo < organ.size(); lo += per) {
      const std::size_t n = std::min(per, organ.size() - lo);
      organ_pairs_.resize(n);
      CANOPY_CUDA_CHECK(cudaMemcpy(organ_pairs_.get(), organ.data() + lo, n * sizeof(OrganPair), cudaMemcpyHostToDevice));
      hit_.resize(n);
      exact_timer.start();
      launch_exact(dev_.view(), work_.get(), organ_pairs_.get(), static_cast<std::uint32_t>(n), req.clearance, hit_.get());
      exact_timer.stop();
      CANOPY_CUDA_CHECK(cudaMemcpy(hit.data() + lo, hit_.get(), n, cudaMemcpyDeviceToHost));
      if (lo > 0) ++out.batches;
    }
    out.device_seconds[3] = exact_timer.seconds();
    out.pairs = keep_hits(organ_contacts, hit);
    out.counts[3] = count_pairs(out.pairs);
    out.seconds[3] = now() - t;
    return out;
  }

  int device_;
  std::string name_;
  std::optional<Mbvt> tree_;
  std::unique_ptr<PrototypeLibrary> lib_;
  StandOnDevice dev_;
  DeviceBuffer<WorkItem> work_;
  DeviceBuffer<ClusterPair> cluster_pairs_;
  DeviceBuffer<OrganPair> organ_pairs_;
  DeviceBuffer<std::uint8_t> hit_;
  DeviceBuffer<Counters> counters_;
};

}  // namespace

std::unique_ptr<DetectionBackend> make_cuda_backend(int device) { return std::make_unique<CudaBackend>(device); }

}  // namespace canopy::cuda
