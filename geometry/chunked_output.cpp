#include "geometry/chunked_output.hpp"

#include "geometry/organ_mesh.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>

namespace canopy {

ExportScope ExportScope::whole(const Stand& s) {
  ExportScope e{s, {}, {}, {}, {}, 0, 0, nullptr};
  const std::size_t n = s.plant_count();
  e.plants.resize(n);
  e.plant_id.resize(n);
  for (std::size_t p = 0; p < n; ++p)
    e.plants[p] = static_cast<std::uint32_t>(p), e.plant_id[p] = static_cast<std::int64_t>(p);
  e.organ_shift.assign(n, 0);
  e.leaf_shift.assign(n, 0);
  e.plants_total = n;
  e.organs_total = s.organ_count();
  return e;
}

void ExportScope::exclusive(std::vector<std::uint64_t>& values, int k,
                            std::vector<std::uint64_t>& totals) const {
  if (scan) {
    scan->exclusive(values, k, totals);
    return;
  }
  exclusive_sums(values, k, totals);
}

void exclusive_sums(std::vector<std::uint64_t>& values, int k, std::vector<std::uint64_t>& totals) {
  totals.assign(static_cast<std::size_t>(k), 0);
  const std::size_t n = values.size() / static_cast<std::size_t>(k);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < static_cast<std::size_t>(k); ++j) {
      std::uint64_t& v = values[i * static_cast<std::size_t>(k) + j];
      const std::uint64_t own = v;
      v = totals[j];
      totals[j] += own;
    }
}

void ChunkFile::fixed(std::string_view text) {
  out_.write(text);
  offset_ += text.size();
}

void ChunkFile::plants(std::size_t n, std::size_t batch,
                       const std::function<void(std::size_t, std::string&)>& make) {
  std::atomic<std::uint64_t> bytes{0};
  write_ordered(out_, n, batch, [&](std::size_t first, std::size_t last, std::string& buf) {
    for (std::size_t i = first; i < last; ++i) make(i, buf);
    bytes += buf.size();
  });
  offset_ += bytes.load();
}

void ChunkFile::patch(std::uint64_t at, std::string_view bytes) {
  std::FILE* f = out_.get();
  std::fflush(f);
  if (fseeko(f, static_cast<off_t>(at), SEEK_SET) != 0 ||
      std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || fseeko(f, 0, SEEK_END) != 0)
    throw std::runtime_error(
        fmt::format("{}: cannot rewrite {} bytes at offset {}", out_.path(), bytes.size(), at));
}

}  // namespace canopy
