// Reading a stand folder back (organs.csv + plants.csv, as canopy detect, canopy render and
// Python's Stand.read do): what canopy writes is read; anything else is refused with its place,
// never read as a stand that detection would then index out of bounds or fill with NaN.
#include "geometry/export.hpp"

#include <doctest/doctest.h>

#include <cstring>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace canopy;
namespace fs = std::filesystem;

namespace {

const std::string kPlants =
    "id,x,y,rotation,seed,grammar,steps\n"
    "0,0,0,0,7,tomato.yaml,6\n"
    "1,0.4,0,90,8,tomato.yaml,6\n";
const std::string kOrgansHeader =
    "id,plant,parent,kind,leaf,area,length,prototype,p0,p1,lod,joint_limit,hx,hy,hz,lx,ly,lz,ux,uy,uz,tx,ty,"
    "tz\n";
/// Two plants: an internode carrying a petiole and a leaflet of compound leaf 0; then plant 1's
/// internode and leaflet of its compound leaf, id 1.
const std::vector<std::string> kOrgans{
    "0,0,-1,internode,-1,0.1,0.1,cylinder,0.1,0.01,2,60,0,0,0.1,0,-0.01,0,0.01,0,0,0,0,0",
    "1,0,0,petiole,0,0.1,0.1,cylinder,0.08,0.004,2,60,0.06,0,0.04,0,-0.004,0,0.002,0,-0.003,0,0,0.1",
    "2,0,1,leaflet,0,0.1,0.1,leaflet,0.07,0.04,2,60,0.042,0.056,0,-0.032,0.024,0,0,0,0.02,0.1,0."
    "01,0.15",
    "3,1,-1,internode,-1,0.1,0.1,cylinder,0.1,0.01,2,60,0,0,0.1,0,-0.01,0,0.01,0,0,0,0,0",
    "4,1,3,leaflet,1,0.1,0.1,leaflet,0.07,0.04,2,60,0.042,0.056,0,-0.032,0.024,0,0,0,0.02,0.1,0."
    "01,0.15",
};

std::string organs_with(std::size_t row, std::size_t column, const std::string& cell) {
  std::string out = kOrgansHeader;
  for (std::size_t r = 0; r < kOrgans.size(); ++r) {
    std::string line = kOrgans[r];
    if (r == row) {
      std::size_t b = 0;
      for (std::size_t c = 0; c < column; ++c) b = line.find(',', b) + 1;
      const std::size_t e = line.find(',', b);
      line.replace(b, e == std::string::npos ? std::string::npos : e - b, cell);
    }
    out += line + "\n";
  }
  return out;
}

/// A stand folder holding these two files.
struct Folder {
  std::string dir;
  Folder(const std::string& plants, const std::string& organs) {
    char name[] = "/tmp/canopy-tables-XXXXXX";
    REQUIRE(mkdtemp(name));
    dir = name;
    std::ofstream(dir + "/plants.csv") << plants;
    std::ofstream(dir + "/organs.csv") << organs;
  }
  ~Folder() { fs::remove_all(dir); }
  /// What read_stand throws, with the folder's path left out ("" when it reads).
  std::string error() const {
    try {
      read_stand(dir);
    } catch (const std::exception& e) {
      std::string m = e.what();
      for (std::size_t at; (at = m.find(dir)) != std::string::npos;) m.replace(at, dir.size(), "DIR");
      return m;
    }
    return "";
  }
};

}  // namespace

TEST_CASE("a stand folder as canopy writes it reads back") {
  const Folder f(kPlants, organs_with(99, 0, ""));
  REQUIRE(f.error() == "");
  const Stand s = read_stand(f.dir);
  REQUIRE(s.plant_count() == 2);
  CHECK(s.organ_count() == 5);
  CHECK(s.plants[0].organ_count == 3);
  CHECK(s.plants[0].leaf_count == 1);
  CHECK(s.plants[1].first_organ == 3);
  CHECK(s.plants[1].first_leaf == 1);
  CHECK(s.plants[1].leaf_count == 1);
}

TEST_CASE("tables saved with Windows line ends read back the same") {
  const auto crlf = [](std::string t) {
    for (std::size_t at = 0; (at = t.find('\n', at)) != std::string::npos; at += 2) t.insert(at, "\r");
    return t;
  };
  const Folder unix_ends(kPlants, organs_with(99, 0, "")),
      windows_ends(crlf(kPlants), crlf(organs_with(99, 0, "")));
  REQUIRE(windows_ends.error() == "");
  const Stand a = read_stand(unix_ends.dir), b = read_stand(windows_ends.dir);
  CHECK(a.organ_count() == b.organ_count());
  CHECK(std::memcmp(a.transforms.data(), b.transforms.data(), a.transforms.size() * sizeof(Affine3f)) == 0);
}

TEST_CASE("an empty organs.csv or plants.csv is not a stand of plants without organs") {
  CHECK(Folder(kPlants, "").error() ==
        "DIR/organs.csv:1: expected the header " + kOrgansHeader.substr(0, kOrgansHeader.size() - 1));
  CHECK(Folder("", organs_with(99, 0, "")).error() ==
        "DIR/plants.csv:1: expected the header id,x,y,rotation,seed,grammar,steps");
}

