#pragma once
/// The benchmark programs' answer to an argument none of their options took (tools/bench_*): --help
/// or -h prints the usage on stdout, exit status 0; anything else (an unknown option, or an option
/// missing its value) is named on stderr above the usage, exit status 2. Called while the
/// arguments are read, before anything is run or written, so a mistyped command leaves earlier
/// results as they were.
#include <cstdio>
#include <cstring>
#include <string>

namespace canopy {

/// The exit status for `main` to return. With `print` false (an MPI rank other than the first)
/// nothing is printed.
inline int help_or_refuse(const char* program, const char* arg, const std::string& usage, bool print = true) {
  const bool help = !std::strcmp(arg, "--help") || !std::strcmp(arg, "-h");
  if (print) {
    if (!help) std::fprintf(stderr, "%s: unknown option or missing value: %s\n", program, arg);
    std::fputs(usage.c_str(), help ? stdout : stderr);
  }
  return help ? 0 : 2;
}

}  // namespace canopy
