// Arrays read in lanes start on a cache line (geometry/line_aligned.hpp): line-aligned vectors of
// every size, the first-touch allocator's small (heap) and large (mapped) arrays, and the arrays
// the CPU backend reads in lanes once made (a prototype's corners, a tree's OBBs and lanes).
#include "collision/mbvt.hpp"
#include "geometry/first_touch.hpp"
#include "geometry/line_aligned.hpp"
#include "geometry/obb.hpp"
#include "geometry/prototype.hpp"
#include "tests/collision/helpers.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

using namespace canopy;

namespace {
bool on_line(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kCacheLine == 0; }
}  // namespace

TEST_CASE("line-aligned vectors start on a cache line at every size, and after growing") {
  for (std::size_t n : {1u, 3u, 17u, 100u, 4096u, 100000u}) {
    LineAlignedVector<float> v(n, 1.0f);
    CHECK(on_line(v.data()));
    v.resize(3 * n + 5);
    CHECK(on_line(v.data()));
    CHECK(v[0] == 1.0f);
  }
}

TEST_CASE("the first-touch allocator's arrays start on a cache line, small and large") {
  for (std::size_t n : {1u, 5u, 1000u, 20000u, 2000000u}) {  // 64 B to 128 MB of OBBs
    std::vector<Obb, FirstTouchAllocator<Obb>> obbs(n);
    CHECK(on_line(obbs.data()));
  }
}

TEST_CASE("the arrays read in lanes start on a cache line once made") {
  PrototypeLibrary lib;
  CHECK(on_line(lib.get(PrototypeKind::leaflet, 1).corner_lanes.data()));
  CHECK(on_line(lib.get(PrototypeKind::cylinder, 2).corner_lanes.data()));
  const Stand s = test::random_stand(7, 3);
  const Mbvt m = build_mbvt(s, lib, MbvtConfig{});
  CHECK(on_line(m.obbs.data()));
  CHECK(on_line(m.lanes.organs.data.data()));
  CHECK(on_line(m.lanes.clusters.data.data()));
  CHECK(on_line(m.lanes.root_lanes.data.data()));
}
