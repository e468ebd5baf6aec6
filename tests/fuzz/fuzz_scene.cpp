// libFuzzer target: any bytes as a scene file must give a valid Scene or one rk::Error, never a
// crash, a hang or another exception.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "error.hpp"
#include "scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/rk_fuzz_scene_" + std::to_string(::getpid()) + ".yaml";
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    rk::load_scene(path);
  } catch (const rk::Error&) {
  }
  return 0;
}
