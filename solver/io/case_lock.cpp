#include "io/case_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>

#include "error.hpp"

namespace rk {

CaseLock::CaseLock(const std::string& case_dir) {
  const std::string path = case_dir + "/.rksolve.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return;
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  const int why = errno;
  ::close(fd_);
  fd_ = -1;
  if (why == EWOULDBLOCK)
    throw Error(case_dir + ": another rksolve is running in this case (it holds " + path +
                "); wait for it to end or stop it, or solve a copy of the case");
}

CaseLock::~CaseLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace rk
