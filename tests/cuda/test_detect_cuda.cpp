// The CUDA backend gives exactly the CPU backend's contacts, at every level, on the oracle
// stands, crowded plants, twins on one spot, a stand far from the origin, with a clearance, and
// on 1,000- and 10,000-plant default stands. (Skipped without a GPU: see test_device.cpp.)
#include "../collision/hard_cases.hpp"
#include "../collision/helpers.hpp"
#include "resolution/resolve.hpp"
#include "cuda/check.hpp"
#include "cuda/detect_cuda.hpp"
#include "cuda/device.hpp"
#include "cuda/stand_on_device.hpp"
#include "collision/broad_phase.hpp"
#include "geometry/organ_mesh.hpp"

#include <algorithm>
#include <cstring>

#include <chrono>

using namespace canopy;
using namespace canopy::test;

namespace {

void same_everywhere(const Stand& s, DetectRequest req, const char* what) {
  auto cpu = make_cpu_backend();
  auto gpu = cuda::make_cuda_backend();
  for (ContactLevel level :
       {ContactLevel::plant, ContactLevel::leaf, ContactLevel::organ, ContactLevel::exact}) {
    req.level = level;
    const Contacts a = cpu->detect(s, req), b = gpu->detect(s, req);
    INFO(what << " level " << name_of(level));
    CHECK(a.pairs == b.pairs);
    for (std::size_t l = 0; l <= static_cast<std::size_t>(level); ++l) {
      REQUIRE(a.counts[l].has_value());
      REQUIRE(b.counts[l].has_value());
      CHECK(a.counts[l]->between == b.counts[l]->between);
      CHECK(a.counts[l]->within == b.counts[l]->within);
    }
  }
}

Stand default_stand(int n) {
  GrowRequest req;
  req.grammar = source("grammars/tomato.yaml");
  req.plants = default_stand_layout(n);
  return grow_stand(req);
}

}  // namespace

TEST_CASE("CUDA equals CPU on the oracle stands, and both equal brute force") {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Stand s = random_stand(seed);
    DetectRequest req;
    same_everywhere(s, req, "random");
    req.collide = parse_collide_kinds("all");
    same_everywhere(s, req, "random, all kinds");
    req.level = ContactLevel::exact;
    CHECK(cuda::make_cuda_backend()->detect(s, req).pairs == brute_force_exact(s, req.collide));
  }
}

TEST_CASE("CUDA equals CPU with a clearance, on crowded plants, twins and far from the origin") {
  DetectRequest req;
  req.clearance = 0.005f;
  same_everywhere(random_stand(21, 8), req, "clearance");
  GrowRequest g;
  g.grammar = source("grammars/tomato.yaml");
  for (const char* o : {"phyllotaxis=15", "internode_min=0.015", "internode_max=0.02"})
    g.load.overrides.push_back(parse_override(o));
  g.steps = 14;
  PlantPlacement p;
  p.seed = 3;
  g.plants = {p, p};
  p.x = 0.2, p.seed = 4;
  g.plants.push_back(p);
  same_everywhere(grow_stand(g), DetectRequest{}, "crowded twins");
  for (auto& q : g.plants) q.x += 1e6, q.y -= 2e6;
  same_everywhere(grow_stand(g), DetectRequest{}, "far from the origin");
}

