// Narrowing of counts and offsets to the 32-bit int that MPI counts, METIS (built with 32-bit
// indices) and the 32-bit index arrays take: a value that does not fit is one error naming what it
// counts, never a silent wrap into a negative offset.
#pragma once
#include <climits>
#include <cstdint>
#include <string>

#include "error.hpp"

namespace rk {

// `value` as an int; throws rk::Error "WHAT: VALUE exceeds the 2147483647 a 32-bit int holds".
inline int checked_int(std::int64_t value, const std::string& what) {
  if (value < INT_MIN || value > INT_MAX)
    throw Error(what + ": " + std::to_string(value) + " exceeds the " + std::to_string(INT_MAX) + " a 32-bit int holds");
  return int(value);
}

}  // namespace rk
