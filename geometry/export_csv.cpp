// organs.csv and plants.csv, and reading a stand back from them.
#include "geometry/export.hpp"

#include "geometry/csv_field.hpp"
#include "geometry/atomic_file.hpp"
#include "geometry/input_file.hpp"
#include "geometry/layout.hpp"
#include "geometry/organ_extent.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/staged_folder.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

namespace canopy {
namespace {

constexpr const char* kOrganHeader =
    "id,plant,parent,kind,leaf,area,length,prototype,p0,p1,lod,joint_limit,"
    "hx,hy,hz,lx,ly,lz,ux,uy,uz,tx,ty,tz\n";
/// A stand with a curved leaflet has three more columns, its angles (geometry/leaflet_shape.hpp;
/// 0 for every other organ); a stand without one keeps the columns above, byte for byte.
constexpr const char* kShapeColumns = ",bend,cup,fold";
/// The cosine between two axes of an organ's frame above which organs.csv is refused as sheared.
constexpr double kMaxFrameShear = 1e-4;
constexpr const char* kPlantHeader = "id,x,y,rotation,seed,grammar,steps\n";

/// A header as a message quotes it, on the message's one line.
std::string_view without_newline(std::string_view header) { return header.substr(0, header.size() - 1); }

/// The next row of a table canopy wrote: blank lines at its end (an editor's) end it, and a blank
/// line with rows after it is refused by line.
bool next_row(InputFile& in, std::string& line) {
  if (!in.next_line(line)) return false;
  if (!line.empty()) return true;
  const int blank = in.line_number();
  std::string rest;
  while (in.next_line(rest))
    if (!rest.empty())
      throw std::runtime_error(
          fmt::format("{}:{}: a blank line inside the table (rows follow on line {})", in.path(), blank,
                      in.line_number()));
  return false;
}

/// Splits an organs.csv line: its cells are numbers and names, never quoted (plants.csv, whose
/// grammar cell is free text, goes through split_csv).
std::vector<std::string_view> cells(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i)
    if (i == line.size() || line[i] == ',') {
      out.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  return out;
}

template <typename T>
T parse(std::string_view cell, const std::string& file, int line, int column) {
  T v{};
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  const bool whole_cell = !cell.empty() && r.ptr == cell.data() + cell.size();
  if (whole_cell && r.ec == std::errc::result_out_of_range)
    throw std::runtime_error(fmt::format("{}:{}: column {} '{}' is out of range", file, line, column, cell));
  if (!whole_cell || r.ec != std::errc())
    throw std::runtime_error(
        fmt::format("{}:{}: column {} '{}' is not a valid number", file, line, column, cell));
  return v;
}

/// `v` when finite (from_chars reads "nan" and "inf" as numbers).
template <typename T>
T finite(T v, std::string_view cell, const std::string& file, int line, int column) {
  if (!std::isfinite(v))
    throw std::runtime_error(
        fmt::format("{}:{}: column {} '{}' is not a finite number", file, line, column, cell));
  return v;
}

/// A prototype parameter: finite, not negative, at most kMaxOrganExtent.
float size(float v, std::string_view cell, const std::string& file, int line, int column) {
  finite(v, cell, file, line, column);
  if (!(v >= 0 && v <= kMaxOrganExtent))
    throw std::runtime_error(fmt::format("{}:{}: column {} '{}' is out of range (a size from 0 to {} m)",
                                         file, line, column, cell, kMaxOrganExtent));
  return v;
}

}  // namespace

void write_organs_csv(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& out) {
  const Stand& s = e.stand;
  // Whether any process writes a curved leaflet (the same answer on every process).
  std::vector<std::uint64_t> curved(e.plants.size(), 0), totals;
  for (std::size_t i = 0; i < e.plants.size(); ++i) {
    const PlantRecord& pr = s.plants[e.plants[i]];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id)
      curved[i] += s.organs[id].shape != 0;
  }
  e.exclusive(curved, 1, totals);
  const bool shapes = totals[0] > 0;
  const std::string_view header(kOrganHeader);
  out.fixed(shapes ? std::string(header.substr(0, header.size() - 1)) + kShapeColumns + "\n"
                   : std::string(header));
  make_meshes(s, lib);
  out.plants(e.plants.size(), 16, [&](std::size_t i, std::string& t) {
    const PlantRecord& pr = s.plants[e.plants[i]];
    // Each row made in a buffer of its own and appended once (no check of the string's room for
    // each of its 24 cells): at most 6 integers, 2 names, 2 doubles and 15 floats of 24 characters.
    char row[1024];
    for (std::size_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) {
      const OrganRecord& r = s.organs[id];
      char* p = row;
      p = put_number(p, e.organ(static_cast<std::int64_t>(id)));
      *p++ = ',';
      p = put_number(p, e.plant(static_cast<std::size_t>(r.plant)));
      *p++ = ',';
      p = put_number(p, e.organ(r.parent));
      *p++ = ',';
      p = put_text(p, name_of(r.kind));
      *p++ = ',';
      p = put_number(p, e.leaf_of(id));
      *p++ = ',';
      p = put_number(p, organ_area(s, id, lib));
      *p++ = ',';
      p = put_number(p, organ_length(s, id));
      *p++ = ',';
      p = put_text(p, name_of(r.prototype));
      *p++ = ',';
      p = put_number(p, s.params[id][0]);
      *p++ = ',';
      p = put_number(p, s.params[id][1]);
      *p++ = ',';
      p = put_number(p, static_cast<int>(r.lod));
      *p++ = ',';
      p = put_number(p, s.joint_limit_deg[id]);
      const Affine3f& m = s.transforms[id];
      for (const Vec3f& c : {m.c0, m.c1, m.c2, m.t}) {
        *p++ = ',';
        p = put_number(p, c.x);
        *p++ = ',';
        p = put_number(p, c.y);
        *p++ = ',';
        p = put_number(p, c.z);
      }
      if (shapes) {
        const LeafletShape shape = leaflet_shape(r.shape);
        for (double a : {shape.bend_deg, shape.cup_deg, shape.fold_deg}) {
          *p++ = ',';
          p = put_number(p, a);
        }
      }
      *p++ = '\n';
      t.append(row, p);
    }
  });
}

