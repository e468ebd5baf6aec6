// Subdomain file: round trip, and refusal of another format version, another run, a truncated file
// and a corrupted dataset, each with a message naming the file and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "error.hpp"
#include "h5file.hpp"
#include "hash.hpp"
#include "subdomain.hpp"
#include "source_dir.hpp"

namespace {

namespace fs = std::filesystem;

rk::Subdomain sample() {
  rk::Subdomain s;
  s.rank = 1, s.ranks = 2, s.scene_hash = "0123456789abcdef";
  const int n = 5000;  // large enough that the data fills whole chunks
  for (int i = 0; i < n; ++i) {
    s.global_id.push_back(2 * i);
    for (int d = 0; d < 3; ++d) s.X.push_back(1e-3 * (i + 0.25 * d));
    s.volume.push_back(1e-9);
    s.spacing.push_back(1e-3);
    s.owner.push_back(i % 2);
    s.flags.push_back(i % 3 == 0 ? rk::kSurface : 0);
  }
  s.cell_global_id = {10, 11};
  s.cell_node_offsets = {0, 4, 8};
  s.cell_nodes = {0, 1, 2, 3, 1, 2, 3, 4};
  for (int g = 0; g < 8; ++g) {
    for (int d = 0; d < 3; ++d) s.point_X.push_back(1e-4 * g);
    s.point_weight.push_back(1e-10);
    s.point_cell.push_back(g / 4);
  }
  s.neighbour_ranks = {0};
  s.overlap = {{0, 3, 7}};
  return s;
}

std::string temp_prefix() { return "rk_test_" + std::to_string(::getpid()) + "_"; }

std::string temp(const std::string& name) { return (fs::temp_directory_path() / (temp_prefix() + name)).string(); }

// Removes this process's temporary files (and their hash files) when the tests end.
struct TempFiles {
  ~TempFiles() {
    std::error_code ec;
    std::vector<fs::path> mine;
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path(), ec))
      if (e.path().filename().string().rfind(temp_prefix(), 0) == 0) mine.push_back(e.path());
    for (const auto& p : mine) fs::remove(p, ec);
  }
} temp_files;

void rehash(const std::string& path) {  // as if the file had been written like this
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(rk::subdomain_hash_path(path)) << rk::fnv1a_hex(bytes) << "\n";
}

std::string error_of(const std::string& path, int rank, int ranks, const std::string& hash) {
  try {
    rk::read_subdomain(path, rank, ranks, hash);
  } catch (const rk::Error& e) {
    return e.what();
  }
  return "";
}

TEST(Subdomain, RoundTrip) {
  const auto path = temp("roundtrip.h5");
  const rk::Subdomain s = sample();
  rk::write_subdomain(path, s);
  const rk::Subdomain r = rk::read_subdomain(path, 1, 2, s.scene_hash);
  EXPECT_EQ(r.global_id, s.global_id);
  EXPECT_EQ(r.X, s.X);
  EXPECT_EQ(r.volume, s.volume);
  EXPECT_EQ(r.owner, s.owner);
  EXPECT_EQ(r.flags, s.flags);
  EXPECT_EQ(r.cell_nodes, s.cell_nodes);
  EXPECT_EQ(r.point_X, s.point_X);
  EXPECT_EQ(r.point_cell, s.point_cell);
  EXPECT_EQ(r.neighbour_ranks, s.neighbour_ranks);
  EXPECT_EQ(r.overlap, s.overlap);
}

TEST(Subdomain, AnotherRunIsRefused) {
  const auto path = temp("run.h5");
  rk::write_subdomain(path, sample());
  EXPECT_NE(error_of(path, 1, 3, "0123456789abcdef").find("prepared for 2 ranks but the job has 3"), std::string::npos);
  EXPECT_NE(error_of(path, 0, 2, "0123456789abcdef").find("belongs to rank 1, not rank 0"), std::string::npos);
  EXPECT_NE(error_of(path, 1, 2, "ffffffffffffffff").find("was prepared from another scene"), std::string::npos);
  EXPECT_NE(error_of(temp("missing.h5"), 1, 2, "").find("file not found"), std::string::npos);
}

