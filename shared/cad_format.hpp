// CAD files by their extension, as rkprep reads them and the scene checks their units.
#pragma once
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace rk {

// The file's extension in lower case (".geo", ".step", ...).
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// STEP and IGES: OpenCASCADE reads them in millimetres, converting from the unit the file declares.
inline bool declares_its_unit(const std::string& ext) { return ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs"; }

}  // namespace rk
