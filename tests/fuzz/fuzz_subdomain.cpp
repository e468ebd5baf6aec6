// libFuzzer target: any bytes as a subdomain file must be read or refused with one rk::Error.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "error.hpp"
#include "subdomain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/rk_fuzz_sub_" + std::to_string(::getpid()) + ".h5";
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    rk::read_subdomain(path, 0, 1, "");
  } catch (const rk::Error&) {
  }
  return 0;
}
