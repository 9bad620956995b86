#include "cuda/detect_cuda.hpp"

#include "resolution/attempt_source.hpp"
#include "collision/broad_phase.hpp"
#include "cuda/attempt_runner_cuda.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/device.hpp"
#include "cuda/device_buffer.hpp"
#include "cuda/event_timer.hpp"
#include "cuda/device_lists.hpp"
#include "cuda/keys.hpp"
#include "cuda/plant_level.hpp"
#include "cuda/stand_on_device.hpp"
#include "geometry/clock.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

namespace canopy::cuda {
namespace {

/// Device bytes per organ pair in a batch: its key, the sorted copy, its hit flag, its record.
constexpr std::size_t kOrganPairBytes = 2 * sizeof(std::uint64_t) + 1 + sizeof(Contact);
/// Device bytes per cluster pair when the leaf level is the last: the pair, its key and work
/// item twice (two sorts), its record.
constexpr std::size_t kLeafPairBytes =
    sizeof(ClusterPair) + 2 * (sizeof(std::uint64_t) + sizeof(std::uint32_t)) + sizeof(Contact);

class CudaBackend : public DetectionBackend, public AttemptSource {
 public:
  explicit CudaBackend(int device) : device_(device) {
    const DeviceReport r = query_devices();
    if (device < 0 || static_cast<std::size_t>(device) >= r.devices.size())
      throw CudaError(fmt::format("no CUDA device {} ({})", device,
                                  r.devices.empty() ? r.unavailable_reason : "out of range"));
    name_ = r.devices[static_cast<std::size_t>(device)].name;
    CANOPY_CUDA_CHECK(cudaSetDevice(device));
    counters_.resize(1);
    // The stand's staging blocks from now on, while the stand grows (canopy stand starts the
    // backend meanwhile): the first large load would otherwise allocate them.
    dev_.reserve_staging();
  }
  std::string name() const override { return "cuda"; }
  std::string device() const override { return name_; }

  /// The stand's arrays set travelling, the tree's shape built on the host meanwhile (the
  /// stand's structure alone), then the rest of the upload (`load_s`: the upload the shape did
  /// not cover); then every box fitted on the device (`build_s`: the shape and the fit) and the
  /// stages.
  Contacts detect(const Stand& s, const DetectRequest& req) override {
    check_request(req);
    use_device();
    double t = now_seconds();
    lib_ = std::make_unique<PrototypeLibrary>();
    attempts_.reset();  // its tables belong to the stand held before
    tree_.reset();
    plants_.reset();
    dev_.begin_load(s, *lib_);
    double load_s = now_seconds() - t;
    t = now_seconds();
    std::vector<std::uint8_t> self;
    try {
      tree_ = build_mbvt_topology(s, mbvt_config(req));
      self = plants_with_free_pairs(s, *tree_);
    } catch (...) {
      dev_.abandon_load();  // the caller may free the stand as this unwinds
      tree_.reset();
      throw;
    }
    const double shape_s = now_seconds() - t;
    t = now_seconds();
    dev_.end_load(s, *tree_, self);
    load_s += now_seconds() - t;
    t = now_seconds();
    dev_.fit(req.clearance);
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    Contacts out = run(req, shape_s + now_seconds() - t);
    out.load_s = load_s;
    return out;
  }

  /// The device runs resolution's bulk attempts against the stand it holds (the one detected or
  /// re-detected last: its meshes, organ records and origins; the transforms travel with the
  /// attempts).
  AttemptRunner* attempt_runner(const Stand& s) override {
    if (!tree_ || tree_->takes_part.size() != s.organ_count()) return nullptr;
    use_device();
    if (!attempts_) attempts_ = std::make_unique<CudaAttemptRunner>(dev_);
    return attempts_.get();
  }

  Contacts redetect(const Stand& s, const DetectRequest& req,
                    const std::vector<std::uint32_t>& moved) override {
    check_request(req);
    if (!tree_ || tree_->takes_part.size() != s.organ_count())
      throw std::logic_error("redetect: no tree of this stand from an earlier detect()");
    use_device();
    const double t = now_seconds();
    dev_.refit(s, *tree_, moved);  // on the device: only the moved organs' transforms travel
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    return run(req, now_seconds() - t);
  }

