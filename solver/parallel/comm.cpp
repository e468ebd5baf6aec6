#include "parallel/comm.hpp"

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
std::vector<double> Comm::gather_all(const std::vector<double>& mine) const {
  int count = int(mine.size());
  std::vector<int> counts(size_), offsets(size_ + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(offsets[size_]);
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD);
  return all;
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
