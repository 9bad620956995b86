// memory_available: the room a process may still take, under the machine's memory, its control
// group's limit and its address-space limit, whichever is smallest.
#include "geometry/available_memory.hpp"

#include <doctest/doctest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace canopy;

TEST_CASE("the address-space limit bounds the memory available") {
  const std::size_t machine = memory_available();
  REQUIRE(machine > 0);  // Linux: MemAvailable is there
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  REQUIRE(static_cast<bool>(statm >> pages));
  const std::uint64_t size = pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  // In a child (the limit stays with it): the size now and 256 MiB more.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    const rlimit r{size + (std::uint64_t{256} << 20), RLIM_INFINITY};
    if (::setrlimit(RLIMIT_AS, &r) != 0) ::_exit(2);
    const std::size_t room = memory_available();
    // The room left under the limit (the child's size is the parent's, give or take a few pages).
    ::_exit(room > (std::uint64_t{200} << 20) && room <= (std::uint64_t{256} << 20) ? 0 : 1);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  // No limit of its own: the machine's (or its group's) room, a few pages aside.
  CHECK(memory_available() <= machine + (std::uint64_t{64} << 20));
}
