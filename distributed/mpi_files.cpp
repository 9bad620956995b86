#include "distributed/mpi_files.hpp"

#include "distributed/mpi_comm.hpp"
#include "geometry/first_exception.hpp"
#include "geometry/run_files.hpp"

#include <fmt/format.h>
#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <exception>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace canopy::mpi {
namespace {

/// Every rank's (id, k values) pairs laid out by global id: the whole stand's table.
std::vector<std::uint64_t> by_global_id(const std::vector<std::int64_t>& ids,
                                        const std::vector<std::uint64_t>& values, int k,
                                        std::uint64_t plants_total) {
  std::vector<std::uint64_t> rows;
  rows.reserve(ids.size() * static_cast<std::size_t>(k + 1));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    rows.push_back(static_cast<std::uint64_t>(ids[i]));
    for (int j = 0; j < k; ++j)
      rows.push_back(values[i * static_cast<std::size_t>(k) + static_cast<std::size_t>(j)]);
  }
  const std::vector<std::uint64_t> all = allgather(rows);
  std::vector<std::uint64_t> table(plants_total * static_cast<std::uint64_t>(k), 0);
  for (std::size_t r = 0; r < all.size(); r += static_cast<std::size_t>(k + 1))
    for (int j = 0; j < k; ++j)
      table[all[r] * static_cast<std::uint64_t>(k) + static_cast<std::uint64_t>(j)] =
          all[r + 1 + static_cast<std::size_t>(j)];
  return table;
}

}  // namespace

void RankScan::exclusive(std::vector<std::uint64_t>& values, int k,
                         std::vector<std::uint64_t>& totals) const {
  std::vector<std::uint64_t> table = by_global_id(ids_, values, k, total_);
  exclusive_sums(table, k, totals);
  for (std::size_t i = 0; i < ids_.size(); ++i)
    for (std::size_t j = 0; j < static_cast<std::size_t>(k); ++j)
      values[i * static_cast<std::size_t>(k) + j] =
          table[static_cast<std::size_t>(ids_[i]) * static_cast<std::size_t>(k) + j];
}

