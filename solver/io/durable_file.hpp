// Files that are either whole or absent: written under a temporary name, synced, then renamed over
// the final name (a rename within a directory is atomic), and the directory synced. Checkpoints and
// result frames are written this way, so a killed job or a full disk never leaves half a file.
#pragma once
#include <string>

namespace rk {

// fsync of a file or directory; false if it cannot be opened or synced.
bool fsync_path(const std::string& path);

// Syncs `tmp`, renames it to `path` and syncs the directory; throws rk::Error naming `path`
// (the temporary file is removed then).
void commit_file(const std::string& tmp, const std::string& path);

}  // namespace rk