TEST_CASE(
    "CUDA equals CPU on one plant, with no organ taking part, on plants kilometres apart, and for active "
    "plants") {
  GrowRequest g;
  g.grammar = source("grammars/tomato.yaml");
  g.steps = 14;
  PlantPlacement p;
  g.plants = {p};
  same_everywhere(grow_stand(g), DetectRequest{}, "one plant");
  DetectRequest none;
  none.collide = KindMask{};  // no kind takes part
  same_everywhere(grow_stand(g), none, "no organ taking part");
  // A close group, and plants 300 km and 200 km away (a sparse grid of few, far cells).
  for (double x : {0.3, 0.6}) p.x = x, p.seed += 1, g.plants.push_back(p);
  p.x = 3e5, p.y = 0, g.plants.push_back(p);
  p.x = 0, p.y = -2e5, g.plants.push_back(p);
  const Stand far = grow_stand(g);
  same_everywhere(far, DetectRequest{}, "kilometres apart");
  // Re-detection limited to active plants (as resolution rounds ask): the device grid's filter.
  auto cpu = make_cpu_backend();
  auto gpu = cuda::make_cuda_backend();
  DetectRequest req;
  cpu->detect(far, req), gpu->detect(far, req);
  const std::vector<std::uint8_t> active{0, 1, 0, 1, 0};
  req.active_plants = &active;
  for (ContactLevel level : {ContactLevel::plant, ContactLevel::leaf, ContactLevel::exact}) {
    req.level = level;
    INFO(name_of(level));
    const Contacts a = cpu->redetect(far, req, {}), b = gpu->redetect(far, req, {});
    CHECK(a.pairs == b.pairs);
    CHECK(a.counts[0]->between == b.counts[0]->between);
    CHECK(a.counts[0]->within == b.counts[0]->within);
  }
}

TEST_CASE("the hard cases on the device: the triangle tests and detection give the host's answers") {
  // Every triangle pair in every vertex order and both argument orders, with and without a
  // clearance: the device's answer is the host's (and, without clearance, the one worked out by hand).
  std::vector<std::array<Vec3f, 6>> pairs;
  std::vector<int> want;
  for (const TrianglePairCase& c : hard_triangle_pairs()) {
    std::array<int, 3> pa{0, 1, 2};
    do {
      std::array<int, 3> pb{0, 1, 2};
      do {
        pairs.push_back({c.a[pa[0]], c.a[pa[1]], c.a[pa[2]], c.b[pb[0]], c.b[pb[1]], c.b[pb[2]]});
        pairs.push_back({c.b[pb[0]], c.b[pb[1]], c.b[pb[2]], c.a[pa[0]], c.a[pa[1]], c.a[pa[2]]});
        want.push_back(c.meet), want.push_back(c.meet);
      } while (std::next_permutation(pb.begin(), pb.end()));
    } while (std::next_permutation(pa.begin(), pa.end()));
  }
  for (float clearance : {0.0f, 1e-4f, 0.05f}) {
    const std::vector<std::uint8_t> got = cuda::device_triangle_tests(pairs, clearance);
    REQUIRE(got.size() == pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Vec3f* p = pairs[k].data();
      const bool host = clearance > 0 ? triangles_within(p, p + 3, clearance) : triangles_intersect(p, p + 3);
      INFO("pair " << k << ", clearance " << clearance);
      CHECK(static_cast<bool>(got[k]) == host);
      if (clearance == 0) CHECK(host == static_cast<bool>(want[k]));
    }
  }
  DetectRequest req;
  req.collide = parse_collide_kinds("all");
  for (const BuiltCase& c : hard_built_stands()) same_everywhere(c.built.stand, req, c.what.c_str());
}

TEST_CASE("CUDA equals CPU on 1,000- and 10,000-plant default stands") {
  for (int n : {1000, 10000}) {
    const Stand s = default_stand(n);
    auto cpu = make_cpu_backend();
    auto gpu = cuda::make_cuda_backend();
    DetectRequest req;
    const auto t0 = std::chrono::steady_clock::now();
    const Contacts a = cpu->detect(s, req);
    const auto t1 = std::chrono::steady_clock::now();
    gpu->detect(s, req);  // warm-up
    const auto t2 = std::chrono::steady_clock::now();
    const Contacts b = gpu->detect(s, req);
    const auto t3 = std::chrono::steady_clock::now();
    INFO(n << " plants");
    CHECK(a.pairs == b.pairs);
    MESSAGE(n << " plants: " << b.pairs.size() << " exact contacts; cpu "
              << std::chrono::duration<double>(t1 - t0).count() << " s, cuda (stand load included) "
              << std::chrono::duration<double>(t3 - t2).count() << " s on " << gpu->device());
    // A second detection of the resident stand with nothing moved gives the same list.
    CHECK(gpu->redetect(s, req, {}).pairs == b.pairs);
    for (ContactLevel level : {ContactLevel::organ, ContactLevel::leaf, ContactLevel::plant}) {
      req.level = level;
      INFO(name_of(level));
      const Contacts c = cpu->detect(s, req), d = gpu->detect(s, req);
      CHECK(c.pairs == d.pairs);
      for (std::size_t l = 0; l <= static_cast<std::size_t>(level); ++l) {
        CHECK(c.counts[l]->between == d.counts[l]->between);
        CHECK(c.counts[l]->within == d.counts[l]->within);
      }
    }
  }
}

