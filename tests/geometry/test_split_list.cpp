// The comma-separated lists of the command line and the benchmarks (geometry/split_list.hpp).
#include "geometry/split_list.hpp"

#include <doctest/doctest.h>

using canopy::split_list;
using List = std::vector<std::string>;

TEST_CASE("split_list: every item as written, empty ones included") {
  CHECK(split_list("glb,obj,ply") == List{"glb", "obj", "ply"});
  CHECK(split_list("leaflet") == List{"leaflet"});
  CHECK(split_list("") == List{""});
  CHECK(split_list(",a,,b,") == List{"", "a", "", "b", ""});
  CHECK(split_list(" a , b") == List{" a ", " b"});
  CHECK(split_list("1;2", ';') == List{"1", "2"});
}
