// Staged host-to-device copies: every byte arrives, whether the copies are waited for at once,
// overlapped with other host work, or abandoned and dropped.
#include "cuda/device_buffer.hpp"
#include "cuda/pinned_upload.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <numeric>
#include <vector>

using namespace canopy::cuda;

namespace {

std::vector<std::uint32_t> counting(std::size_t n, std::uint32_t from) {
  std::vector<std::uint32_t> v(n);
  std::iota(v.begin(), v.end(), from);
  return v;
}

}  // namespace

TEST_CASE("a staged load copies every byte, started and waited for apart") {
  // Three arrays over kStagedFrom in all, of sizes that are no multiple of the block or of the
  // workers' shares.
  const std::size_t words = PinnedUpload::kStagedFrom / 4 / 2 + 12345;
  const auto a = counting(words, 7), b = counting(words + 3, 1u << 30), c = counting(1001, 99);
  PinnedUpload up;
  DeviceBuffer<std::uint32_t> da, db, dc;
  da.upload(a, up), db.upload(b, up), dc.upload(c, up);
  up.start();
  // The host's other work meanwhile (the tree's shape, in the backend).
  const std::uint64_t sum = std::accumulate(a.begin(), a.end(), std::uint64_t{0});
  up.wait();
  CHECK(sum > 0);
  CHECK(da.download(a.size()) == a);
  CHECK(db.download(b.size()) == b);
  CHECK(dc.download(c.size()) == c);
  // Again through the same blocks, with finish().
  const auto d = counting(words * 2, 5);
  DeviceBuffer<std::uint32_t> dd;
  dd.upload(d, up);
  up.finish();
  CHECK(dd.download(d.size()) == d);
}

TEST_CASE("a small load is copied by start() itself; a dropped load leaves the stager reusable") {
  PinnedUpload up;
  up.reserve();
  const auto small = counting(1000, 3);
  DeviceBuffer<std::uint32_t> ds;
  ds.upload(small, up);
  up.start();
  CHECK(ds.download(small.size()) == small);  // already there
  up.wait();
  const auto big = counting(PinnedUpload::kStagedFrom / 4 + 1, 11);
  DeviceBuffer<std::uint32_t> db;
  db.upload(big, up);
  up.start();
  up.drop();  // an exception between start() and wait(): the copies end, nothing is kept
  db.upload(big, up);
  up.finish();
  CHECK(db.download(big.size()) == big);
}

TEST_CASE("blocks reserved in the background serve the first large load, or go unused") {
  {
    PinnedUpload unused;
    unused.reserve_in_background();  // a small stand's backend: never waited for, joined at the end
  }
  PinnedUpload up;
  up.reserve_in_background();
  up.reserve_in_background();  // once
  const auto big = counting(PinnedUpload::kStagedFrom / 4 + 77, 21);
  DeviceBuffer<std::uint32_t> db;
  db.upload(big, up);
  up.finish();
  CHECK(db.download(big.size()) == big);
}