TEST_CASE("resolution on CUDA: the same turns, transforms and contacts as on the CPU") {
  for (bool device_search : {true, false})
    for (int n : {20, 300}) {
      const char* way = device_search ? "attempts on the device (the default)" : "the host's search";
      INFO(way);
      GrowRequest g;
      g.grammar = source("grammars/tomato.yaml");
      g.plants = default_stand_layout(n);
      for (PlantPlacement& p : g.plants) p.x *= 0.7;  // denser than the default: more to resolve
      Stand a = grow_stand(g), b = a;
      auto cpu = make_cpu_backend();
      auto gpu = cuda::make_cuda_backend();
      ResolveRequest req;
      req.bulk_attempts = device_search;
      const Contacts ca = cpu->detect(a, req.detect), cb = gpu->detect(b, req.detect);
      REQUIRE(ca.pairs == cb.pairs);
      const ResolveResult ra = resolve(a, *cpu, req, ca), rb = resolve(b, *gpu, req, cb);
      INFO(n << " plants: " << ra.contacts_before << " -> " << ra.contacts_after);
      CHECK(ra.contacts_after == rb.contacts_after);
      CHECK(ra.rounds == rb.rounds);
      CHECK(ra.organs_moved == rb.organs_moved);
      CHECK(ra.planning == "host search");
      CHECK(rb.planning == (device_search
                                ? "device attempts, " + std::to_string(ResolveRequest{}.bulk_lanes) + " lanes"
                                : std::string("host search")));
      CHECK(std::memcmp(a.transforms.data(), b.transforms.data(), a.transforms.size() * sizeof(Affine3f)) ==
            0);
      // Re-detection after the rounds (refit kept on the device) equals a fresh CPU detection.
      CHECK(gpu->detect(b, req.detect).pairs == cpu->detect(a, req.detect).pairs);
      MESSAGE(n << " plants: " << ra.contacts_before << " -> " << ra.contacts_after << " contacts in "
                << ra.rounds << " rounds");
    }
}

TEST_CASE("resolution's attempts on every GPU of the machine: the CPU's turns") {
  // A process given another GPU than the first (a rank under mpirun) plans on that GPU from the
  // lanes' own threads, which start on device 0: each GPU must give the CPU's turns.
  GrowRequest g;
  g.grammar = source("grammars/tomato.yaml");
  g.plants = default_stand_layout(40);
  for (PlantPlacement& p : g.plants) p.x *= 0.7;
  const Stand grown = grow_stand(g);
  Stand a = grown;
  auto cpu = make_cpu_backend();
  ResolveRequest req;
  req.bulk_attempts = true;
  const ResolveResult ra = resolve(a, *cpu, req, cpu->detect(a, req.detect));
  const std::size_t devices = cuda::query_devices().devices.size();
  if (devices < 2)
    MESSAGE(
        "one GPU: the lanes' threads and the backend share device 0 (the case of a second GPU is not "
        "exercised)");
  for (std::size_t d = 0; d < devices; ++d) {
    INFO("device " << d);
    Stand b = grown;
    auto gpu = cuda::make_cuda_backend(static_cast<int>(d));
    const ResolveResult rb = resolve(b, *gpu, req, gpu->detect(b, req.detect));
    CHECK(rb.planning == "device attempts, " + std::to_string(ResolveRequest{}.bulk_lanes) + " lanes");
    CHECK(ra.contacts_after == rb.contacts_after);
    CHECK(ra.organs_moved == rb.organs_moved);
    CHECK(std::memcmp(a.transforms.data(), b.transforms.data(), a.transforms.size() * sizeof(Affine3f)) == 0);
  }
  CANOPY_CUDA_CHECK(cudaSetDevice(0));
}

