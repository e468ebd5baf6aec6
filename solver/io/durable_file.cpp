#include "io/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "error.hpp"

namespace rk {

bool fsync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

void commit_file(const std::string& tmp, const std::string& path) {
  std::error_code ignored;
  if (!fsync_path(tmp)) {
    std::filesystem::remove(tmp, ignored);
    throw Error(tmp + ": cannot be synced to disk (disk full?)");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::filesystem::remove(tmp, ignored);
    throw Error(path + ": cannot be written (rename failed)");
  }
  fsync_path(std::filesystem::path(path).parent_path().string());
}

}  // namespace rk
