#include "distributed/mpi_comm.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace canopy::mpi {
namespace {

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(
      fmt::format("MPI: {} failed: {}", what, std::string(text, static_cast<std::size_t>(len))));
}

int to_int(std::size_t n, const char* what) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error(fmt::format("MPI: {} of {} bytes is more than one message can carry", what, n));
  return static_cast<int>(n);
}

}  // namespace

bool launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

Session::Session() {
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

Session::~Session() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

std::string library_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(text, &len);
  std::string v(text, static_cast<std::size_t>(len));
  return v.substr(0, v.find_first_of(",\n"));
}

int rank() {
  int r = 0;
  check(MPI_Comm_rank(MPI_COMM_WORLD, &r), "MPI_Comm_rank");
  return r;
}

int size() {
  int s = 1;
  check(MPI_Comm_size(MPI_COMM_WORLD, &s), "MPI_Comm_size");
  return s;
}

int local_rank() {
  MPI_Comm node;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node),
        "MPI_Comm_split_type");
  int r = 0;
  MPI_Comm_rank(node, &r);
  MPI_Comm_free(&node);
  return r;
}

void barrier() { check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

std::vector<std::int64_t> sum(std::vector<std::int64_t> values) {
  std::vector<std::int64_t> out(values.size());
  check(MPI_Allreduce(values.data(), out.data(), to_int(values.size(), "sum"), MPI_INT64_T, MPI_SUM,
                      MPI_COMM_WORLD),
        "MPI_Allreduce (sum)");
  return out;
}

double max(double value) {
  double out = value;
  check(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce (max)");
  return out;
}

std::vector<char> allgather_bytes(const void* data, std::size_t bytes, std::vector<std::size_t>* starts) {
  const int p = size();
  const long long mine = static_cast<long long>(bytes);
  std::vector<long long> counts(static_cast<std::size_t>(p));
  check(MPI_Allgather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, MPI_COMM_WORLD),
        "MPI_Allgather (sizes)");
  std::vector<int> c(static_cast<std::size_t>(p)), d(static_cast<std::size_t>(p));
  std::size_t total = 0;
  for (std::size_t r = 0; r < c.size(); ++r) {
    d[r] = to_int(total, "allgather");
    c[r] = to_int(static_cast<std::size_t>(counts[r]), "allgather");
    total += static_cast<std::size_t>(counts[r]);
  }
  to_int(total, "allgather");
  std::vector<char> out(total);
  check(MPI_Allgatherv(data, c[static_cast<std::size_t>(rank())], MPI_BYTE, out.data(), c.data(), d.data(),
                       MPI_BYTE, MPI_COMM_WORLD),
        "MPI_Allgatherv");
  if (starts) {
    starts->assign(d.begin(), d.end());
    starts->push_back(total);
  }
  return out;
}

std::vector<std::vector<char>> alltoall_bytes(const std::vector<std::vector<char>>& out) {
  const auto p = static_cast<std::size_t>(size());
  std::vector<int> sc(p), sd(p), rc(p), rd(p);
  std::vector<char> send;
  for (std::size_t r = 0; r < p; ++r) {
    sd[r] = to_int(send.size(), "alltoall");
    sc[r] = to_int(out[r].size(), "alltoall");
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  check(MPI_Alltoall(sc.data(), 1, MPI_INT, rc.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Alltoall (sizes)");
  std::size_t total = 0;
  for (std::size_t r = 0; r < p; ++r)
    rd[r] = to_int(total, "alltoall"), total += static_cast<std::size_t>(rc[r]);
  std::vector<char> recv(total);
  check(MPI_Alltoallv(send.data(), sc.data(), sd.data(), MPI_BYTE, recv.data(), rc.data(), rd.data(),
                      MPI_BYTE, MPI_COMM_WORLD),
        "MPI_Alltoallv");
  std::vector<std::vector<char>> in(p);
  for (std::size_t r = 0; r < p; ++r) in[r].assign(recv.begin() + rd[r], recv.begin() + rd[r] + rc[r]);
  return in;
}

void agree(const std::string& error) {
  std::vector<std::size_t> starts;
  const std::vector<char> all = allgather_bytes(error.data(), error.size(), &starts);
  for (std::size_t r = 0; r + 1 < starts.size(); ++r)
    if (starts[r + 1] > starts[r])
      throw std::runtime_error(fmt::format("rank {} of {} failed: {}", r, starts.size() - 1,
                                           std::string(all.data() + starts[r], starts[r + 1] - starts[r])));
}

void abort(const std::string& message) {
  fmt::print(stderr, "error: rank {} of {}: {}\n", rank(), size(), message);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 2);
  std::abort();
}

}  // namespace canopy::mpi
