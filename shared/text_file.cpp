#include "text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "error.hpp"

namespace rk {

void write_text_file(const std::string& path, const std::string& text) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "w");
  int err = f ? 0 : (errno ? errno : EIO);
  if (f) {
    if (std::fwrite(text.data(), 1, text.size(), f) != text.size()) err = errno ? errno : EIO;
    if (std::fclose(f) != 0 && !err) err = errno ? errno : EIO;  // the buffered rest is written here
  }
  if (err) throw Error(path + ": cannot write (" + std::strerror(err) + ")");
}

}  // namespace rk