TEST_CASE(
    "resolution's attempts on the device: the host search's turns at the organ level, with clearances, "
    "crowded") {
  // Asked for bulk attempts, the CUDA backend runs each level's attempts on the device
  // (BatchedScan + CudaAttemptRunner); the CPU backend searches candidate by candidate on the host.
  struct Case {
    const char* name;
    ContactLevel level;
    float detect_clearance;
    double clearance;
    bool crowded;
    std::size_t lanes = ResolveRequest{}.bulk_lanes, batch = ResolveRequest{}.batch_contacts;
    /// Levels of fewer candidates searched on the host: none (every level on the device) unless
    /// the case says so.
    std::size_t host_below = 0;
  };
  for (const Case& k :
       {Case{"organ level", ContactLevel::organ, 0, 1e-4, false},
        Case{"clearances", ContactLevel::exact, 0.001f, 0.002, false},
        Case{"crowded", ContactLevel::exact, 0, 1e-4, true},
        Case{"one lane", ContactLevel::exact, 0, 1e-4, false, 1},
        Case{"batches of 40 contacts, 3 lanes at once", ContactLevel::exact, 0, 1e-4, false, 3, 40},
        Case{"crowded, batches of 25, 8 lanes", ContactLevel::exact, 0, 1e-4, true, 8, 25},
        Case{"small levels on the host (the default)", ContactLevel::exact, 0, 1e-4, false,
             ResolveRequest{}.bulk_lanes, ResolveRequest{}.batch_contacts,
             ResolveRequest{}.host_levels_below},
        Case{"crowded, levels below 16 on the host, 2 lanes", ContactLevel::exact, 0, 1e-4, true, 2, 40,
             16}}) {
    GrowRequest g;
    g.grammar = source("grammars/tomato.yaml");
    g.plants = default_stand_layout(k.crowded ? 12 : 40);
    for (PlantPlacement& p : g.plants) p.x *= k.crowded ? 0.3 : 0.7, p.y *= k.crowded ? 0.3 : 1.0;
    Stand a = grow_stand(g), b = a;
    auto cpu = make_cpu_backend();
    auto gpu = cuda::make_cuda_backend();
    ResolveRequest req;
    req.config.level = k.level;
    req.bulk_attempts = true;  // the CPU backend has no runner: it searches on the host
    req.bulk_lanes = k.lanes, req.batch_contacts = k.batch, req.host_levels_below = k.host_below;
    req.config.clearance = k.clearance;
    req.config.max_rounds = k.crowded ? 5 : req.config.max_rounds;
    req.detect.level = k.level;
    req.detect.clearance = k.detect_clearance;
    const Contacts ca = cpu->detect(a, req.detect), cb = gpu->detect(b, req.detect);
    REQUIRE(ca.pairs == cb.pairs);
    const ResolveResult ra = resolve(a, *cpu, req, ca), rb = resolve(b, *gpu, req, cb);
    INFO(std::string(k.name) << ": " << ra.contacts_before << " -> " << ra.contacts_after);
    CHECK(ra.organs_moved > 0);
    CHECK(ra.contacts_after == rb.contacts_after);
    CHECK(ra.rounds == rb.rounds);
    CHECK(ra.organs_moved == rb.organs_moved);
    CHECK(ra.mean_turn_deg == rb.mean_turn_deg);
    CHECK(std::memcmp(a.transforms.data(), b.transforms.data(), a.transforms.size() * sizeof(Affine3f)) == 0);
    MESSAGE(std::string(k.name) << ": " << ra.contacts_before << " -> " << ra.contacts_after << " contacts, "
                                << ra.organs_moved << " turned");
  }
}

