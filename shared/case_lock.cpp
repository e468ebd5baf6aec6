#include "case_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "case_layout.hpp"
#include "error.hpp"

namespace rk {

CaseLock::CaseLock(const std::string& case_dir) : path_(case_dir + "/" + kSolveLock) {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    // something else by the lock's name (a folder made by hand) would let two runs write one case: refused
    if (struct stat at {}; fd_ < 0 && ::lstat(path_.c_str(), &at) == 0 && !S_ISREG(at.st_mode))
      throw Error(case_dir + ": " + path_ + " is not a lock file, so the case cannot be locked against another run "
                  "writing it; remove it");
    if (fd_ < 0) return;
    // (a few tries over 0.1 s: rkpost's case_locked holds a shared lock for an instant)
    int got = -1, why = 0;
    for (int tries = 0; tries < 5; ++tries) {
      got = ::flock(fd_, LOCK_EX | LOCK_NB);
      why = errno;
      if (got == 0 || why != EWOULDBLOCK) break;
      ::usleep(20000);
    }
    if (got != 0) {
      ::close(fd_);
      fd_ = -1;
      if (why == EWOULDBLOCK)
        throw Error(case_dir + ": another rksolve or rkprep is writing this case (it holds " + path_ +
                    "); wait for it to end or stop it, or use a copy of the case");
      return;
    }
    // the file locked is the one at the path still (the run before may have removed it on its way out)
    struct stat held {}, now {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &now) == 0 && held.st_ino == now.st_ino && held.st_dev == now.st_dev)
      return;
    ::close(fd_);
    fd_ = -1;
  }
}

bool case_locked(const std::string& case_dir) {
  const int fd = ::open((case_dir + "/" + kSolveLock).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // (drops a shared lock this took)
  return held;
}

CaseLock::~CaseLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // (while still held: a run that opens it now finds it gone and makes its own)
  ::close(fd_);
}

}  // namespace rk