void write_plants_csv(const ExportScope& e, ChunkWriter& out) {
  const Stand& s = e.stand;
  out.fixed(kPlantHeader);
  out.plants(e.plants.size(), 256, [&](std::size_t i, std::string& t) {
    const PlantRecord& pr = s.plants[e.plants[i]];
    append_number(t, e.plant(e.plants[i]));
    t += ',';
    append_number(t, pr.x);
    t += ',';
    append_number(t, pr.y);
    t += ',';
    append_number(t, pr.rotation_deg);
    // The grammar's path, the table's one free-text cell, quoted where it holds a comma or a quote (a
    // path with a line break is refused before a stand is grown, lsystem/grow.cpp).
    t += fmt::format(",{},{},{}\n", pr.seed, csv_field(s.grammars[static_cast<std::size_t>(pr.grammar)]),
                     pr.steps);
  });
}

void write_organs_csv(const Stand& s, PrototypeLibrary& lib, AtomicFile& out) {
  ChunkFile f(out);
  write_organs_csv(ExportScope::whole(s), lib, f);
}

void write_plants_csv(const Stand& s, AtomicFile& out) {
  ChunkFile f(out);
  write_plants_csv(ExportScope::whole(s), f);
}

Stand read_stand(const std::string& dir) {
  Stand s;
  const std::string pfile = (std::filesystem::path(dir) / "plants.csv").string();
  const std::string ofile = (std::filesystem::path(dir) / "organs.csv").string();
  auto open = [&](const std::string& file, const char* what, std::uint64_t limit) {
    try {
      return std::make_unique<InputFile>(file, what, limit);
    } catch (const FileNotFound&) {
      throw std::runtime_error(fmt::format("{}: cannot open (is {} a canopy stand folder?)", file, dir));
    }
  };
  std::unique_ptr<InputFile> pin, oin;
  open_in_one_set(dir, {pfile, ofile}, [&] {  // never plants of one run and organs of another
    pin = open(pfile, "plants table", kMaxPlantsCsvBytes);
    oin = open(ofile, "organs table", kMaxOrgansCsvBytes);
  });
  std::string line;
  std::map<std::string, int> grammar_index;
  // A spreadsheet that saved a table as "CSV UTF-8" put a byte-order mark before the header (a
  // positions file takes it too): not part of the header.
  const auto header = [](InputFile& in, std::string& l) {
    if (!in.next_line(l)) return false;
    if (l.starts_with("\xEF\xBB\xBF")) l.erase(0, 3);
    return true;
  };
  if (!header(*pin, line) || line + "\n" != kPlantHeader)
    throw std::runtime_error(
        fmt::format("{}:1: expected the header {}", pfile, without_newline(kPlantHeader)));
  std::vector<std::string> c;
  while (next_row(*pin, line)) {
    const int ln = pin->line_number();
    if (!split_csv(line, c))
      throw std::runtime_error(fmt::format("{}:{}: a quoted cell is not closed", pfile, ln));
    if (c.size() != 7)
      throw std::runtime_error(fmt::format("{}:{}: expected 7 cells, got {}", pfile, ln, c.size()));
    PlantRecord pr;
    if (parse<std::size_t>(c[0], pfile, ln, 1) != s.plants.size())
      throw std::runtime_error(fmt::format("{}:{}: plant ids must run 0, 1, 2, ...", pfile, ln));
    pr.x = finite(parse<double>(c[1], pfile, ln, 2), c[1], pfile, ln, 2);
    pr.y = finite(parse<double>(c[2], pfile, ln, 3), c[2], pfile, ln, 3);
    if (std::abs(pr.x) > kMaxPlantCoordinate || std::abs(pr.y) > kMaxPlantCoordinate)
      throw std::runtime_error(
          fmt::format("{}:{}: the plant at ({}, {}) lies more than {:g} m from the origin, "
                      "as canopy stand never places one",
                      pfile, ln, c[1], c[2], kMaxPlantCoordinate));
    pr.rotation_deg = finite(parse<double>(c[3], pfile, ln, 4), c[3], pfile, ln, 4);
    pr.seed = parse<std::uint64_t>(c[4], pfile, ln, 5);
    const std::string g(c[5]);
    auto it = grammar_index.find(g);
    if (it == grammar_index.end()) {
      it = grammar_index.emplace(g, static_cast<int>(s.grammars.size())).first;
      s.grammars.push_back(g);
    }
    pr.grammar = it->second;
    pr.steps = parse<int>(c[6], pfile, ln, 7);
    if (pr.steps < 0 || pr.steps > kMaxSteps)
      throw std::runtime_error(
          fmt::format("{}:{}: column 7 (steps) must lie in 0..{}, got {}", pfile, ln, kMaxSteps, pr.steps));
    s.plants.push_back(pr);
  }
  const std::string_view plain(kOrganHeader);
  const std::string with_shapes = std::string(plain.substr(0, plain.size() - 1)) + kShapeColumns + "\n";
  std::size_t columns = 24;
  if (!header(*oin, line))
    throw std::runtime_error(
        fmt::format("{}:1: expected the header {}", ofile, without_newline(kOrganHeader)));
  if (line + "\n" == with_shapes) columns = 27;
  else if (line + "\n" != plain)
    throw std::runtime_error(
        fmt::format("{}:1: expected the header {}", ofile, without_newline(kOrganHeader)));
  // Organs come plant by plant; within a plant a compound leaf takes the next id when its first
  // organ appears (as the turtle numbers them), so the plants' leaf ranges follow each other.
  std::int32_t plant = -1;
  std::uint32_t next_leaf = 0;
  while (next_row(*oin, line)) {
    const int ln = oin->line_number();
    const auto c = cells(line);
    if (c.size() != columns)
      throw std::runtime_error(fmt::format("{}:{}: expected {} cells, got {}", ofile, ln, columns, c.size()));
    const std::size_t id = parse<std::size_t>(c[0], ofile, ln, 1);
    if (id != s.organs.size())
      throw std::runtime_error(fmt::format("{}:{}: organ ids must run 0, 1, 2, ...", ofile, ln));
    if (id >= static_cast<std::size_t>(INT32_MAX))
      throw std::runtime_error(fmt::format("{}:{}: too many organs", ofile, ln));
    OrganRecord r;
    r.plant = parse<std::int32_t>(c[1], ofile, ln, 2);
    r.parent = parse<std::int32_t>(c[2], ofile, ln, 3);
    const auto kind = parse_organ_kind(c[3]);
    if (!kind) throw std::runtime_error(fmt::format("{}:{}: unknown organ kind '{}'", ofile, ln, c[3]));
    r.kind = *kind;
    r.leaf = parse<std::int32_t>(c[4], ofile, ln, 5);
    const auto proto = parse_prototype(c[7]);
    if (!proto) throw std::runtime_error(fmt::format("{}:{}: unknown prototype '{}'", ofile, ln, c[7]));
    r.prototype = *proto;
    const int lod = parse<int>(c[10], ofile, ln, 11);
    if (lod < 1 || lod > kMaxLod)
      throw std::runtime_error(fmt::format("{}:{}: lod must lie in 1..{}", ofile, ln, kMaxLod));
    r.lod = static_cast<std::uint8_t>(lod);
    if (columns == 27) {
      const LeafletShape shape{parse<double>(c[24], ofile, ln, 25), parse<double>(c[25], ofile, ln, 26),
                               parse<double>(c[26], ofile, ln, 27)};
      std::string why;
      const auto code = leaflet_shape_code(shape, &why);
      if (!code) throw std::runtime_error(fmt::format("{}:{}: {}", ofile, ln, why));
      if (*code != 0 && r.prototype != PrototypeKind::leaflet)
        throw std::runtime_error(
            fmt::format("{}:{}: a {} has no bend, cup or fold (only leaflets curve)", ofile, ln, c[7]));
      r.shape = *code;
    }
    if (r.plant < 0 || static_cast<std::size_t>(r.plant) >= s.plants.size())
      throw std::runtime_error(fmt::format("{}:{}: plant {} is not in {}", ofile, ln, r.plant, pfile));
    if (r.plant < plant)
      throw std::runtime_error(fmt::format("{}: organs must be grouped plant by plant", ofile));
    PlantRecord& pr = s.plants[static_cast<std::size_t>(r.plant)];
    if (r.plant != plant) {
      pr.first_organ = static_cast<std::uint32_t>(id);
      pr.first_leaf = next_leaf;
      plant = r.plant;
    }
    ++pr.organ_count;
    // A parent is an earlier organ of the same plant.
    if (r.parent < -1 || r.parent >= static_cast<std::int32_t>(id) ||
        (r.parent >= 0 && r.parent < static_cast<std::int32_t>(pr.first_organ)))
      throw std::runtime_error(
          fmt::format("{}:{}: parent {} is not an earlier organ of plant {}", ofile, ln, r.parent, r.plant));
    if (r.leaf < -1 || (r.leaf >= 0 && (static_cast<std::uint32_t>(r.leaf) < pr.first_leaf ||
                                        static_cast<std::uint32_t>(r.leaf) > pr.first_leaf + pr.leaf_count)))
      throw std::runtime_error(fmt::format(
          "{}:{}: leaf {} is out of order (plant {}'s compound leaves are numbered from {} as they "
          "first appear)",
          ofile, ln, r.leaf, r.plant, pr.first_leaf));
    if (r.leaf >= 0 && static_cast<std::uint32_t>(r.leaf) == pr.first_leaf + pr.leaf_count)
      ++pr.leaf_count, ++next_leaf;
    // area and length: computed again where used, but a table of NaN or negative ones is not a
    // stand canopy wrote (every number finite, as the limits say).
    for (const int k : {5, 6})
      if (!(finite(parse<double>(c[k], ofile, ln, k + 1), c[k], ofile, ln, k + 1) >= 0))
        throw std::runtime_error(
            fmt::format("{}:{}: column {} '{}' must not be negative", ofile, ln, k + 1, c[k]));
    const float p0 = size(parse<float>(c[8], ofile, ln, 9), c[8], ofile, ln, 9);
    const float p1 = size(parse<float>(c[9], ofile, ln, 10), c[9], ofile, ln, 10);
    s.params.push_back({p0, p1});
    const float joint = finite(parse<float>(c[11], ofile, ln, 12), c[11], ofile, ln, 12);
    if (!(joint >= 0 && joint <= 180))
      throw std::runtime_error(
          fmt::format("{}:{}: column 12 (joint_limit) must lie in [0, 180], got {}", ofile, ln, c[11]));
    s.joint_limit_deg.push_back(joint);
    float v[12];
    for (int k = 0; k < 12; ++k) {
      const auto cell = c[static_cast<std::size_t>(12 + k)];
      v[k] = finite(parse<float>(cell, ofile, ln, 13 + k), cell, ofile, ln, 13 + k);
      if (!(std::fabs(v[k]) <= kMaxOrganExtent))
        throw std::runtime_error(fmt::format("{}:{}: column {} '{}' is out of range (at most {} m)", ofile,
                                             ln, 13 + k, cell, kMaxOrganExtent));
    }
    // An organ's frame is turned and scaled, never sheared (canopy writes its axes orthogonal to
    // 1.5e-7 of their lengths): the bounds detection fits to a frame hold its mesh only then.
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        double dot = 0, ni = 0, nj = 0;
        for (int k = 0; k < 3; ++k)
          dot += double{v[3 * i + k]} * v[3 * j + k], ni += double{v[3 * i + k]} * v[3 * i + k],
              nj += double{v[3 * j + k]} * v[3 * j + k];
        if (std::fabs(dot) > kMaxFrameShear * std::sqrt(ni * nj))
          throw std::runtime_error(fmt::format(
              "{}:{}: the organ's frame (columns 13-21) is sheared: its axes {} and {} meet at {:.4g} "
              "degrees, "
              "not 90 (canopy turns and scales organs, never shears them; bounds would not hold the mesh)",
              ofile, ln, "hlu"[i], "hlu"[j],
              std::acos(std::clamp(dot / std::sqrt(ni * nj), -1.0, 1.0)) * 180 / M_PI));
      }
    s.transforms.push_back(
        {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, {v[9], v[10], v[11]}});
    s.organs.push_back(r);
  }
  // A plant without organs has its (empty) leaf range where the next plant's begins.
  std::uint32_t leaf = 0;
  for (PlantRecord& pr : s.plants) {
    if (pr.organ_count == 0) pr.first_leaf = leaf;
    leaf = pr.first_leaf + pr.leaf_count;
  }
  if (!s.plants.empty()) s.stand_origin = {s.plants[0].x, s.plants[0].y, 0};
  return s;
}

}  // namespace canopy
