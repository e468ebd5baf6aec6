#pragma once
// The source tree's root (set by tests/CMakeLists.txt), where the unit tests read the shipped scenes and data.
#include <string>

namespace rk::test {
inline const std::string kSource = RK_SOURCE_DIR;
}  // namespace rk::test
