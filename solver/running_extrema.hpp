// The least and the largest of f(0), ..., f(n - 1) and a start value, in eight running extrema: one chain
// of minsd or maxsd would wait on each compare, eight fill two vectors. min and max are exact, so the order
// does not change the result; a NaN term is passed over (std::min and std::max keep their first argument).
#pragma once
#include <algorithm>
#include <cstddef>
#include <iterator>

namespace rk {

template <class Pick, class Term>
double running_extremum(std::size_t n, double start, Pick pick, Term f) {
  constexpr std::size_t kChains = 8;
  double e[kChains];
  std::fill(std::begin(e), std::end(e), start);
  const std::size_t whole = n / kChains * kChains;
  for (std::size_t i = 0; i < whole; i += kChains)
    for (std::size_t j = 0; j < kChains; ++j) e[j] = pick(e[j], f(i + j));
  for (std::size_t i = whole; i < n; ++i) e[0] = pick(e[0], f(i));
  for (std::size_t j = 1; j < kChains; ++j) e[0] = pick(e[0], e[j]);
  return e[0];
}

template <class Term>
double least_of(std::size_t n, double start, Term f) {
  return running_extremum(n, start, [](double a, double b) { return std::min(a, b); }, f);
}

template <class Term>
double largest_of(std::size_t n, double start, Term f) {
  return running_extremum(n, start, [](double a, double b) { return std::max(a, b); }, f);
}

}  // namespace rk