 private:
  /// The backend's device made current on the calling thread: the backend may have been made on
  /// another (canopy stand starts it while the stand grows), and a thread's device is its own.
  void use_device() const { CANOPY_CUDA_CHECK(cudaSetDevice(device_)); }

  /// Bytes of the stage lists held now (free for the next batch's lists).
  std::size_t list_bytes() const {
    return cluster_pairs_.size() * sizeof(ClusterPair) +
           (organ_keys_.size() + organ_sorted_.size()) * sizeof(std::uint64_t) +
           (leaf_work_.size() + leaf_work_sorted_.size()) * sizeof(std::uint32_t) + hits_.size() +
           contacts_.size() * sizeof(Contact) + keys_.bytes();
  }

  /// Device bytes the stage lists may use: the request's budget (or what is free now, with the
  /// lists already held counted as free) less what the stand and the work list hold.
  std::size_t stage_budget(const DetectRequest& req, std::size_t work_bytes) {
    const std::size_t held = dev_.bytes() + work_bytes + sizeof(Counters);
    std::size_t budget = req.max_device_bytes;
    if (!budget) {
      std::size_t free = 0, total = 0;
      CANOPY_CUDA_CHECK(cudaMemGetInfo(&free, &total));
      budget = held + (free + list_bytes()) / 10 * 9;
    }
    if (budget <= held + 4096)
      throw CudaError(
          fmt::format("the stand needs {:.1f} MB on the device, more than the {:.1f} MB allowed{}",
                      static_cast<double>(held) / 1e6, static_cast<double>(budget) / 1e6,
                      req.max_device_bytes ? " (--max-device-memory)" : " (free device memory)"));
    return budget - held;
  }

  /// The contact records of n organ-pair keys, made on the device and appended to `to`.
  void download_contacts(const std::uint64_t* keys, std::size_t n, bool tight, std::vector<Contact>& to) {
    contacts_.fit(n, tight);
    launch_contacts(dev_.view(), keys, static_cast<std::uint32_t>(n), contacts_.get());
    append_download(to, contacts_.get(), n, staged_contacts_);
  }

  /// A batch's nc cluster pairs as keys pair_key(a, b) sorted into organ_sorted_, their work
  /// items alongside in leaf_work_sorted_.
  void sort_cluster_pairs(std::size_t nc, bool tight) {
    organ_keys_.fit(nc, tight), organ_sorted_.fit(nc, tight), leaf_work_.fit(nc, tight),
        leaf_work_sorted_.fit(nc, tight);
    launch_cluster_keys(cluster_pairs_.get(), static_cast<std::uint32_t>(nc), organ_keys_.get(),
                        leaf_work_.get());
    keys_.sort_pairs(organ_keys_.get(), organ_sorted_.get(), leaf_work_.get(), leaf_work_sorted_.get(), nc);
  }

  /// The leaf level's records of a batch's nc cluster pairs, sorted as the CPU sorts them (plant
  /// pair, then clusters): by cluster pair, then stably by work item (work items are sorted).
  void download_cluster_contacts(const WorkItem* batch, std::size_t nc, bool tight,
                                 std::vector<Contact>& to) {
    sort_cluster_pairs(nc, tight);
    keys_.sort_pairs(leaf_work_sorted_.get(), leaf_work_.get(), organ_sorted_.get(), organ_keys_.get(), nc);
    contacts_.fit(nc, tight);
    launch_cluster_contacts(batch, leaf_work_.get(), organ_keys_.get(), static_cast<std::uint32_t>(nc),
                            contacts_.get());
    append_download(to, contacts_.get(), nc, staged_contacts_);
  }

