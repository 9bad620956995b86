// ThreadLimit: OpenMP's default team while it lives, restored after; nothing changed for 0.
#include "geometry/thread_limit.hpp"

#include <doctest/doctest.h>
#include <omp.h>

using namespace canopy;

namespace {

/// The size of the team a parallel region without its own count gets now.
int default_team() {
  int n = 0;
#pragma omp parallel
  {
#pragma omp single
    n = omp_get_num_threads();
  }
  return n;
}

}  // namespace

TEST_CASE("ThreadLimit bounds the default team while it lives") {
  const int before = omp_get_max_threads();
  omp_set_dynamic(0);  // exactly the count asked for, even beyond the cores
  {
    const ThreadLimit limit(1);
    CHECK(omp_get_max_threads() == 1);
    CHECK(default_team() == 1);
    {
      const ThreadLimit inner(3);
      CHECK(default_team() == 3);
    }
    CHECK(default_team() == 1);
    const ThreadLimit none(0);  // no limit asked for: the one in force stays
    CHECK(default_team() == 1);
  }
  CHECK(omp_get_max_threads() == before);
  CHECK(default_team() == before);
}
