// `--backend auto` (resolution/auto_backend.hpp) on the host: a test backend that offers a runner
// of resolution's bulk attempts, as the CUDA backend does, wrapped by auto. The runner must reach
// resolution (auto plans exactly as the wrapped backend does), and a failure of the wrapped
// backend, in detection or half-way through a round's attempts, must leave the same turns.
#include "resolution/attempt_runner_host.hpp"
#include "resolution/auto_backend.hpp"
#include "resolution/resolve.hpp"
#include "tests/collision/helpers.hpp"

#include <atomic>
#include <cstring>

using namespace canopy;
using namespace canopy::test;

namespace {

/// Stands in for a GPU's backend: detection through the CPU backend, attempts answered by a
/// HostAttemptRunner that counts its calls and that can fail (BackendFailure) at a given call.
class TestRunner : public HostAttemptRunner {
 public:
  TestRunner(PrototypeLibrary& lib, std::size_t lanes) : HostAttemptRunner(lib, 2, lanes) {}
  std::string hardware() const override { return "test"; }
  std::vector<std::uint32_t> touching(std::size_t lane, const AttemptTables& tables,
                                      std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override {
    if (++calls == fail_at) throw BackendFailure("the test device failed");
    return HostAttemptRunner::touching(lane, tables, groups, settings);
  }
  std::atomic<int> calls{0};
  int fail_at = -1;  // the call that throws (1 is the first); -1: none
};

class TestBackend : public DetectionBackend, public AttemptSource {
 public:
  explicit TestBackend(std::size_t lanes) : runner(lib, lanes) {}
  std::string name() const override { return "test"; }
  std::string device() const override { return "test device"; }
  Contacts detect(const Stand& s, const DetectRequest& r) override {
    if (fail_detect) throw BackendFailure("the test device is lost");
    return cpu->detect(s, r);
  }
  Contacts redetect(const Stand& s, const DetectRequest& r,
                    const std::vector<std::uint32_t>& moved) override {
    return cpu->redetect(s, r, moved);
  }
  AttemptRunner* attempt_runner(const Stand&) override { return &runner; }

  PrototypeLibrary lib;
  TestRunner runner;
  std::unique_ptr<DetectionBackend> cpu = make_cpu_backend();
  bool fail_detect = false;
};

struct Outcome {
  ResolveResult result;
  Stand stand;
  Contacts first;
};

Outcome run(Stand s, DetectionBackend& backend) {
  ResolveRequest req;
  req.host_levels_below = 0;  // every level through the runner: the calls the tests count and fail
  const Contacts first = backend.detect(s, req.detect);
  ResolveResult r = resolve(s, backend, req, first);
  return {std::move(r), std::move(s), first};
}

void same_turns(const Outcome& a, const Outcome& b) {
  CHECK(a.first.pairs == b.first.pairs);
  CHECK(a.result.contacts_after == b.result.contacts_after);
  CHECK(a.result.organs_moved == b.result.organs_moved);
  REQUIRE(a.stand.transforms.size() == b.stand.transforms.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.stand.transforms.size(); ++k)
    differ += std::memcmp(&a.stand.transforms[k], &b.stand.transforms[k], sizeof(Affine3f)) != 0;
  CHECK(differ == 0);
}

}  // namespace

TEST_CASE("auto backend: the wrapped backend's runner plans the resolution, with its lanes") {
  const Stand s = row_stand(2);
  auto cpu = make_cpu_backend();
  const Outcome host = run(s, *cpu);
  REQUIRE(host.result.contacts_before > 20);
  CHECK(host.result.planning == "host search");
  CHECK(host.result.search == "host");

  auto test = std::make_unique<TestBackend>(3);
  TestBackend& inner = *test;
  auto wrapped = make_auto_backend(std::move(test), make_cpu_backend);
  CHECK(wrapped->name() == "test");
  CHECK(wrapped->device() == "test device");
  const Outcome bulk = run(s, *wrapped);
  CHECK(inner.runner.calls > 0);
  CHECK(bulk.result.planning == "test attempts, 3 lanes");
  CHECK(bulk.result.search == "test");
  CHECK(bulk.result.lanes == 3);
  same_turns(host, bulk);
  CHECK(wrapped->name() == "test");  // no fallback
}

TEST_CASE("auto backend: a failure half-way through the attempts, the same turns on the host") {
  const Stand s = row_stand(4);
  auto cpu = make_cpu_backend();
  const Outcome host = run(s, *cpu);
  auto test = std::make_unique<TestBackend>(2);
  test->runner.fail_at = 3;
  TestRunner& runner = test->runner;
  auto wrapped = make_auto_backend(std::move(test), make_cpu_backend);
  const Outcome bulk = run(s, *wrapped);
  CHECK(runner.calls >= 3);
  same_turns(host, bulk);
  // The round that failed finished with the host's attempts; later rounds, if any, searched on
  // the host with the CPU backend.
  CHECK(bulk.result.planning.starts_with("host attempts, 2 lanes"));
  CHECK(wrapped->name() == "cpu");
  CHECK(wrapped->device().find("the test backend on test device failed: the test device failed") !=
        std::string::npos);
}

TEST_CASE("auto backend: a failure in detection, the CPU backend's contacts and turns") {
  const Stand s = row_stand(1);
  auto cpu = make_cpu_backend();
  const Outcome host = run(s, *cpu);
  auto test = std::make_unique<TestBackend>(2);
  test->fail_detect = true;
  TestRunner& runner = test->runner;
  auto wrapped = make_auto_backend(std::move(test), make_cpu_backend);
  const Outcome after = run(s, *wrapped);
  CHECK(runner.calls == 0);
  CHECK(after.result.planning == host.result.planning);
  same_turns(host, after);
}

TEST_CASE("auto backend: the wrapped runner's statistics reach the result when asked") {
  Stand s = row_stand(2);
  auto test = std::make_unique<TestBackend>(2);
  TestRunner& runner = test->runner;
  auto wrapped = make_auto_backend(std::move(test), make_cpu_backend);
  ResolveRequest req;
  req.statistics = true;
  const Contacts first = wrapped->detect(s, req.detect);
  const ResolveResult r = resolve(s, *wrapped, req, first);
  REQUIRE(r.stats.attempts);
  CHECK(r.stats.attempts->hardware == "test");
  CHECK(r.stats.attempts->calls > 0);
  CHECK(r.stats.attempts->calls == static_cast<std::uint64_t>(runner.calls.load()));
}
