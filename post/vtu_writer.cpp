#include "vtu_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "error.hpp"
#include "text_file.hpp"

namespace rk {
namespace {

// Standard base64 of n bytes, padded.
void base64(const unsigned char* p, std::size_t n, std::string& out) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i < n; i += 3) {
    const std::uint32_t b = std::uint32_t(p[i]) << 16 | (i + 1 < n ? std::uint32_t(p[i + 1]) << 8 : 0) |
                            (i + 2 < n ? std::uint32_t(p[i + 2]) : 0);
    out += kDigits[b >> 18 & 63];
    out += kDigits[b >> 12 & 63];
    out += i + 1 < n ? kDigits[b >> 6 & 63] : '=';
    out += i + 2 < n ? kDigits[b & 63] : '=';
  }
}

// The arrays of one file in the <AppendedData> block after the XML, base64-encoded: each array is
// base64(header) base64(data), the two encoded apart as VTK writes them. Uncompressed, the header is
// the byte count; compressed, it holds the block count, block size, last block size and the
// compressed sizes, and the data the zlib blocks (vtkZLibDataCompressor). Base64 rather than raw
// bytes: meshio converts a raw block to base64 itself and, when one array's new offset equals a later
// array's raw offset, gives that later array's name to the wrong data (measured: a velocity array of
// 243 x 3 for 729 points, read correctly by VTK).
class Appended {
 public:
  explicit Appended(bool compress) : compress_(compress) {}

  template <class T>
  void array(std::ostream& xml, const char* type, const std::string& name, int components, const std::vector<T>& v) {
    xml << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
        << "\" format=\"appended\" offset=\"" << text_.size() << "\"/>\n";
    const auto* raw = reinterpret_cast<const unsigned char*>(v.data());
    const std::uint64_t size = v.size() * sizeof(T);
    if (!compress_) {
      base64(reinterpret_cast<const unsigned char*>(&size), 8, text_);
      base64(raw, size, text_);
      return;
    }
    constexpr std::uint64_t kBlock = 32768;
    const std::uint64_t blocks = size == 0 ? 0 : (size + kBlock - 1) / kBlock;
    std::vector<std::uint64_t> header{blocks, kBlock, blocks == 0 ? 0 : size - (blocks - 1) * kBlock};
    std::vector<unsigned char> packed;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t n = std::min(kBlock, size - b * kBlock);
      uLongf out = compressBound(uLong(n));
      const std::size_t start = packed.size();
      packed.resize(start + out);
      if (compress2(packed.data() + start, &out, raw + b * kBlock, uLong(n), 6) != Z_OK)
        throw Error("zlib failed to compress the VTK array " + name);
      packed.resize(start + out);
      header.push_back(out);
    }
    base64(reinterpret_cast<const unsigned char*>(header.data()), 8 * header.size(), text_);
    base64(packed.data(), packed.size(), text_);
  }

  void write(std::ostream& f) const { f << "  <AppendedData encoding=\"base64\">\n   _" << text_ << "\n  </AppendedData>\n"; }

 private:
  bool compress_;
  std::string text_;
};

void arrays(std::ostream& f, Appended& data, const std::vector<VtuArray>& list) {
  for (const auto& a : list) {
    const std::string type = vtk_type(a);
    if (type == "UInt8") data.array(f, "UInt8", a.name, a.components, a.u8);
    else if (type == "Float64") data.array(f, "Float64", a.name, a.components, a.f64);
    else data.array(f, "Int64", a.name, a.components, a.i64);
  }
}

}  // namespace

const char* vtk_type(const VtuArray& a) {
  if (!a.u8.empty()) return "UInt8";
  return !a.i64.empty() || a.f64.empty() ? "Int64" : "Float64";
}

void VtuCells::add(const std::int64_t* points, int count, std::uint8_t type) {
  connectivity.insert(connectivity.end(), points, points + count);
  offsets.push_back(std::int64_t(connectivity.size()));
  types.push_back(type);
}

VtuCells VtuCells::triangles(const std::vector<std::int32_t>& corners) {
  VtuCells c;
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    const std::int64_t p[3] = {corners[t], corners[t + 1], corners[t + 2]};
    c.add(p, 3, 5);
  }
  return c;
}

void write_vtu(const std::string& path, const std::vector<double>& points, const std::vector<VtuArray>& point_data,
               const VtuCells& cells, const std::vector<VtuArray>& cell_data, bool compress) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw Error(path + ": cannot write the VTK file");
    Appended data(compress);
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (compress ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
      << points.size() / 3 << "\" NumberOfCells=\"" << cells.types.size() << "\">\n      <PointData>\n";
    arrays(f, data, point_data);
    f << "      </PointData>\n      <CellData>\n";
    arrays(f, data, cell_data);
    f << "      </CellData>\n      <Points>\n";
    data.array(f, "Float64", "Points", 3, points);
    f << "      </Points>\n      <Cells>\n";
    data.array(f, "Int64", "connectivity", 1, cells.connectivity);
    data.array(f, "Int64", "offsets", 1, cells.offsets);
    data.array(f, "UInt8", "types", 1, cells.types);
    f << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    data.write(f);
    f << "</VTKFile>\n";
    f.close();
    if (!f) {
      std::remove(tmp.c_str());
      throw Error(path + ": write failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write (renaming " + tmp + " over it: " + std::strerror(err) + ")");
  }
}

void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries) {
  std::ostringstream f;
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
  f.precision(12);
  for (const auto& e : entries)
    f << "    <DataSet timestep=\"" << e.time << "\" part=\"" << e.part << "\" name=\"" << e.name << "\" file=\""
      << e.file << "\"/>\n";
  f << "  </Collection>\n</VTKFile>\n";
  write_text_file(path, f.str());
}

}  // namespace rk
