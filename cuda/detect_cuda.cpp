#include "cuda/detect_cuda.hpp"

#include "collision/broad_phase.hpp"
#include "cuda/detect_kernels.hpp"
#include "cuda/device.hpp"
#include "cuda/device_buffer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>

namespace canopy::cuda {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// Runs `launch` into a buffer of `capacity` items; when more were found, grows the buffer to fit
/// and runs again. Returns the item count.
template <typename T, typename Launch>
std::size_t collect(DeviceBuffer<T>& out, DeviceBuffer<Counters>& counters, Counters& host, std::size_t capacity, Launch&& launch) {
  for (;;) {
    out.resize(std::max<std::size_t>(capacity, 1));
    const Counters zero{};
    CANOPY_CUDA_CHECK(cudaMemcpy(counters.get(), &zero, sizeof zero, cudaMemcpyHostToDevice));
    launch(out.get(), static_cast<unsigned long long>(out.size()));
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    CANOPY_CUDA_CHECK(cudaMemcpy(&host, counters.get(), sizeof host, cudaMemcpyDeviceToHost));
    if (host.appended <= out.size()) return static_cast<std::size_t>(host.appended);
    capacity = static_cast<std::size_t>(host.appended);
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
    // Prototype meshes, stored once.
    std::vector<MeshRef> meshes(4 * (kMaxLod + 1));
    std::vector<Vec3f> positions;
    std::vector<std::uint32_t> indices;
    for (const OrganRecord& r : s.organs) {
      MeshRef& ref = meshes[static_cast<std::size_t>(r.prototype) * (kMaxLod + 1) + r.lod];
      if (ref.vertex_count) continue;
      const PrototypeMesh& pm = lib_->get(r.prototype, r.lod);
      ref = {static_cast<std::uint32_t>(positions.size()), static_cast<std::uint32_t>(pm.positions.size()),
             static_cast<std::uint32_t>(indices.size()), static_cast<std::uint32_t>(pm.triangle_count())};
      positions.insert(positions.end(), pm.positions.begin(), pm.positions.end());
      indices.insert(indices.end(), pm.indices.begin(), pm.indices.end());
    }
    upload(s, *tree_, meshes, positions, indices);
    return run(s, req, now() - t);
  }

  Contacts redetect(const Stand& s, const DetectRequest& req, const std::vector<std::uint32_t>& moved) override {
    if (!tree_ || tree_->obbs.size() != s.organ_count())
      throw std::logic_error("redetect: no tree of this stand from an earlier detect()");
    const double t = now();
    Mbvt& m = *tree_;
    refit_mbvt(m, s, *lib_, moved);
    // Only what changed travels: the moved organs' transforms and boxes, the LCD nodes of their
    // plants, and the plant bounds.
    std::vector<Affine3f> tr;
    std::vector<Obb> ob;
    for (std::uint32_t k : moved) tr.push_back(s.transforms[k]), ob.push_back(m.obbs[k]);
    scatter(transforms_, moved, tr);
    scatter(obbs_, moved, ob);
    std::vector<std::uint8_t> dirty(s.plant_count(), 0);
    for (std::uint32_t k : moved) dirty[static_cast<std::size_t>(s.organs[k].plant)] = 1;
    std::vector<std::uint32_t> node_ids;
    std::vector<LcdNode> nodes;
    for (std::size_t p = 0; p < s.plant_count(); ++p) {
      if (!dirty[p]) continue;
      const PlantBound& pb = m.plants[p];
      for (std::uint32_t c = pb.first_cluster; c < pb.first_cluster + pb.cluster_count; ++c)
        for (std::uint32_t n = m.clusters[c].first_node; n < m.clusters[c].first_node + m.clusters[c].node_count; ++n)
          node_ids.push_back(n), nodes.push_back(m.nodes[n]);
    }
    scatter(nodes_, node_ids, nodes);
    plants_.upload(m.plants);
    view_.plants = plants_.get();
    return run(s, req, now() - t);
  }

 private:
  template <typename T>
  void scatter(DeviceBuffer<T>& dst, const std::vector<std::uint32_t>& ids, const std::vector<T>& values) {
    static_assert(sizeof(T) % 4 == 0);
    if (ids.empty()) return;
    scatter_ids_.upload(ids);
    DeviceBuffer<T> v;
    v.upload(values);
    launch_scatter(dst.get(), v.get(), scatter_ids_.get(), static_cast<std::uint32_t>(ids.size()), sizeof(T) / 4);
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
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

    t = now();
    work_.upload(work);
    Counters host{};
    const std::size_t nc = collect(cluster_pairs_, counters_, host, 64 * work.size(), [&](ClusterPair* o, unsigned long long cap) {
      launch_cluster_pairs(view_, work_.get(), static_cast<std::uint32_t>(work.size()), o, cap, counters_.get());
    });
    out.counts[1] = LevelCount{static_cast<std::size_t>(host.between), static_cast<std::size_t>(host.within)};
    out.seconds[1] = now() - t;
    if (req.level == ContactLevel::leaf) {
      for (const ClusterPair& c : cluster_pairs_.download(nc))
        out.pairs.push_back({-1, -1, work[c.work].p, work[c.work].q, static_cast<std::int32_t>(c.a), static_cast<std::int32_t>(c.b)});
      std::sort(out.pairs.begin(), out.pairs.end());
      return out;
    }

    t = now();
    const std::size_t no = collect(organ_pairs_, counters_, host, 4 * nc + 1024, [&](OrganPair* o, unsigned long long cap) {
      launch_organ_pairs(view_, work_.get(), cluster_pairs_.get(), static_cast<std::uint32_t>(nc), o, cap, counters_.get());
    });
    std::vector<OrganPair> organ = organ_pairs_.download(no);
    std::sort(organ.begin(), organ.end(), [](const OrganPair& a, const OrganPair& b) { return a.a != b.a ? a.a < b.a : a.b < b.b; });
    organ.erase(std::unique(organ.begin(), organ.end(), [](const OrganPair& a, const OrganPair& b) { return a.a == b.a && a.b == b.b; }),
                organ.end());
    std::vector<Contact> organ_contacts;
    for (const OrganPair& p : organ)
      organ_contacts.push_back({p.a, p.b, s.organs[static_cast<std::size_t>(p.a)].plant, s.organs[static_cast<std::size_t>(p.b)].plant, -1, -1});
    out.counts[2] = count_pairs(organ_contacts);
    out.seconds[2] = now() - t;
    if (req.level == ContactLevel::organ) {
      out.pairs = std::move(organ_contacts);
      return out;
    }

    t = now();
    organ_pairs_.upload(organ);
    hit_.resize(std::max<std::size_t>(organ.size(), 1));
    launch_exact(view_, work_.get(), organ_pairs_.get(), static_cast<std::uint32_t>(organ.size()), req.clearance, hit_.get());
    CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
    const std::vector<std::uint8_t> hit = hit_.download(organ.size());
    out.pairs = keep_hits(organ_contacts, hit);
    out.counts[3] = count_pairs(out.pairs);
    out.seconds[3] = now() - t;
    return out;
  }

  void upload(const Stand& s, const Mbvt& m, const std::vector<MeshRef>& meshes, const std::vector<Vec3f>& positions,
              const std::vector<std::uint32_t>& indices) {
    transforms_.upload(s.transforms);
    organs_.upload(s.organs);
    obbs_.upload(m.obbs);
    cluster_organs_.upload(m.cluster_organs);
    clusters_.upload(m.clusters);
    nodes_.upload(m.nodes);
    plants_.upload(m.plants);
    positions_.upload(positions);
    indices_.upload(indices);
    meshes_.upload(meshes);
    counters_.resize(1);
    view_ = {transforms_.get(), organs_.get(), obbs_.get(), cluster_organs_.get(), clusters_.get(), nodes_.get(),
             plants_.get(), positions_.get(), indices_.get(), meshes_.get()};
  }

  int device_;
  std::string name_;
  std::optional<Mbvt> tree_;
  std::unique_ptr<PrototypeLibrary> lib_;
  DeviceBuffer<std::uint32_t> scatter_ids_;
  DeviceBuffer<Affine3f> transforms_;
  DeviceBuffer<OrganRecord> organs_;
  DeviceBuffer<Obb> obbs_;
  DeviceBuffer<std::uint32_t> cluster_organs_;
  DeviceBuffer<Cluster> clusters_;
  DeviceBuffer<LcdNode> nodes_;
  DeviceBuffer<PlantBound> plants_;
  DeviceBuffer<Vec3f> positions_;
  DeviceBuffer<std::uint32_t> indices_;
  DeviceBuffer<MeshRef> meshes_;
  DeviceBuffer<WorkItem> work_;
  DeviceBuffer<ClusterPair> cluster_pairs_;
  DeviceBuffer<OrganPair> organ_pairs_;
  DeviceBuffer<std::uint8_t> hit_;
  DeviceBuffer<Counters> counters_;
  StandView view_{};
};

}  // namespace

std::unique_ptr<DetectionBackend> make_cuda_backend(int device) { return std::make_unique<CudaBackend>(device); }

}  // namespace canopy::cuda
