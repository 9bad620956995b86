// ThreadLimit: OpenMP's default team while it lives, restored after; nothing changed for 0.
#include "geometry/thread_limit.hpp"

#include <doctest/doctest.h>
#include <omp.h>

#include <stdexcept>

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

TEST_CASE("thread counts past canopy's maximum are refused, not handed to libgomp") {
  // libgomp keeps a team's bookkeeping on the caller's stack: 100,000 threads crashed it.
  CHECK(max_threads() >= 1024);
  CHECK_THROWS_WITH_AS(ThreadLimit(100000), doctest::Contains("the thread count 100000 is more than the"),
                       std::invalid_argument);
  CHECK_THROWS_AS(ThreadLimit(-1), std::invalid_argument);
  CHECK(checked_threads(max_threads()) == max_threads());
  // OMP_NUM_THREADS sets the default team as this does; with no count given it is the one used.
  const int before = omp_get_max_threads();
  omp_set_num_threads(100000);
  CHECK_THROWS_WITH_AS(ThreadLimit(0), doctest::Contains("OMP_NUM_THREADS asks for 100000 threads"),
                       std::invalid_argument);
  {
    const ThreadLimit given(2);  // a count given wins over the default
    CHECK(omp_get_max_threads() == 2);
  }
  omp_set_num_threads(before);
}
