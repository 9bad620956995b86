#pragma once
/// MPI for canopy (OpenMPI from Debian): the session, and the few collectives the tiled run
/// needs, each checked (a failed call throws with what failed). Only this folder includes mpi.h.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace canopy::mpi {

/// True when this process was started by mpirun/mpiexec (OpenMPI, PMI or PMIx environment).
bool launched();

/// MPI_Init_thread (funneled) when constructed, MPI_Finalize when destroyed.
class Session {
 public:
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

/// The MPI library's name and version (first line of MPI_Get_library_version).
std::string library_version();
int rank();
int size();
/// The rank among the processes of this node (for one GPU per rank).
int local_rank();
void barrier();
std::vector<std::int64_t> sum(std::vector<std::int64_t> values);
double max(double value);
/// Every rank's bytes, concatenated in rank order, and where each rank's part starts (size+1).
std::vector<char> allgather_bytes(const void* data, std::size_t bytes,
                                  std::vector<std::size_t>* starts = nullptr);
/// Sends `out[r]` to rank r, returns what each rank sent here.
std::vector<std::vector<char>> alltoall_bytes(const std::vector<std::vector<char>>& out);
/// Collective: when any rank passes a non-empty error, every rank throws std::runtime_error
/// naming the first failed rank and its message.
void agree(const std::string& error);
/// Ends every rank after printing `message` (for a failure inside a collective section).
[[noreturn]] void abort(const std::string& message);

/// allgather of trivially copyable values.
template <typename T>
std::vector<T> allgather(const std::vector<T>& mine) {
  const std::vector<char> all = allgather_bytes(mine.data(), mine.size() * sizeof(T));
  std::vector<T> out(all.size() / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), all.data(), all.size());
  return out;
}

}  // namespace canopy::mpi
