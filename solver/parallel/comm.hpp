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
  // Every rank calls it. If any rank is not ok, every rank throws rk::Error with the message of the
  // lowest failing rank: one clear message, no hang, no rank left waiting.
  void check(bool ok, const std::string& message) const;
  void barrier() const;
  double wtime() const { return MPI_Wtime(); }

 private:
  int rank_ = 0, size_ = 1;
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
