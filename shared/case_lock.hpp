// One program at a time writes a case folder: two rksolve runs into one case interleaved their history
// rows and left one run's solve.json beside the other's last frame, both exiting 0, and `rkprep
// --force` removed a running solve's results under it. rksolve's rank 0, and rkprep while it replaces
// a case, hold an advisory lock (flock) on CASE/.rksolve.lock and remove the file at their end; the
// system drops the lock when the process ends however it ends, so a killed run's file locks nothing.
#pragma once
#include <string>

namespace rk {

class CaseLock {
 public:
  // Takes the lock, or throws Error naming the case when another process holds it. Where the file
  // cannot be made (no such folder, a read-only case) nothing is locked: the run's own checks say why;
  // something other than a file by its name is refused.
  explicit CaseLock(const std::string& case_dir);
  ~CaseLock();
  CaseLock(const CaseLock&) = delete;
  CaseLock& operator=(const CaseLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

// Whether a program holds the case's lock now (rkpost: a run in progress has no solve.json yet).
bool case_locked(const std::string& case_dir);

}  // namespace rk
