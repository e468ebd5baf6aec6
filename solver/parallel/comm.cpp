#include "parallel/comm.hpp"

#include <algorithm>
#include <vector>

#include "error.hpp"

namespace rk {

Comm::Comm() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void Comm::max(double* v, int n) const { MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD); }
void Comm::sum(double* v, int n) const { MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD); }
void Comm::sum(std::int64_t* v, int n) const { MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD); }
void Comm::min(double* v, int n) const { MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD); }
std::vector<double> Comm::gather_all(const std::vector<double>& mine, std::int64_t max_count) const {
  // the counts and offsets in 64 bits: their sum over many ranks passes what an MPI int count holds
  std::int64_t count = std::int64_t(mine.size());
  std::vector<std::int64_t> counts(size_), offsets(size_ + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT64_T, counts.data(), 1, MPI_INT64_T, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(std::size_t(offsets[size_]));
  if (offsets[size_] <= max_count) {  // one call: every count and offset fits an int
    std::vector<int> n(size_), at(size_);
    for (int r = 0; r < size_; ++r) n[r] = int(counts[r]), at[r] = int(offsets[r]);
    MPI_Allgatherv(mine.data(), n[rank_], MPI_DOUBLE, all.data(), n.data(), at.data(), MPI_DOUBLE, MPI_COMM_WORLD);
    return all;
  }
  // more than an int counts: each rank's share broadcast from it in pieces of at most max_count
  std::copy(mine.begin(), mine.end(), all.begin() + offsets[rank_]);
  for (int r = 0; r < size_; ++r)
    for (std::int64_t done = 0; done < counts[r]; done += max_count) {
      const int piece = int(std::min(max_count, counts[r] - done));
      MPI_Bcast(all.data() + offsets[r] + done, piece, MPI_DOUBLE, r, MPI_COMM_WORLD);
    }
  return all;
}

void Comm::all_gather(const double* mine, int count, double* all) const {
  MPI_Allgather(mine, count, MPI_DOUBLE, all, count, MPI_DOUBLE, MPI_COMM_WORLD);
}

void Comm::exchange(const std::vector<double>& send, const std::vector<int>& send_counts, std::vector<double>& received,
                    std::vector<int>& recv_counts) const {
  recv_counts.resize(std::size_t(size_));
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  send_at_.resize(std::size_t(size_)), recv_at_.resize(std::size_t(size_));
  int s = 0, r = 0;
  for (std::size_t q = 0; q < std::size_t(size_); ++q) send_at_[q] = s, recv_at_[q] = r, s += send_counts[q], r += recv_counts[q];
  received.resize(std::size_t(r));
  MPI_Alltoallv(send.data(), send_counts.data(), send_at_.data(), MPI_DOUBLE, received.data(), recv_counts.data(),
                recv_at_.data(), MPI_DOUBLE, MPI_COMM_WORLD);
}

void Comm::barrier() const { MPI_Barrier(MPI_COMM_WORLD); }

void Comm::check(bool ok, const std::string& message) const {
  int failing = ok ? size_ : rank_;
  MPI_Allreduce(MPI_IN_PLACE, &failing, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (failing == size_) return;
  int length = rank_ == failing ? int(message.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, failing, MPI_COMM_WORLD);
  std::vector<char> text(message.begin(), message.end());
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, failing, MPI_COMM_WORLD);
  throw Error(std::string(text.begin(), text.end()));
}

}  // namespace rk