SharedFile::SharedFile(const std::string& path, const std::vector<std::int64_t>& ids,
                       std::uint64_t plants_total)
    : path_(path), ids_(ids), plants_total_(plants_total) {
  MPI_File fh;
  const int rc =
      MPI_File_open(MPI_COMM_WORLD, path_.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
  if (rc != MPI_SUCCESS)
    throw std::runtime_error(fmt::format("cannot write {} (MPI_File_open failed)", path_));
  if (MPI_File_set_size(fh, 0) != MPI_SUCCESS)
    throw std::runtime_error(fmt::format("cannot truncate {}", path_));
  handle_ = fh;
}

SharedFile::~SharedFile() {
  if (handle_) {
    MPI_File fh = static_cast<MPI_File>(handle_);
    MPI_File_close(&fh);
  }
}

void SharedFile::close() {
  if (!handle_) return;
  MPI_File fh = static_cast<MPI_File>(handle_);
  handle_ = nullptr;
  if (MPI_File_close(&fh) != MPI_SUCCESS) throw std::runtime_error(fmt::format("cannot close {}", path_));
}

void SharedFile::write_at(std::uint64_t at, const char* data, std::size_t n) {
  MPI_File fh = static_cast<MPI_File>(handle_);
  while (n > 0) {
    const std::size_t piece = std::min<std::size_t>(n, std::size_t(1) << 30);
    MPI_Status status;
    if (MPI_File_write_at(fh, static_cast<MPI_Offset>(at), data, static_cast<int>(piece), MPI_BYTE,
                          &status) != MPI_SUCCESS)
      throw std::runtime_error(fmt::format("cannot write {} bytes at offset {} of {}", piece, at, path_));
    at += piece, data += piece, n -= piece;
  }
}

void SharedFile::fixed(std::string_view text) {
  if (rank() == 0) write_at(offset_, text.data(), text.size());
  offset_ += text.size();
}

void SharedFile::root_text(std::string_view text) {
  if (rank() == 0) write_at(offset_, text.data(), text.size());
}

void SharedFile::patch(std::uint64_t at, std::string_view bytes) {
  if (rank() == 0) write_at(at, bytes.data(), bytes.size());
}

void SharedFile::plants(std::size_t n, std::size_t batch,
                        const std::function<void(std::size_t, std::string&)>& make) {
  // This rank's chunks, formatted on all threads a wave at a time and spilled in order to a file
  // of its own beside the output (so memory stays bounded whatever the section's size), then
  // copied to their places after every earlier plant's chunk once all sizes are known.
  batch = std::max<std::size_t>(1, batch);
  const std::size_t batches = (n + batch - 1) / batch;
  const std::size_t wave = 4 * static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  std::vector<std::uint64_t> sizes(n, 0);
  // Named as a temporary file of this process: where a kill leaves it (in the staging folder of
  // a run that never swapped), the next run's clean-up knows it for a dead run's (is_dead_temporary).
  const std::string spill_path = fmt::format("{}.spill-rank{}.tmp-{}", path_, rank(), process_tag());
  const std::uint64_t registered = register_run_path(spill_path, RunPath::file);  // a signal removes it
  struct Remove {
    const std::string& path;
    std::uint64_t id;
    ~Remove() {
      std::remove(path.c_str());
      unregister_run_path(id);
    }
  } remove_spill{spill_path, registered};
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> spill(std::fopen(spill_path.c_str(), "w+b"), &std::fclose);
  if (!spill) throw std::runtime_error(fmt::format("cannot write {}", spill_path));
  for (std::size_t w0 = 0; w0 < batches; w0 += wave) {
    std::vector<std::string> text(std::min(wave, batches - w0));
    FirstException failed;  // thrown after the region: an exception must not leave it
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t b = 0; b < text.size(); ++b) try {
        for (std::size_t i = (w0 + b) * batch; i < std::min(n, (w0 + b + 1) * batch); ++i) {
          const std::size_t before = text[b].size();
          make(i, text[b]);
          sizes[i] = text[b].size() - before;
        }
      } catch (...) {
        failed.keep();
      }
    failed.rethrow();
    for (const std::string& t : text)
      if (std::fwrite(t.data(), 1, t.size(), spill.get()) != t.size())
        throw std::runtime_error(fmt::format("cannot write {} bytes to {}", t.size(), spill_path));
  }
  RankScan scan(ids_, plants_total_);
  std::vector<std::uint64_t> at = sizes, totals;
  scan.exclusive(at, 1, totals);
  // Consecutive plants of this rank that are consecutive in the file go out together.
  std::rewind(spill.get());
  std::string buf;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    std::uint64_t bytes = sizes[i];
    while (j < n && at[j] == at[i] + bytes) bytes += sizes[j++];
    for (std::uint64_t done = 0; done < bytes;) {
      const std::size_t piece =
          static_cast<std::size_t>(std::min<std::uint64_t>(bytes - done, std::uint64_t(1) << 28));
      buf.resize(piece);
      if (std::fread(buf.data(), 1, piece, spill.get()) != piece)
        throw std::runtime_error(fmt::format("cannot read back {} bytes from {}", piece, spill_path));
      write_at(offset_ + at[i] + done, buf.data(), piece);
      done += piece;
    }
    i = j;
  }
  offset_ += totals[0];
}

SharedOutputSet::SharedOutputSet(const std::string& dir, std::vector<std::string> replaces,
                                 std::string marker, std::vector<std::int64_t> ids,
                                 std::uint64_t plants_total)
    : ids_(std::move(ids)), plants_total_(plants_total) {
  std::string error;
  if (rank() == 0) {
    try {
      folder_ = std::make_unique<StagedFolder>(dir, std::move(replaces), std::move(marker));
      folder_->make();
      staging_ = folder_->staging();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  agree(error);
  std::vector<std::size_t> starts;
  const std::vector<char> all = allgather_bytes(staging_.data(), staging_.size(), &starts);
  staging_.assign(all.data(), starts[1]);  // rank 0's
}

SharedOutputSet::~SharedOutputSet() {
  files_.clear();  // closed before rank 0's StagedFolder removes what is not committed
}

void SharedOutputSet::remove_temporaries() const {
  if (!staging_.empty()) remove_flat_folder(staging_);
}

SharedFile& SharedOutputSet::open(const std::string& name) {
  const std::string path = staging_ + "/" + name;
  files_.emplace_back(path, std::make_unique<SharedFile>(path, ids_, plants_total_));
  return *files_.back().second;
}

void SharedOutputSet::commit_all(const std::string& local_error) {
  std::string error = local_error;
  for (auto& f : files_) {
    try {
      f.second->close();
    } catch (const std::exception& e) {
      if (error.empty()) error = e.what();
    }
  }
  agree(error);
  std::string swap_error;
  if (rank() == 0) {
    try {
      committed_set_ = folder_->commit();
    } catch (const std::exception& e) {
      swap_error = e.what();
    }
  }
  agree(swap_error);
  committed_ = true;
}

}  // namespace canopy::mpi
