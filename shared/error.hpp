// One exception type for every input boundary: the message names the file, key, line or particle.
#pragma once
#include <stdexcept>
#include <string>

namespace rk {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace rk