TEST(Subdomain, AnotherFormatVersionIsRefused) {
  const auto path = temp("version.h5");
  rk::write_subdomain(path, sample());
  {
    rk::H5File f(path, rk::H5File::Mode::append);
    f.set_attr("format_version", std::int64_t(rk::kFormatVersion + 1));
  }
  rehash(path);  // a consistent file of another version
  const std::string e = error_of(path, 1, 2, "");
  EXPECT_NE(e.find(path), std::string::npos);
  EXPECT_NE(e.find("format version " + std::to_string(rk::kFormatVersion + 1)), std::string::npos) << e;
}

TEST(Subdomain, TruncatedFileIsRefused) {
  const auto path = temp("truncated.h5");
  rk::write_subdomain(path, sample());
  fs::resize_file(path, fs::file_size(path) / 2);
  const std::string e = error_of(path, 1, 2, "");
  EXPECT_NE(e.find(path + ": checksum mismatch: the file is corrupt or truncated"), std::string::npos) << e;
  rehash(path);  // even with a matching hash, HDF5 and our checks refuse it
  const std::string e2 = error_of(path, 1, 2, "");
  EXPECT_TRUE(e2.find("truncated") != std::string::npos || e2.find("corrupt") != std::string::npos) << e2;
}

TEST(Subdomain, CorruptedDatasetFailsItsChecksum) {
  const auto path = temp("corrupt.h5");
  rk::Subdomain s = sample();
  rk::write_subdomain(path, s);
  // Find the bytes of particles/volume (5000 copies of 1e-9) and flip one bit in the middle.
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const double v = 1e-9;
  std::string pattern(reinterpret_cast<const char*>(&v), 8);
  pattern += pattern + pattern + pattern;
  const auto at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 17] ^= 0x10;
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_NE(error_of(path, 1, 2, "").find("checksum mismatch"), std::string::npos) << "the whole-file hash";
  rehash(path);  // past the whole-file hash, the dataset's Fletcher32 checksum still catches it
  const std::string e = error_of(path, 1, 2, "");
  EXPECT_NE(e.find("particles/volume"), std::string::npos) << e;
  EXPECT_NE(e.find("checksum"), std::string::npos) << e;
}

}  // namespace

namespace {

// Crashes found by `make fuzz` (tests/fuzz), kept as regression tests.
std::string fuzz_case(const std::string& name) {  // a copy with a matching hash: HDF5 parses it
  const std::string path = temp(name);
  fs::copy_file(rk::test::kSource + "/tests/unit/data/" + name, path, fs::copy_options::overwrite_existing);
  rehash(path);
  return path;
}

TEST(SubdomainFuzz, HugeClaimedDatasetIsRefusedNotAllocated) {
  const std::string e = error_of(fuzz_case("fuzz_subdomain_oom_1.h5"), 0, 1, "");
  EXPECT_FALSE(e.empty());
  EXPECT_TRUE(e.find("corrupt") != std::string::npos || e.find("cannot") != std::string::npos ||
              e.find("missing") != std::string::npos || e.find("checksum") != std::string::npos) << e;
}

}  // namespace

namespace {

TEST(SubdomainFuzz, CorruptFileIsRefusedBeforeHdf5ParsesIt) {  // libhdf5 itself overflows on this one
  const std::string path = temp("fuzz_overflow.h5");
  fs::copy_file(rk::test::kSource + "/tests/unit/data/fuzz_subdomain_overflow_1.h5", path,
                fs::copy_options::overwrite_existing);
  const std::string e = error_of(path, 0, 1, "");
  EXPECT_NE(e.find("checksum file missing"), std::string::npos) << e;
  std::ofstream(rk::subdomain_hash_path(path)) << "0123456789abcdef\n";
  EXPECT_NE(error_of(path, 0, 1, "").find("checksum mismatch"), std::string::npos);
}

}  // namespace
