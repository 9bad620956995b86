// organs.csv and plants.csv, and reading a stand back from them.
#include "geometry/export.hpp"
#include "geometry/atomic_file.hpp"
#include "geometry/organ_mesh.hpp"
#include "geometry/text_out.hpp"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace canopy {
namespace {

constexpr const char* kOrganHeader =
    "id,plant,parent,kind,leaf,area,length,prototype,p0,p1,lod,joint_limit,"
    "hx,hy,hz,lx,ly,lz,ux,uy,uz,tx,ty,tz\n";
constexpr const char* kPlantHeader = "id,x,y,rotation,seed,grammar,steps\n";

/// Splits a CSV line without quoting (canopy never writes commas inside cells).
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
  if (cell.empty() || r.ec != std::errc() || r.ptr != cell.data() + cell.size())
    throw std::runtime_error(fmt::format("{}:{}: column {} '{}' is not a valid number", file, line, column, cell));
  return v;
}

}  // namespace

void write_organs_csv(const ExportScope& e, PrototypeLibrary& lib, ChunkWriter& out) {
  const Stand& s = e.stand;
  out.fixed(kOrganHeader);
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
    t += fmt::format(",{},{},{}\n", pr.seed, s.grammars[static_cast<std::size_t>(pr.grammar)], pr.steps);
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
  std::ifstream pin(pfile), oin(ofile);
  if (!pin) throw std::runtime_error(fmt::format("{}: cannot open (is {} a canopy stand folder?)", pfile, dir));
  if (!oin) throw std::runtime_error(fmt::format("{}: cannot open (is {} a canopy stand folder?)", ofile, dir));
  std::string line;
  std::map<std::string, int> grammar_index;
  int ln = 0;
  while (std::getline(pin, line)) {
    if (++ln == 1) {
      if (line + "\n" != kPlantHeader) throw std::runtime_error(fmt::format("{}:1: expected the header {}", pfile, kPlantHeader));
      continue;
    }
    const auto c = cells(line);
    if (c.size() != 7) throw std::runtime_error(fmt::format("{}:{}: expected 7 cells, got {}", pfile, ln, c.size()));
    PlantRecord pr;
    if (parse<std::size_t>(c[0], pfile, ln, 1) != s.plants.size())
      throw std::runtime_error(fmt::format("{}:{}: plant ids must run 0, 1, 2, ...", pfile, ln));
    pr.x = parse<double>(c[1], pfile, ln, 2);
    pr.y = parse<double>(c[2], pfile, ln, 3);
    pr.rotation_deg = parse<double>(c[3], pfile, ln, 4);
    pr.seed = parse<std::uint64_t>(c[4], pfile, ln, 5);
    const std::string g(c[5]);
    auto it = grammar_index.find(g);
    if (it == grammar_index.end()) {
      it = grammar_index.emplace(g, static_cast<int>(s.grammars.size())).first;
      s.grammars.push_back(g);
    }
    pr.grammar = it->second;
    pr.steps = parse<int>(c[6], pfile, ln, 7);
    s.plants.push_back(pr);
  }
  ln = 0;
  while (std::getline(oin, line)) {
    if (++ln == 1) {
      if (line + "\n" != kOrganHeader) throw std::runtime_error(fmt::format("{}:1: expected the header {}", ofile, kOrganHeader));
      continue;
    }
    const auto c = cells(line);
    if (c.size() != 24) throw std::runtime_error(fmt::format("{}:{}: expected 24 cells, got {}", ofile, ln, c.size()));
    const std::size_t id = parse<std::size_t>(c[0], ofile, ln, 1);
    if (id != s.organs.size()) throw std::runtime_error(fmt::format("{}:{}: organ ids must run 0, 1, 2, ...", ofile, ln));
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
    r.lod = static_cast<std::uint8_t>(parse<int>(c[10], ofile, ln, 11));
    if (r.lod < 1 || r.lod > kMaxLod) throw std::runtime_error(fmt::format("{}:{}: lod must lie in 1..{}", ofile, ln, kMaxLod));
    if (r.plant < 0 || static_cast<std::size_t>(r.plant) >= s.plants.size() || r.parent >= static_cast<std::int32_t>(id))
      throw std::runtime_error(fmt::format("{}:{}: plant or parent out of range", ofile, ln));
    s.params.push_back({parse<float>(c[8], ofile, ln, 9), parse<float>(c[9], ofile, ln, 10)});
    s.joint_limit_deg.push_back(parse<float>(c[11], ofile, ln, 12));
    float v[12];
    for (int k = 0; k < 12; ++k) v[k] = parse<float>(c[static_cast<std::size_t>(12 + k)], ofile, ln, 13 + k);
    s.transforms.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, {v[9], v[10], v[11]}});
    s.organs.push_back(r);
  }
  // Organ ranges and leaf ranges per plant, from the organs' plant and leaf columns.
  std::int32_t prev = -1;
  for (std::size_t id = 0; id < s.organs.size(); ++id) {
    const OrganRecord& r = s.organs[id];
    if (r.plant < prev) throw std::runtime_error(fmt::format("{}: organs must be grouped plant by plant", ofile));
    PlantRecord& pr = s.plants[static_cast<std::size_t>(r.plant)];
    if (r.plant != prev) pr.first_organ = static_cast<std::uint32_t>(id);
    ++pr.organ_count;
    prev = r.plant;
  }
  std::uint32_t next_leaf = 0;
  for (PlantRecord& pr : s.plants) {
    std::int32_t hi = -1;
    for (std::uint32_t id = pr.first_organ; id < pr.first_organ + pr.organ_count; ++id) hi = std::max(hi, s.organs[id].leaf);
    pr.first_leaf = next_leaf;
    pr.leaf_count = hi < 0 ? 0 : static_cast<std::uint32_t>(hi + 1) - next_leaf;
    next_leaf += pr.leaf_count;
  }
  if (!s.plants.empty()) s.stand_origin = {s.plants[0].x, s.plants[0].y, 0};
  return s;
}

}  // namespace canopy
