#include "parallel/overlap_exchange.hpp"

namespace rk {

OverlapExchange::OverlapExchange(const Model& model, int width) : model_(model), width_(width) {
  for (const auto& list : model.overlap) {
    send_.emplace_back(list.size() * width);
    recv_.emplace_back(list.size() * width);
  }
  requests_.resize(2 * model.overlap.size());
}

// Tag 17: any tag serves, these are the solver's only point-to-point messages.
void OverlapExchange::start(const std::vector<Fixed>& partial) {
  const int k = int(model_.overlap.size());
  for (int q = 0; q < k; ++q)
    MPI_Irecv(recv_[q].data(), int(recv_[q].size() * sizeof(Fixed)), MPI_BYTE, model_.neighbour_ranks[q], 17,
              MPI_COMM_WORLD, &requests_[q]);
  for (int q = 0; q < k; ++q) {
    const auto& list = model_.overlap[q];
    for (std::size_t j = 0; j < list.size(); ++j)
      for (int c = 0; c < width_; ++c) send_[q][j * width_ + c] = partial[std::size_t(list[j]) * width_ + c];
    MPI_Isend(send_[q].data(), int(send_[q].size() * sizeof(Fixed)), MPI_BYTE, model_.neighbour_ranks[q], 17,
              MPI_COMM_WORLD, &requests_[k + q]);
  }
}

void OverlapExchange::finish(std::vector<Fixed>& partial) {
  MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  for (std::size_t q = 0; q < model_.overlap.size(); ++q) {
    const auto& list = model_.overlap[q];
    for (std::size_t j = 0; j < list.size(); ++j)
      for (int c = 0; c < width_; ++c) partial[std::size_t(list[j]) * width_ + c] += recv_[q][j * width_ + c];
  }
}

}  // namespace rk
