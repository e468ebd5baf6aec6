// The files two programs exchange, defined once in shared/ (run_summary.hpp, history_columns.hpp):
// - solve.json: what the writer writes, the reader reads back field by field; a file of another
//   format (or none: an older rksolve) is refused with the file's name and both formats;
// - history.csv: every column of every shipped scene has its unit; the scalars come first, then
//   per die its six columns in order, so a reader finds the press force beside its stroke; a
//   Johnson-Cook scene has its three temperature columns (K) after the scalars.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "error.hpp"
#include "history_columns.hpp"
#include "phase_names.hpp"
#include "run_summary.hpp"
#include "scene.hpp"
#include "source_dir.hpp"

namespace {

using rk::test::kSource;

TEST(Contracts, RunSummaryReadsBackWhatWasWritten) {
  const std::string path = (std::filesystem::temp_directory_path() / "rk_contract_solve.json").string();
  rk::RunSummary s;
  s.steps = 10705, s.time = 8e-5, s.particles = 1369, s.max_energy_error = 6.3e-4, s.ebc_method = "nodal";
  s.mass_scaling = 12.5, s.warnings = {"die 'punch' never touched the part"};
  for (int p = 0; p < rk::kPhaseCount; ++p) s.phases[rk::kPhaseNames[p]] = {0.5 * p, double(p)};
  rk::write_run_summary(path, s);
  const rk::RunSummary r = rk::read_run_summary(path);
  EXPECT_EQ(r.format, rk::kRunSummaryFormat);
  EXPECT_EQ(r.steps, s.steps);
  EXPECT_EQ(r.time, s.time);
  EXPECT_EQ(r.particles, s.particles);
  EXPECT_EQ(r.max_energy_error, s.max_energy_error);
  EXPECT_EQ(r.ebc_method, s.ebc_method);
  EXPECT_EQ(r.mass_scaling, s.mass_scaling);
  EXPECT_EQ(r.warnings, s.warnings);
  ASSERT_EQ(r.phases.size(), std::size_t(rk::kPhaseCount));
  EXPECT_EQ(r.phases.at("contact").max_s, double(rk::kContact));
  std::filesystem::remove(path);
}

TEST(Contracts, RunSummaryOfAnotherFormatIsRefused) {
  const std::string path = (std::filesystem::temp_directory_path() / "rk_contract_old.json").string();
  std::ofstream(path) << R"({"steps": 3, "time": 1e-5})";  // an older rksolve: no format
  try {
    rk::read_run_summary(path);
    FAIL() << "an unversioned solve.json was read";
  } catch (const rk::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find("format 0, this one reads 1"), std::string::npos) << m;
  }
  std::filesystem::remove(path);
}

TEST(Contracts, EveryHistoryColumnHasItsUnit) {
  const std::vector<std::string> fractions = {"energy_error", "kinetic_internal_ratio", "volume_change"};
  for (const char* scene : {"upsetting/scene_friction.yaml", "taylor_bar/scene.yaml", "back_extrusion/scene.yaml",
                            "elastic_bar/scene_walls.yaml", "beam/scene.yaml", "wheel_forging/scene.yaml",
                            "taylor_bar/scene_johnson_cook.yaml", "upsetting/scene_hammer.yaml"}) {
    const auto columns = rk::history_columns(rk::load_scene(kSource + "/geometry/" + scene, {}));
    ASSERT_GE(columns.size(), std::size(rk::kHistoryScalars)) << scene;
    for (std::size_t k = 0; k < std::size(rk::kHistoryScalars); ++k) EXPECT_EQ(columns[k], rk::kHistoryScalars[k].name);
    for (const auto& c : columns) {
      const bool fraction = std::find(fractions.begin(), fractions.end(), c) != fractions.end() || c.ends_with(".filled");
      EXPECT_EQ(rk::history_unit(c) == "-", fraction) << scene << ": column " << c;
    }
  }
  const auto up = rk::history_columns(rk::load_scene(kSource + "/geometry/upsetting/scene_friction.yaml", {}));
  const auto stroke = std::find(up.begin(), up.end(), "die.stroke");
  ASSERT_NE(stroke, up.end());
  const std::vector<std::string> die(stroke, stroke + 6);
  EXPECT_EQ(die, (std::vector<std::string>{"die.stroke", "die.force", "die.fx", "die.fy", "die.fz", "die.work"}));
  EXPECT_EQ(rk::history_unit("die.force"), "N");
  EXPECT_EQ(rk::history_unit("die.stroke"), "m");
  EXPECT_EQ(rk::history_unit("time"), "s");
  EXPECT_EQ(rk::history_unit("contacts"), "count");
  const auto hot = rk::history_columns(rk::load_scene(kSource + "/geometry/taylor_bar/scene_johnson_cook.yaml", {}));
  const std::size_t k = std::size(rk::kHistoryScalars);
  ASSERT_GE(hot.size(), k + 3);
  EXPECT_EQ(std::vector<std::string>(hot.begin() + k, hot.begin() + k + 3),
            (std::vector<std::string>{"temperature_mean", "temperature_min", "temperature_max"}));
  EXPECT_EQ(rk::history_unit("temperature_max"), "K");
}

}  // namespace