TEST_CASE("a plant farther from the origin than canopy stand places one is refused") {
  const std::string far =
      "id,x,y,rotation,seed,grammar,steps\n0,0,0,0,7,tomato.yaml,6\n1,1e12,0,90,8,tomato.yaml,6\n";
  CHECK(Folder(far, organs_with(99, 0, "")).error() ==
        "DIR/plants.csv:3: the plant at (1e12, 0) lies more than 1e+08 m from the origin, as canopy stand "
        "never "
        "places one");
}

TEST_CASE("numbers that are not finite, or do not fit, are refused with their place") {
  CHECK(Folder(kPlants, organs_with(1, 12, "nan")).error() ==
        "DIR/organs.csv:3: column 13 'nan' is not a finite number");
  CHECK(Folder(kPlants, organs_with(1, 23, "-inf")).error() ==
        "DIR/organs.csv:3: column 24 '-inf' is not a finite number");
  CHECK(Folder(kPlants, organs_with(0, 14, "1e300")).error() ==
        "DIR/organs.csv:2: column 15 '1e300' is out of range");
  CHECK(Folder(kPlants, organs_with(0, 14, "2e6")).error() ==
        "DIR/organs.csv:2: column 15 '2e6' is out of range (at most 1000000 m)");
  CHECK(Folder(kPlants, organs_with(2, 8, "-0.5")).error() ==
        "DIR/organs.csv:4: column 9 '-0.5' is out of range (a size from 0 to 1000000 m)");
  // A sheared frame (canopy's are orthogonal): the bounds detection fits would not hold its mesh.
  CHECK(Folder(kPlants, organs_with(2, 13, "0.06")).error() ==
        "DIR/organs.csv:4: the organ's frame (columns 13-21) is sheared: its axes h and l meet at 88.12 "
        "degrees, "
        "not 90 (canopy turns and scales organs, never shears them; bounds would not hold the mesh)");
  CHECK(Folder(kPlants, organs_with(2, 13, "0.056000001")).error() == "");  // float rounding is no shear
  CHECK(Folder(kPlants, organs_with(2, 11, "200")).error() ==
        "DIR/organs.csv:4: column 12 (joint_limit) must lie in [0, 180], got 200");
  CHECK(Folder(kPlants, organs_with(2, 1, "abc")).error() ==
        "DIR/organs.csv:4: column 2 'abc' is not a valid number");
  CHECK(Folder("id,x,y,rotation,seed,grammar,steps\n0,nan,0,0,7,t.yaml,6\n1,0,0,0,8,t.yaml,6\n",
               organs_with(99, 0, ""))
            .error() == "DIR/plants.csv:2: column 2 'nan' is not a finite number");
}

TEST_CASE("structure that detection would index out of bounds is refused") {
  // A parent before the organs, in another plant, or after the organ itself.
  CHECK(Folder(kPlants, organs_with(1, 2, "-5")).error() ==
        "DIR/organs.csv:3: parent -5 is not an earlier organ of plant 0");
  CHECK(Folder(kPlants, organs_with(4, 2, "0")).error() ==
        "DIR/organs.csv:6: parent 0 is not an earlier organ of plant 1");
  CHECK(Folder(kPlants, organs_with(1, 2, "1")).error() ==
        "DIR/organs.csv:3: parent 1 is not an earlier organ of plant 0");
  // Compound-leaf ids that skip, go below the plant's first, or are negative.
  CHECK(Folder(kPlants, organs_with(4, 4, "2147483647"))
            .error()
            .starts_with("DIR/organs.csv:6: leaf 2147483647 is out of order"));
  CHECK(Folder(kPlants, organs_with(4, 4, "0"))
            .error()
            .starts_with("DIR/organs.csv:6: leaf 0 is out of order"));
  CHECK(Folder(kPlants, organs_with(1, 4, "-2"))
            .error()
            .starts_with("DIR/organs.csv:3: leaf -2 is out of order"));
  CHECK(Folder(kPlants, organs_with(3, 1, "5")).error() ==
        "DIR/organs.csv:5: plant 5 is not in DIR/plants.csv");
  CHECK(Folder(kPlants, organs_with(3, 1, "0")).error() ==
        "DIR/organs.csv:6: parent 3 is not an earlier organ of plant 1");
}

TEST_CASE("a stand folder whose tables are not regular files is refused at once") {
  const Folder f(kPlants, organs_with(99, 0, ""));
  fs::remove(f.dir + "/organs.csv");
  fs::create_symlink("/dev/zero", f.dir + "/organs.csv");
  CHECK(f.error() == "DIR/organs.csv: the organs table is not a regular file (a device, pipe or socket)");
  fs::remove(f.dir + "/organs.csv");
  CHECK(f.error() == "DIR/organs.csv: cannot open (is DIR a canopy stand folder?)");
}
