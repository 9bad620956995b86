#include "geometry/thread_limit.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace canopy {

namespace {

/// Whether OMP_NUM_THREADS, when set, is what OpenMP reads as a thread count: whole numbers of at
/// least 1, one per nesting level, separated by commas, with blanks around them. libgomp only warns
/// about anything else and runs on every core, which a user who set it did not ask for.
bool omp_num_threads_readable(const char* v) {
  const std::string_view s(v);
  std::size_t i = 0;
  if (s.find_first_not_of(" \t\n\v\f\r") == std::string_view::npos) return true;  // set but blank: unset
  const auto blanks = [&] {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  };
  for (;;) {
    blanks();
    const std::size_t digits = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    if (i == digits || s.find_first_not_of('0', digits) >= i) return false;  // no number, or 0
    blanks();
    if (i == s.size()) return true;
    if (s[i++] != ',') return false;
  }
}

}  // namespace

int max_threads() { return std::max(1024, omp_get_num_procs()); }

int checked_threads(int threads) {
  if (threads < 0)
    throw std::invalid_argument(
        fmt::format("the thread count must be at least 0 (0: all cores; got {})", threads));
  const int most = max_threads();
  if (threads > most)
    throw std::invalid_argument(
        fmt::format("the thread count {} is more than the {} canopy runs at most", threads, most));
  if (threads > 0) return threads;
  if (const char* v = std::getenv("OMP_NUM_THREADS"); v && !omp_num_threads_readable(v))
    throw std::invalid_argument(
        fmt::format("OMP_NUM_THREADS='{}' is not a thread count (a whole number from 1, or a comma-separated "
                    "list of them); set it right, unset it or give a thread count",
                    v));
  const int fallback = omp_get_max_threads();
  if (fallback > most)
    throw std::invalid_argument(
        fmt::format("OMP_NUM_THREADS asks for {} threads, more than the {} canopy runs at most; set it lower "
                    "or give a thread count",
                    fallback, most));
  return fallback;
}

ThreadLimit::ThreadLimit(int threads) : before_(omp_get_max_threads()), set_(threads > 0) {
  checked_threads(threads);
  if (set_) omp_set_num_threads(threads);
}

ThreadLimit::~ThreadLimit() {
  if (set_) omp_set_num_threads(before_);
}

}  // namespace canopy
