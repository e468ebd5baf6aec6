// Whole text files written at once (prep.json, scene.resolved.yaml, solve.json, report.md, the .pvd,
// the subdomains' hash sidecars): every step of the write is checked, so a full disk or a path that
// cannot be created is one error naming the file, never a silently short or missing file.
#pragma once
#include <string>

namespace rk {

// Writes `text` to `path` (replacing it); throws rk::Error "PATH: cannot write (REASON)".
void write_text_file(const std::string& path, const std::string& text);

}  // namespace rk