TEST_CASE("a stand that must be batched: the same contacts in batches under --max-device-memory") {
  GrowRequest g;
  g.grammar = source("grammars/tomato.yaml");
  g.plants = default_stand_layout(400);
  const Stand s = grow_stand(g);
  auto cpu = make_cpu_backend();
  auto gpu = cuda::make_cuda_backend();
  for (ContactLevel level : {ContactLevel::leaf, ContactLevel::organ, ContactLevel::exact}) {
    DetectRequest req;
    req.level = level;
    const Contacts want = cpu->detect(s, req);
    const Contacts whole = gpu->detect(s, req);
    CHECK(whole.batches == 1);
    // What the stand itself needs, from the error for too small a budget; then 300 KB for lists.
    req.max_device_bytes = 1;  // probe: the error names what the stand needs
    std::string message;
    try {
      gpu->detect(s, req);
    } catch (const cuda::CudaError& e) {
      message = e.what();
    }
    INFO(message);
    REQUIRE(message.find("the stand needs") != std::string::npos);
    const double needs_mb = std::stod(message.substr(message.find("needs") + 6));
    req.max_device_bytes = static_cast<std::size_t>(needs_mb * 1e6) + 300000;
    const Contacts batched = gpu->detect(s, req);
    MESSAGE(name_of(level) << ": " << batched.batches << " batches under " << req.max_device_bytes
                           << " bytes");
    CHECK(batched.batches > 1);
    CHECK(batched.pairs == want.pairs);
    for (std::size_t l = 0; l <= static_cast<std::size_t>(level); ++l) {
      CHECK(batched.counts[l]->between == want.counts[l]->between);
      CHECK(batched.counts[l]->within == want.counts[l]->within);
    }
  }
}

TEST_CASE(
    "the device stand's organ OBBs are the host's bit for bit, fitted and refitted (the attempts read "
    "them)") {
  for (std::uint64_t seed : {3, 8}) {
    INFO("seed " << seed);
    Stand s = random_stand(seed);
    PrototypeLibrary lib, host_lib;
    const Mbvt tree = build_mbvt_topology(s, MbvtConfig{});
    cuda::StandOnDevice dev;
    dev.load(s, tree, lib, plants_with_free_pairs(s, tree));
    dev.fit(0);
    CHECK(dev.obb_clearance() == 0);
    make_meshes(s, host_lib, 2);
    const auto differing = [&] {
      CANOPY_CUDA_CHECK(cudaDeviceSynchronize());
      std::vector<Obb> got(s.organ_count());
      CANOPY_CUDA_CHECK(
          cudaMemcpy(got.data(), dev.view().obbs, got.size() * sizeof(Obb), cudaMemcpyDeviceToHost));
      std::size_t n = 0;
      for (std::size_t k = 0; k < got.size(); ++k) {
        const OrganRecord& r = s.organs[k];
        const Obb want = make_obb(s.transforms[k], host_lib.get(r).box, 0);
        n += std::memcmp(&want, &got[k], sizeof(Obb)) != 0;
      }
      return n;
    };
    CHECK(differing() == 0);
    // Every third organ turned a little about its own axes (as resolution turns them), refitted.
    std::vector<std::uint32_t> moved;
    for (std::uint32_t k = 0; k < s.organ_count(); k += 3) {
      Affine3f& m = s.transforms[k];
      const float c = 0.9f, d = 0.43588989f;
      const Vec3f c0 = m.c0, c1 = m.c1;
      m.c0 = c0 * c + c1 * d, m.c1 = c1 * c - c0 * d;
      moved.push_back(k);
    }
    dev.refit(s, tree, moved);
    CHECK(differing() == 0);
  }
}

TEST_CASE("curved leaflets: CUDA equals CPU at every level and both equal brute force") {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Stand s = curved_stand(seed, 1 + static_cast<int>(seed % 3));
    DetectRequest req;
    same_everywhere(s, req, "curved");
    req.collide = parse_collide_kinds("all");
    same_everywhere(s, req, "curved, all kinds");
    req.level = ContactLevel::exact;
    CHECK(cuda::make_cuda_backend()->detect(s, req).pairs == brute_force_exact(s, req.collide));
  }
}
