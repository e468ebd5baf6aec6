// The MPI world as the solver sees it: reductions and collective error checks. With the overlap
// exchange (parallel/overlap_exchange.cpp) and main.cpp's start and end, these are the only places
// that call MPI.
#pragma once
#include <mpi.h>

#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "error.hpp"

namespace rk {

class Comm {
 public:
  Comm();
  int rank() const { return rank_; }
  int size() const { return size_; }
  void max(double* values, int count) const;  // in place, over all ranks
  void sum(double* values, int count) const;
  void sum(std::int64_t* values, int count) const;  // exact: integers (fixed-point sums)
  void min(double* values, int count) const;
  // Every rank's `mine`, concatenated in rank order, on every rank (set-up only). Totals past
  // max_count values (an MPI int count) travel in pieces of at most max_count.
  std::vector<double> gather_all(const std::vector<double>& mine, std::int64_t max_count = INT_MAX) const;
  // Per step, into buffers sized by the caller's earlier calls (no allocation once they have grown):
  // every rank's `count` values at `mine`, in rank order, into `all` (count * size values).
  void all_gather(const double* mine, int count, double* all) const;
  // `send` holds send_counts[q] values for each rank q in rank order; `received` gets what each rank
  // sent this one, in rank order (recv_counts per rank). Counts are per rank and small (a surface's share).
  void exchange(const std::vector<double>& send, const std::vector<int>& send_counts, std::vector<double>& received,
                std::vector<int>& recv_counts) const;
  // Every rank calls it. If any rank is not ok, every rank throws rk::Error with the message of the
  // lowest failing rank: one clear message, no hang, no rank left waiting.
  void check(bool ok, const std::string& message) const;
  void barrier() const;
  double wtime() const { return MPI_Wtime(); }

 private:
  int rank_ = 0, size_ = 1;
  mutable std::vector<int> send_at_, recv_at_;  // exchange's offsets, kept between calls
};

// Runs `fn` on every rank; an rk::Error on any rank becomes the same error on all ranks (for a step
// that can fail on one rank, e.g. a write to a full disk, between collective calls).
template <class Fn>
auto collectively(const Comm& comm, Fn fn) {
  std::string message;
  decltype(fn()) result{};
  try {
    result = fn();
  } catch (const Error& e) {
    message = e.what();
  }
  comm.check(message.empty(), message);
  return result;
}

}  // namespace rk