  Contacts run(const DetectRequest& req, double build_s) {
    Contacts out;
    out.level = req.level;
    out.build_s = build_s;
    const bool tight = req.max_device_bytes != 0;
    EventTimer plant_timer, leaf_timer, organ_timer, exact_timer;
    double t = now_seconds();
    const std::vector<std::uint64_t> work =
        plants_.work(dev_, req, tight, keys_, counters_, plant_timer, out.counts[0], work_);
    out.seconds[0] = now_seconds() - t;
    out.device_seconds[0] = plant_timer.seconds();
    if (req.level == ContactLevel::plant) {
      for (std::uint64_t k : work)
        out.pairs.push_back(
            {-1, -1, static_cast<std::int32_t>(key_hi(k)), static_cast<std::int32_t>(key_lo(k)), -1, -1});
      return out;
    }

    // Leaf, organ and exact stages, in batches of plant pairs whose lists fit the budget: a
    // batch that does not fit is halved. An organ pair belongs to one plant pair, so to one batch.
    const std::size_t budget = stage_budget(req, work.size() * sizeof(WorkItem) + plants_.bytes());
    LevelCount leaves, organs;
    std::size_t batches = 0;
    double t_leaf = 0, t_organ = 0, t_exact = 0;
    for (std::size_t lo = 0, size = work.size(); lo < work.size();) {
      const std::size_t hi = std::min(work.size(), lo + size);
      const auto n = static_cast<std::uint32_t>(hi - lo);
      const WorkItem* batch = work_.get() + lo;
      if (tight) {
        cluster_pairs_.resize(0), organ_keys_.resize(0), organ_sorted_.resize(0), hits_.resize(0),
            contacts_.resize(0);
        leaf_work_.resize(0), leaf_work_sorted_.resize(0), keys_.release();
      }
      t = now_seconds();
      Counters host{};
      const std::size_t pair_bytes = req.level == ContactLevel::leaf ? kLeafPairBytes : sizeof(ClusterPair);
      const std::size_t nc = collect(cluster_pairs_, counters_, host, 64 * std::size_t{n},
                                     std::min(kMaxItems, budget / pair_bytes), tight, leaf_timer,
                                     [&](ClusterPair* o, unsigned long long cap) {
                                       launch_cluster_pairs(dev_.view(), batch, n, o, cap, counters_.get());
                                     });
      bool fits = nc * pair_bytes <= budget &&
                  (req.level != ContactLevel::leaf || nc * pair_bytes + KeyOps::scratch_bytes(nc) <= budget);
      const Counters leaf_counts = host;
      t_leaf += now_seconds() - t;
      std::size_t no = 0;
      if (fits && req.level != ContactLevel::leaf) {
        t = now_seconds();
        // Cluster pairs in key order, so that neighbouring threads descend the same trees: an
        // optional step, left out under a memory budget or when its lists would not fit.
        const std::size_t sort_bytes =
            nc * (sizeof(ClusterPair) + 2 * (sizeof(std::uint64_t) + sizeof(std::uint32_t))) +
            KeyOps::scratch_bytes(nc);
        if (!tight && sort_bytes <= budget) {
          organ_timer.start();
          sort_cluster_pairs(nc, false);
          launch_cluster_pairs_from_keys(organ_sorted_.get(), leaf_work_sorted_.get(),
                                         static_cast<std::uint32_t>(nc), cluster_pairs_.get());
          organ_timer.stop();
        }
        const std::size_t room = (budget - nc * sizeof(ClusterPair)) / kOrganPairBytes;
        no = collect(organ_keys_, counters_, host, 4 * nc + 1024, std::min(kMaxItems, room), tight,
                     organ_timer, [&](std::uint64_t* o, unsigned long long cap) {
                       launch_organ_pairs(dev_.view(), batch, cluster_pairs_.get(),
                                          static_cast<std::uint32_t>(nc), o, cap, counters_.get());
                     });
        fits = no <= room &&
               nc * sizeof(ClusterPair) + no * kOrganPairBytes + KeyOps::scratch_bytes(no) <= budget;
        t_organ += now_seconds() - t;
      }
      if (!fits) {
        if (n == 1)
          throw CudaError(fmt::format(
              "plants {} and {} alone need more device memory than the {:.1f} MB allowed for lists",
              key_hi(work[lo]), key_lo(work[lo]), static_cast<double>(budget) / 1e6));
        size = std::max<std::size_t>(1, (hi - lo) / 2);
        continue;
      }
      ++batches;
      leaves.between += static_cast<std::size_t>(leaf_counts.between);
      leaves.within += static_cast<std::size_t>(leaf_counts.within);
      if (req.level == ContactLevel::leaf) {
        t = now_seconds();
        leaf_timer.start();
        download_cluster_contacts(batch, nc, tight, out.pairs);
        leaf_timer.stop();
        t_leaf += now_seconds() - t;
      } else {
        t = now_seconds();
        // Sorted, without repeats (one organ pair can be reached through several node pairs).
        organ_sorted_.fit(no, tight);
        organ_timer.start();
        keys_.sort(organ_keys_.get(), organ_sorted_.get(), no);
        const std::size_t nu = keys_.unique(organ_sorted_.get(), organ_keys_.get(), no);
        CANOPY_CUDA_CHECK(cudaMemset(counters_.get(), 0, sizeof(Counters)));
        launch_count_pairs(dev_.view(), organ_keys_.get(), static_cast<std::uint32_t>(nu), counters_.get());
        organ_timer.stop();
        CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters_.get(), sizeof host, cudaMemcpyDeviceToHost));
        organs.between += static_cast<std::size_t>(host.between);
        organs.within += static_cast<std::size_t>(host.within);
        if (req.level == ContactLevel::organ) download_contacts(organ_keys_.get(), nu, tight, out.pairs);
        t_organ += now_seconds() - t;
        if (req.level == ContactLevel::exact) {
          t = now_seconds();
          hits_.fit(nu, tight);
          exact_timer.start();
          launch_exact(dev_.view(), organ_keys_.get(), static_cast<std::uint32_t>(nu), req.clearance,
                       hits_.get());
          const std::size_t nh = keys_.select(organ_keys_.get(), hits_.get(), organ_sorted_.get(), nu);
          exact_timer.stop();
          download_contacts(organ_sorted_.get(), nh, tight, out.pairs);
          t_exact += now_seconds() - t;
        }
      }
      lo = hi;
    }
    out.batches = std::max<std::size_t>(batches, 1);
    out.counts[1] = leaves;
    out.seconds[1] = t_leaf;
    out.device_seconds[1] = leaf_timer.seconds();
    if (req.level == ContactLevel::leaf) return out;  // batches follow the sorted work list
    out.counts[2] = organs;
    out.seconds[2] = t_organ;
    out.device_seconds[2] = organ_timer.seconds();
    // Each batch's pairs come sorted; batches of later plant pairs may hold lower organ ids.
    t = now_seconds();
    if (batches > 1) std::sort(out.pairs.begin(), out.pairs.end());
    if (req.level == ContactLevel::organ) {
      out.seconds[2] += now_seconds() - t;
      return out;
    }
    out.counts[3] = count_pairs(out.pairs);
    out.seconds[3] = t_exact + (now_seconds() - t);
    out.device_seconds[3] = exact_timer.seconds();
    return out;
  }

  int device_;
  std::string name_;
  std::optional<Mbvt> tree_;
  std::unique_ptr<PrototypeLibrary> lib_;
  StandOnDevice dev_;
  KeyOps keys_;
  PlantLevel plants_;
  DeviceBuffer<WorkItem> work_;
  DeviceBuffer<ClusterPair> cluster_pairs_;
  DeviceBuffer<std::uint64_t> organ_keys_, organ_sorted_;
  DeviceBuffer<std::uint32_t> leaf_work_, leaf_work_sorted_;
  DeviceBuffer<std::uint8_t> hits_;
  DeviceBuffer<Contact> contacts_;
  DeviceBuffer<Counters> counters_;
  PinnedBuffer<Contact> staged_contacts_;
  std::unique_ptr<CudaAttemptRunner> attempts_;
};

}  // namespace

std::unique_ptr<DetectionBackend> make_cuda_backend(int device) {
  return std::make_unique<CudaBackend>(device);
}

}  // namespace canopy::cuda
