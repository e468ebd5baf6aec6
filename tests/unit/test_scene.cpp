// Scene validation: each kind of bad input is one error naming the file, the line and the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

#include "error.hpp"
#include "scene.hpp"
#include "source_dir.hpp"

namespace {

namespace fs = std::filesystem;

const char* kGood = R"(geometry:
  cad: bar.geo
  unit: mm
discretization:
  spacing: 1.0e-3
material:
  model: j2_linear
  density: 8930
  youngs_modulus: 117.0e9
  poisson_ratio: 0.35
  yield_stress: 400.0e6
time:
  end: 1.0e-6
)";

std::string write_scene(const std::string& text) {
  // one file per test: ctest runs the tests in parallel processes
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto path = (fs::temp_directory_path() / (std::string("rk_scene_test.") + info->name() + ".yaml")).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& text, const std::vector<rk::Override>& o = {}, rk::Side side = rk::Side::prep) {
  try {
    rk::load_scene(write_scene(text), o, side);
  } catch (const rk::Error& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  return s.replace(s.find(from), from.size(), to);
}

TEST(Scene, GoodSceneResolvesDefaults) {
  const rk::Scene s = rk::load_scene(write_scene(kGood));
  EXPECT_DOUBLE_EQ(s.geometry.unit, 1e-3);
  EXPECT_DOUBLE_EQ(s.discretization.dilation, 2.0);
  EXPECT_EQ(s.discretization.gauss_order, 2);
  EXPECT_DOUBLE_EQ(s.time.output_interval, 1e-7);
  EXPECT_NE(s.resolved_yaml.find("cfl: 0.9"), std::string::npos);  // no dies: the measured default
  EXPECT_TRUE(fs::path(s.geometry.cad).is_absolute());
  EXPECT_EQ(s.prep_hash.size(), 16u);
}

// Dies take the same default step; their penalty's scale holds at CFL 0.5, so at 0.9 it is taken
// (0.9 / 0.5)^2 times: the same stiffness k = s m / dt^2 at the 1.8x step.
TEST(Scene, DiesTakeTheDefaultStepAndKeepTheirPenaltysStiffness) {
  const rk::Scene s = rk::load_scene(rk::test::kSource + "/geometry/upsetting/scene.yaml");
  ASSERT_FALSE(s.dies.empty());
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.9);
  EXPECT_DOUBLE_EQ(s.penalty_scale_at_cfl(), s.contact.penalty_scale * 3.24);
}

TEST(Scene, UnknownKey) {
  const auto e = error_of(replace(kGood, "  density: 8930", "  density: 8930\n  colour: red"));
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(rk_scene_test\.\w+\.yaml:9: unknown key 'material\.colour')"))) << e;
}

TEST(Scene, MissingKey) {
  const auto e = error_of(replace(kGood, "  yield_stress: 400.0e6\n", ""));
  EXPECT_NE(e.find("missing key 'material.yield_stress'"), std::string::npos) << e;
  EXPECT_NE(e.find(".yaml:7"), std::string::npos) << e;  // the material section's line
}

TEST(Scene, MisspeltRequiredKeyIsNamedOnItsOwnLine) {
  const auto e = error_of(replace(kGood, "  poisson_ratio: 0.35", "  poison_ratio: 0.35"));
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(missing key 'material\.poisson_ratio'\n  \S+\.yaml:10: unknown key )"
                                              R"('material\.poison_ratio' \(did you mean 'poisson_ratio'\?\))")))
      << e;
  // a key far from any known one is not taken for a misspelling
  const auto far = error_of(replace(kGood, "  poisson_ratio: 0.35", "  colour: red"));
  EXPECT_EQ(far.find("did you mean"), std::string::npos) << far;
}

// A key given twice: YAML leaves it to the reader, which took the first value without a word
TEST(Scene, AKeyGivenTwiceIsNamedOnItsSecondLine) {
  const auto e = error_of(replace(kGood, "  density: 8930", "  density: 8930\n  density: 7800"));
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(\.yaml:9: key 'material\.density' is given twice)"))) << e;
}

// Names head history.csv's columns: a comma split them (33 header columns over 26-column rows), an empty
// name gave '.force', two dies of one name two columns 'die.stroke', a die and a wall of one name two 'X.force'
TEST(Scene, NamesAreColumnHeadsUniqueAmongDiesWallsAndFaces) {
  const std::string walls = std::string(kGood) + "boundaries:\n  rigid_walls:\n    - {name: floor, point: [0, 0, 0], normal: [0, 0, 1]}\n";
  const auto comma = error_of(replace(walls, "name: floor", "name: 'floor,left'"));
  EXPECT_NE(comma.find("key 'boundaries.rigid_walls[0].name' = 'floor,left': a name heads columns of history.csv"), std::string::npos)
      << comma;
  const auto empty = error_of(replace(walls, "name: floor", "name: ''"));
  EXPECT_NE(empty.find("= '': a name heads columns"), std::string::npos) << empty;
  const auto twice = error_of(walls + "    - {name: floor, point: [0, 0, 0.03], normal: [0, 0, -1]}\n");
  EXPECT_NE(twice.find("two rigid walls or faces named 'floor'"), std::string::npos) << twice;
  // an unnamed wall takes the first free number: after one named 'wall1' the second is 'wall2'
  const std::string numbered = replace(walls, "name: floor", "name: wall1") + "    - {point: [0, 0, 0.03], normal: [0, 0, -1]}\n";
  EXPECT_EQ(error_of(numbered), "");
  EXPECT_EQ(rk::load_scene(write_scene(numbered)).rigid_walls.at(1).name, "wall2");
  EXPECT_EQ(error_of(replace(walls, "name: floor", "name: 'floor 2.a'")), "");  // (cases named so before still read)
  const std::string die = "  - {name: die, cad: die.geo, unit: mm, motion: {direction: [0, 0, -1], speed: 1}}\n";
  const std::string dies = std::string(kGood) + "dies:\n" + die;
  EXPECT_EQ(error_of(dies), "");
  const auto two = error_of(dies + die);
  EXPECT_NE(two.find("key 'dies[1].name': two dies, rigid walls or faces named 'die'"), std::string::npos) << two;
  const auto wall = error_of(replace(walls, "name: floor", "name: die") + "dies:\n" + die);
  EXPECT_NE(wall.find("key 'dies[0].name': two dies, rigid walls or faces named 'die'"), std::string::npos) << wall;
}

// STEP and IGES come in millimetres from OpenCASCADE, whatever unit the file declares: another unit would
// scale them twice (a millimetre STEP at cm 10x), so it is refused by key, the default's too
TEST(Scene, AStepOrIgesFileTakesMillimetres) {
  const std::string step = replace(kGood, "cad: bar.geo", "cad: bar.STEP");
  EXPECT_EQ(rk::load_scene(write_scene(step)).geometry.unit, 1e-3);
  const auto cm = error_of(replace(step, "  unit: mm\n", "  unit: cm\n"));
  EXPECT_NE(cm.find("key 'geometry.unit' = cm: bar.STEP is read in millimetres whatever unit it declares"), std::string::npos) << cm;
  const auto fallback = error_of(replace(replace(kGood, "cad: bar.geo", "cad: bar.igs"), "  unit: mm\n", ""));
  EXPECT_NE(fallback.find("key 'geometry.unit' = m (the default): bar.igs is read in millimetres"), std::string::npos) << fallback;
  // BREP and .geo carry bare numbers: any unit
  EXPECT_EQ(rk::load_scene(write_scene(replace(replace(kGood, "cad: bar.geo", "cad: bar.brep"), "unit: mm", "unit: in"))).geometry.unit, 0.0254);
}

// Constants in another unit run and give a wrong answer (E in GPa: the whole run in one step): warned by key
TEST(Scene, MaterialConstantsNoMetalHasAreWarnedByTheirKeys) {
  EXPECT_TRUE(rk::material_warnings(rk::load_scene(write_scene(kGood))).empty());
  const auto has = [](const std::vector<std::string>& w, const std::string& text) {
    return std::any_of(w.begin(), w.end(), [&](const std::string& x) { return x.find(text) != std::string::npos; });
  };
  const auto gpa = rk::material_warnings(rk::load_scene(write_scene(replace(kGood, "117.0e9", "117"))));
  EXPECT_TRUE(has(gpa, "material.youngs_modulus = 117 Pa is below any metal's")) << gpa.size();
  const auto gcc = rk::material_warnings(rk::load_scene(write_scene(replace(kGood, "8930", "8.93"))));
  EXPECT_TRUE(has(gcc, "material.density = 8.93 kg/m^3 is outside any metal's")) << gcc.size();
  const auto strong = rk::material_warnings(rk::load_scene(write_scene(replace(kGood, "400.0e6", "400.0e9"))));
  EXPECT_TRUE(has(strong, "material.yield_stress = 4e+11 Pa is 3.4 of youngs_modulus")) << (strong.empty() ? "" : strong[0]);
  // nu near 1/2: the step falls as the volumetric wave's speed rises, (1 - nu) / ((1 + nu) (1 - 2 nu)) under the root:
  // 111x that at 0.3 for 0.49999, 1.68x for 0.45
  const auto stiff = rk::material_warnings(rk::load_scene(write_scene(replace(kGood, "poisson_ratio: 0.35", "poisson_ratio: 0.49999"))));
  EXPECT_TRUE(has(stiff, "material.poisson_ratio = 0.49999: the volumetric wave runs 111x as fast as at 0.3")) << (stiff.empty() ? "" : stiff[0]);
  EXPECT_TRUE(rk::material_warnings(rk::load_scene(write_scene(replace(kGood, "poisson_ratio: 0.35", "poisson_ratio: 0.45")))).empty());
  // the edges: 1 GPa and 5 % of E pass
  EXPECT_TRUE(rk::material_warnings(rk::load_scene(write_scene(replace(replace(kGood, "117.0e9", "1e9"), "400.0e6", "50e6")))).empty());
}

TEST(Scene, AThousandFramesOrMoreAreWarnedOf) {
  EXPECT_TRUE(rk::output_warnings(rk::load_scene(write_scene(kGood))).empty());  // (10 frames by default)
  const auto many = rk::output_warnings(rk::load_scene(write_scene(replace(kGood, "  end: 1.0e-6\n", "  end: 1.0e-6\n  output_interval: 1e-12\n"))));
  ASSERT_EQ(many.size(), 1u);
  EXPECT_NE(many[0].find("time.output_interval = 1e-12 s asks for 1e+06 frames"), std::string::npos) << many[0];
  EXPECT_TRUE(rk::output_warnings(rk::load_scene(write_scene(replace(kGood, "  end: 1.0e-6\n", "  end: 1.0e-6\n  output_interval: 1e-9\n")))).empty());
}

TEST(Scene, WrongType) {
  const auto e = error_of(replace(kGood, "117.0e9", "hard"));
  EXPECT_NE(e.find(".yaml:9: key 'material.youngs_modulus' must be a number"), std::string::npos) << e;
}

TEST(Scene, IncompressiblePoissonRatio) {
  const auto e = error_of(replace(kGood, "0.35", "0.5"));
  EXPECT_NE(e.find(".yaml:10: key 'material.poisson_ratio' = 0.5 is out of range (-1, 0.5)"),
            std::string::npos)
      << e;
}

TEST(Scene, NegativeDensity) {
  const auto e = error_of(replace(kGood, "8930", "-8930"));
  EXPECT_NE(e.find(".yaml:8: key 'material.density' = -8930 is out of range"), std::string::npos) << e;
}

TEST(Scene, SupportTooSmallForTheBasis) {
  const auto e = error_of(replace(kGood, "  spacing: 1.0e-3", "  spacing: 1.0e-3\n  basis: quadratic\n  dilation: 2.0"));
  EXPECT_NE(e.find("'discretization.dilation' = 2.0"), std::string::npos) << e;
  EXPECT_NE(e.find("too small for the quadratic basis"), std::string::npos) << e;
}

TEST(Scene, BadChoiceAndUnit) {
  EXPECT_NE(error_of(replace(kGood, "unit: mm", "unit: furlong")).find("'geometry.unit' = 'furlong' is not one of: m, mm"),
            std::string::npos);
}

TEST(Scene, OverridesApplyAndAreValidated) {
  const rk::Scene s = rk::load_scene(write_scene(kGood), {rk::parse_override("time.cfl=0.25")});
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.25);
  EXPECT_NE(error_of(kGood, {rk::parse_override("time.cfl=-1")}).find("'time.cfl' = -1 is out of range"), std::string::npos);
  EXPECT_NE(error_of(kGood, {rk::parse_override("discretization.spacing=2e-3")}, rk::Side::solve)
                .find("used by rkprep; re-run rkprep"),
            std::string::npos);
  EXPECT_THROW(rk::parse_override("time.cfl"), rk::Error);
  // a bad value from the command line is said to be one (it read as the scene file's line 1)
  const auto typed = error_of(kGood, {rk::parse_override("material.density=abc")});
  EXPECT_NE(typed.find(".yaml (--set material.density): key 'material.density' must be a number"), std::string::npos) << typed;
  const auto ranged = error_of(kGood, {rk::parse_override("time.cfl=-1")});
  EXPECT_NE(ranged.find(".yaml (--set time.cfl): key 'time.cfl' = -1 is out of range"), std::string::npos) << ranged;
  EXPECT_NE(error_of(replace(kGood, "8930", "abc")).find(".yaml:8: key 'material.density' must be a number"), std::string::npos);
  const auto first_line = error_of("colour: red\n" + std::string(kGood), {rk::parse_override("time.cfl=0.5")});
  EXPECT_NE(first_line.find(".yaml:1: unknown key 'colour'"), std::string::npos) << first_line;  // (not "--set colour")
}

// Multi-rate steps: auto or a power of two up to 16, and what they are not built for refused naming the key
TEST(Scene, SubcyclingRefusesWhatItIsNotBuiltFor) {
  const auto with = [](const char* value) {
    return std::vector<rk::Override>{rk::parse_override(std::string("time.subcycling=") + value)};
  };
  EXPECT_EQ(rk::load_scene(write_scene(kGood), with("16")).time.subcycling, 16);
  EXPECT_EQ(rk::load_scene(write_scene(kGood), with("1")).time.subcycling, 1);
  for (const char* bad : {"6", "32", "fast", "0"})
    EXPECT_NE(error_of(kGood, with(bad)).find("key 'time.subcycling': must be auto, 1, 2, 4, 8 or 16"), std::string::npos) << bad;
  const std::string upsetting = rk::test::kSource + "/geometry/upsetting/scene.yaml";
  // auto, the default: the largest ratio where the scene allows it, one rate where it does not; the
  // resolved deck keeps "auto", so that it resolves again when read with other keys set
  const rk::Scene bar = rk::load_scene(write_scene(kGood));
  EXPECT_EQ(bar.time.subcycling, 16);
  EXPECT_NE(bar.resolved_yaml.find("subcycling: auto"), std::string::npos) << bar.resolved_yaml;
  EXPECT_EQ(rk::load_scene(write_scene(kGood), with("auto")).time.subcycling, 16);
  EXPECT_EQ(rk::load_scene(write_scene(kGood), {rk::parse_override("time.stable_step=frequency")}).time.subcycling, 1);
  EXPECT_EQ(rk::load_scene(upsetting).time.subcycling, 1);
  std::string e;
  try {
    rk::load_scene(upsetting, with("4"));
  } catch (const rk::Error& x) {
    e = x.what();
  }
  EXPECT_NE(e.find("'time.subcycling' = 4 cannot be combined with dies or rigid walls"), std::string::npos) << e;
  EXPECT_NE(error_of(kGood, {rk::parse_override("time.subcycling=2"), rk::parse_override("reference_updates.strain=0.2")})
                .find("cannot be combined with 'reference_updates.strain' > 0"),
            std::string::npos);
}

TEST(Scene, SyntaxErrorNamesTheLine) {
  const auto e = error_of("geometry:\n  cad: [unclosed\n");
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;
}

}  // namespace

TEST(Scene, NodalIntegrationRefusesReferenceUpdates) {  // its smoothing cells are not rebuilt at an update
  const auto e = error_of(kGood, {rk::parse_override("discretization.integration=nodal"),
                                  rk::parse_override("reference_updates.strain=0.5")});
  EXPECT_NE(e.find("'reference_updates.strain' cannot be combined with 'discretization.integration' = nodal"),
            std::string::npos)
      << e;
  EXPECT_EQ(error_of(kGood, {rk::parse_override("discretization.integration=nodal")}), "");
}

TEST(Scene, CellRuleIsAGaussCellsKey) {  // nodal integration has no cells' points to place
  EXPECT_EQ(rk::load_scene(write_scene(kGood), {rk::parse_override("discretization.cell_rule=four_point")})
                .discretization.cell_rule, "four_point");
  const auto e = error_of(kGood, {rk::parse_override("discretization.integration=nodal"),
                                  rk::parse_override("discretization.cell_rule=six_point")});
  EXPECT_NE(e.find("'discretization.cell_rule' = six_point places the points of Gauss cells"), std::string::npos) << e;
  EXPECT_NE(error_of(kGood, {rk::parse_override("discretization.cell_rule=five_point")}).find("is not one of"),
            std::string::npos);
}

namespace {

// A hot part: specific heat, conduction, a die and the air (no CAD is read by load_scene's checks)
std::string hot(const std::string& die_temperature) {
  return replace(kGood, "  yield_stress: 400.0e6\n",
                 "  yield_stress: 400.0e6\n  specific_heat: 460\n  conductivity: 45\ninitial_conditions:\n"
                 "  temperature: 1423.15\nthermal:\n  ambient_temperature: 293.15\ndies:\n  - name: top\n    cad: die.geo\n"
                 "    temperature: " + die_temperature + "\n    heat_transfer: 1.0e4\n    motion: {direction: [0, 0, -1], speed: 0.01}\n");
}

TEST(Scene, ACelsiusLookingTemperatureIsWarnedByItsKey) {
  EXPECT_TRUE(rk::temperature_warnings(rk::load_scene(write_scene(hot("523.15")))).empty());
  const auto w = rk::temperature_warnings(rk::load_scene(write_scene(hot("250"))));  // 250 C written as kelvin
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("dies 'top'.temperature = 250 K is -23 C"), std::string::npos) << w[0];
  EXPECT_EQ(rk::scene_warnings(rk::load_scene(write_scene(hot("250")))), w);  // what rksolve prints and reports
}

TEST(Scene, OneGaussPointPerCellIsWarnedByItsKey) {
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(kGood))).empty());  // gauss_order 2
  const auto one = replace(kGood, "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  gauss_order: 1\n");
  const auto w = rk::accuracy_warnings(rk::load_scene(write_scene(one)));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("discretization.gauss_order = 1"), std::string::npos) << w[0];
  EXPECT_EQ(rk::scene_warnings(rk::load_scene(write_scene(one))), w);  // what rksolve prints and reports
  // nodal integration has no Gauss points: an order it does not use is refused (AGaussOrderThePointsDoNotUseIsRefused)
  // nor where a hexahedron takes a four- or six-point rule (the order is then a tetrahedron's)
  const auto four = replace(one, "  gauss_order: 1\n", "  gauss_order: 1\n  cell_rule: four_point\n");
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(four))).empty());
}

TEST(Scene, AFewerPointRuleWithDiesIsWarnedByItsKey) {  // the die loads it moves were measured
  const std::string upsetting = rk::test::kSource + "/geometry/upsetting/scene.yaml";
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(replace(kGood, "  spacing: 1.0e-3\n",
                                                                       "  spacing: 1.0e-3\n  cell_rule: six_point\n"))))
                  .empty());  // no dies: the Taylor bar's validation holds
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(upsetting)).empty());
  for (const char* rule : {"four_point", "six_point"}) {
    const auto w = rk::accuracy_warnings(
        rk::load_scene(upsetting, {rk::parse_override(std::string("discretization.cell_rule=") + rule)}));
    ASSERT_EQ(w.size(), 1u) << rule;
    EXPECT_NE(w[0].find(std::string("discretization.cell_rule = ") + rule + " with dies"), std::string::npos) << w[0];
  }
}

TEST(Scene, APlasticPartWithoutFbarIsWarnedByItsKey) {
  const auto none = replace(kGood, "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  volumetric: none\n");
  const auto w = rk::accuracy_warnings(rk::load_scene(write_scene(none)));  // j2_linear: it locks
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("discretization.volumetric = none"), std::string::npos) << w[0];
  // an elastic part has no isochoric flow to lock, and one point per cell has no F-bar to leave out
  const auto elastic = replace(replace(none, "j2_linear", "elastic"), "  yield_stress: 400.0e6\n", "");
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(elastic))).empty());
  EXPECT_EQ(rk::accuracy_warnings(rk::load_scene(write_scene(
                replace(none, "  volumetric: none\n", "  volumetric: none\n  gauss_order: 1\n")))).size(), 1u);  // Gauss 1's only
}

TEST(Scene, TheFrequencysStepWithAPenaltyContactIsWarnedByItsKey) {
  const auto frequency = replace(kGood, "  end: 1.0e-6\n", "  end: 1.0e-6\n  stable_step: frequency\n");
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(frequency))).empty());  // no contact: nothing softens
  for (const char* contact : {"contact:\n  self: true\n",
                              "boundaries:\n  rigid_walls:\n    - {name: wall, point: [0, 0, 0], normal: [0, 0, 1]}\n"}) {
    const auto w = rk::accuracy_warnings(rk::load_scene(write_scene(frequency + contact)));
    ASSERT_EQ(w.size(), 1u) << contact;
    EXPECT_NE(w[0].find("time.stable_step = frequency"), std::string::npos) << w[0];
  }
}

TEST(Scene, ThermalKeysNeedTheirPhysics) {
  const auto start = error_of(kGood + std::string("initial_conditions:\n  temperature: 600\n"));
  EXPECT_NE(start.find("key 'initial_conditions.temperature' needs a temperature: 'material.specific_heat'"), std::string::npos)
      << start;
  EXPECT_NE(error_of(replace(kGood, "  yield_stress: 400.0e6\n", "  yield_stress: 400.0e6\n  conductivity: 45\n"))
                .find("'material.conductivity' needs 'material.specific_heat'"),
            std::string::npos);
  EXPECT_NE(error_of(kGood + std::string("thermal:\n  convection: 10\n")).find("section 'thermal' needs 'material.conductivity'"),
            std::string::npos);
  EXPECT_NE(error_of(replace(hot("523.15"), "    heat_transfer: 1.0e4\n", "    heat_transfer: -1\n"))
                .find("heat_transfer' = -1 is out of range"),
            std::string::npos);
}

}  // namespace

namespace {

TEST(Scene, AMaterialLibraryGivesTheKeysTheSceneDoesNotOverride) {
  const std::string lib = (fs::temp_directory_path() / "rk_library_steel.yaml").string();
  std::ofstream(lib) << "material:\n  model: j2_linear\n  density: 7850\n  youngs_modulus: 210.0e9\n"
                        "  poisson_ratio: 0.3\n  yield_stress: 300.0e6\n";
  const std::string scene = replace(kGood, "  model: j2_linear\n  density: 8930\n  youngs_modulus: 117.0e9\n  poisson_ratio: 0.35\n"
                                           "  yield_stress: 400.0e6\n",
                                    "  library: " + lib + "\n  yield_stress: 350.0e6\n");
  const rk::Scene s = rk::load_scene(write_scene(scene));
  EXPECT_EQ(s.material.density, 7850);
  EXPECT_EQ(s.material.yield_stress, 350e6);  // the scene's own key wins
  EXPECT_NE(s.resolved_yaml.find("library: " + lib), std::string::npos);
  const std::string missing = error_of(replace(scene, lib, lib + ".absent"));
  EXPECT_NE(missing.find("key 'material.library': cannot read"), std::string::npos) << missing;
  std::ofstream(lib) << "material:\n  model: j2_linear\n  density: -1\n";
  const std::string bad = error_of(scene);
  EXPECT_NE(bad.find("material.density"), std::string::npos) << bad;
  EXPECT_NE(bad.find("with material.library " + lib), std::string::npos) << bad;
}

// A body's own material (section `bodies`): read as the part's (a library under it too), the part's where
// a body names none; one clear error for an unknown or repeated body, a bad key under it, and temperature.
TEST(Scene, ABodyHasItsOwnMaterialOrThePartsOne) {
  const std::string lib = (fs::temp_directory_path() / "rk_library_body_steel.yaml").string();
  std::ofstream(lib) << "material:\n  model: elastic\n  density: 7850\n  youngs_modulus: 210.0e9\n  poisson_ratio: 0.3\n";
  const std::string two = replace(kGood, "  unit: mm\n", "  unit: mm\n  bodies:\n    - {name: striker, cad: s.geo}\n"
                                                         "    - {name: anvil, cad: a.geo}\n");
  const std::string own = two + "bodies:\n  - name: striker\n    material: {library: " + lib + ", poisson_ratio: 0.0}\n";
  const rk::Scene s = rk::load_scene(write_scene(own));
  ASSERT_EQ(s.bodies.size(), 2u);
  ASSERT_TRUE(s.bodies[0].material != nullptr);
  EXPECT_EQ(s.bodies[0].material->density, 7850);
  EXPECT_EQ(s.bodies[0].material->poisson_ratio, 0.0);  // the scene's key over the library's
  EXPECT_TRUE(s.bodies[1].material == nullptr) << "the anvil takes the part's";
  EXPECT_EQ(s.material.density, 8930);
  const std::string unknown = error_of(replace(own, "  - name: striker\n    material", "  - name: hammer\n    material"));
  EXPECT_NE(unknown.find("key 'bodies[0].name': no body 'hammer' in geometry.bodies"), std::string::npos) << unknown;
  const std::string twice = error_of(own + "  - name: striker\n    material: {model: elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n");
  EXPECT_NE(twice.find("bodies[1].name': body 'striker' is listed twice"), std::string::npos) << twice;
  const std::string bad = error_of(replace(own, "poisson_ratio: 0.0}", "poisson_ratio: 0.7}"));
  EXPECT_NE(bad.find("key 'bodies[0].material.poisson_ratio' = 0.7 is out of range"), std::string::npos) << bad;
  EXPECT_NE(bad.find("with bodies[0].material.library " + lib), std::string::npos) << bad;
  const std::string hot = error_of(replace(own, "poisson_ratio: 0.0}", "poisson_ratio: 0.0, specific_heat: 460}"));
  EXPECT_NE(hot.find("bodies[0].material': a body's own material is offered without temperature only"), std::string::npos) << hot;
}

TEST(Scene, TheShippedMaterialsLoad) {
  for (const char* name : {"aisi_1045", "ofhc_copper", "aluminium_2024", "c45_hot"}) {
    const std::string scene = replace(kGood, "  model: j2_linear\n  density: 8930\n  youngs_modulus: 117.0e9\n  poisson_ratio: 0.35\n"
                                             "  yield_stress: 400.0e6\n",
                                      "  library: " + rk::test::kSource + "/geometry/materials/" + name + ".yaml\n");
    const rk::Scene s = rk::load_scene(write_scene(scene));
    EXPECT_TRUE(s.material.thermal() && s.material.conducting()) << name;
    if (std::string(name) == "c45_hot") {  // the Freiberg form's offsets, EN 1993-1-2's c(T) with its peak at 735 C
      EXPECT_TRUE(s.material.strain_offset == 0.1 && s.material.strain_rate_offset == 0.1 &&
                  s.material.specific_heat_table.at(1008.15) == 5000 && s.material.conductivity_at(1423.15) == 27.3);
    }
  }
}

}  // namespace

namespace {

TEST(Scene, TemperatureRegionsSetTheStartByPositionTheLastBoxWinning) {
  const std::string text = replace(hot("523.15"), "  temperature: 1423.15\n",
                                   "  temperature: 1423.15\n  temperature_regions:\n"
                                   "    - {lo: [0, 0, 0], hi: [1, 1, 1], temperature: 1300}\n"
                                   "    - {lo: [0, 0, 0.5], hi: [1, 1, 1], temperature: 1200}\n");
  const rk::Scene s = rk::load_scene(write_scene(text));
  const double out[3] = {-1, 0, 0}, low[3] = {0.5, 0.5, 0.2}, high[3] = {0.5, 0.5, 0.7};
  EXPECT_EQ(s.initial.temperature_at(out), 1423.15);
  EXPECT_EQ(s.initial.temperature_at(low), 1300);
  EXPECT_EQ(s.initial.temperature_at(high), 1200);
  EXPECT_NE(error_of(replace(text, "hi: [1, 1, 1], temperature: 1200", "hi: [1, 1, 0.4], temperature: 1200"))
                .find("a box's hi must exceed its lo"),
            std::string::npos);
  const auto w = rk::temperature_warnings(rk::load_scene(write_scene(replace(text, "temperature: 1200", "temperature: 200"))));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("temperature_regions[1]"), std::string::npos) << w[0];
}

}  // namespace

namespace {

TEST(Scene, AConductivityTableIsPiecewiseLinearAndHeldAtItsEnds) {
  const std::string text = replace(hot("523.15"), "  conductivity: 45\n", "  conductivity_table: [[300, 50], [1300, 25], [1500, 30]]\n");
  const rk::Scene s = rk::load_scene(write_scene(text));
  ASSERT_TRUE(s.material.conducting());
  EXPECT_EQ(s.material.conductivity_at(200), 50);
  EXPECT_DOUBLE_EQ(s.material.conductivity_at(800), 37.5);
  EXPECT_DOUBLE_EQ(s.material.conductivity_at(1400), 27.5);
  EXPECT_EQ(s.material.conductivity_at(2000), 30);
  EXPECT_NE(error_of(replace(text, "[1300, 25], [1500, 30]", "[1500, 25], [1300, 30]")).find("entry 3: the temperatures must ascend"),
            std::string::npos);
  EXPECT_NE(error_of(replace(text, "[300, 50]", "[300, -5]")).find("each conductivity W/(m K) in (0, 10000]"), std::string::npos);
  EXPECT_NE(error_of(replace(text, "  conductivity_table:", "  conductivity: 45\n  conductivity_table:")).find("exclude each other"),
            std::string::npos);
}

// c(T) and rho(T) tables: the enthalpy h = int_0^T c is the table's integral (c held at its first
// value from 0 K), its inverse returns the temperature; the density table replaces the linear
// expansion; a temperature outside a table, or a mass density off the table, is warned by its key.
TEST(Scene, SpecificHeatAndDensityTables) {
  const std::string text =
      replace(hot("523.15"), "  specific_heat: 460\n",
              "  specific_heat_table: [[290, 450], [1000, 700], [1500, 650]]\n  density_table: [[290, 9100], [1500, 8900]]\n");
  const rk::Scene s = rk::load_scene(write_scene(text));
  ASSERT_TRUE(s.material.thermal());
  const rk::PiecewiseLinear& c = s.material.specific_heat_table;
  EXPECT_EQ(s.material.specific_heat, 450);  // temperature on
  EXPECT_DOUBLE_EQ(c.integral(200), 200 * 450.0);
  // 290 * 450 + the trapezoid to 800 K (c from 450 to 450 + 250 * 510 / 710)
  EXPECT_NEAR(c.integral(800), 290 * 450.0 + 510 * (450 + 450 + 250 * 510 / 710.0) / 2, 1e-6);
  EXPECT_NEAR(c.integral(1600), 290 * 450.0 + 710 * 575.0 + 500 * 675.0 + 100 * 650.0, 1e-6);
  for (double T : {150.0, 300.0, 655.5, 1000.0, 1234.5, 1500.0, 2000.0})
    EXPECT_NEAR(c.inverse_integral(c.integral(T)), T, 1e-9 * T) << T;
  EXPECT_EQ(error_of(replace(text, "  density_table:", "  thermal_expansion: 1.0e-5\n  density_table:"))
                .find("'material.density_table' and 'material.thermal_expansion' exclude each other") == std::string::npos,
            false);
  EXPECT_NE(error_of(replace(text, "  specific_heat_table:", "  specific_heat: 460\n  specific_heat_table:")).find("exclude each other"),
            std::string::npos);
  EXPECT_NE(error_of(replace(text, "[1000, 700]", "[1000, 0]")).find("each specific heat J/(kg K) in (0, 100000]"), std::string::npos);
  // every temperature (part 1423.15, die 523.15, air 293.15 K) lies in the tables; the part's density
  // 8930 is the table's 8913 at 1423.15 K within 2 %
  EXPECT_TRUE(rk::temperature_warnings(s).empty());
  const auto warned = rk::temperature_warnings(rk::load_scene(write_scene(replace(text, "[1500, 650]", "[1400, 650]"))));
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_NE(warned[0].find("initial_conditions.temperature = 1423.15 K lies outside material.specific_heat_table (290 to 1400 K)"),
            std::string::npos) << warned[0];
  const auto heavy = rk::temperature_warnings(rk::load_scene(write_scene(replace(text, "[1500, 8900]", "[1500, 8000]"))));
  ASSERT_EQ(heavy.size(), 1u);
  EXPECT_NE(heavy[0].find("material.density = 8930 kg/m^3 is the part's mass density"), std::string::npos) << heavy[0];
}

// A crank press: the stroke from the start angle, the rate its derivative (central differences),
// zero at bottom dead centre; a rod not longer than the crank and a crank with a curve are refused.
TEST(Scene, CrankPressFollowsTheSliderCrankLaw) {
  const std::string crank = "crank: {radius: 0.05, rod: 0.3, strokes_per_minute: 60, start_angle: 90}";
  const std::string text = replace(hot("523.15"), "speed: 0.01}", crank + "}");
  ASSERT_NE(text, hot("523.15"));
  const rk::Scene s = rk::load_scene(write_scene(text));
  const rk::DieMotion& m = s.dies.at(0).motion;
  ASSERT_TRUE(m.cranked());
  EXPECT_EQ(m.stroke(0), 0.0);
  // at 90 degrees: r (1 - cos) + l (1 - sqrt(1 - (r/l)^2)) = 0.05 + 0.3 (1 - sqrt(35/36)); at 180: 2 r
  EXPECT_NEAR(m.crank.position(M_PI / 2), 0.05 + 0.3 * (1 - std::sqrt(35.0 / 36.0)), 1e-15);
  EXPECT_NEAR(m.stroke(m.crank.bottom_dead_centre()), 0.1 - m.crank.position(M_PI / 2), 1e-15);
  EXPECT_NEAR(m.crank.bottom_dead_centre(), 0.25, 1e-15);  // a quarter turn at 1 turn per second
  for (double t : {0.0, 0.05, 0.1, 0.2}) {
    const double d = 1e-6;
    EXPECT_NEAR(m.rate(t), (m.stroke(t + d) - m.stroke(t - d)) / (2 * d), 1e-7) << t;
  }
  EXPECT_NEAR(m.rate(0), 0.05 * 2 * M_PI, 1e-12);  // at 90 degrees the rod is square to the ram's path
  EXPECT_NEAR(m.rate(0.25), 0.0, 1e-12);
  EXPECT_LE(m.rate(0.1), m.fastest());
  EXPECT_NE(error_of(replace(text, "rod: 0.3", "rod: 0.04")).find("the connecting rod must be longer than the crank radius"),
            std::string::npos);
  EXPECT_NE(error_of(replace(text, "end: 1.0e-6", "end: 0.3")).find("'time.end' = 0.3 s runs past the bottom dead centre of die 'top' at 0.25 s"),
            std::string::npos);
  EXPECT_NE(error_of(replace(text, "crank: {", "curve: [[0, 0], [1, 1]], crank: {")).find("exclude each other"), std::string::npos);
  // a speed beside the crank: refused by name (it read "'speed' = 1 is out of range [0, 0]")
  const auto both = error_of(replace(text, "crank: {", "speed: 1, crank: {"));
  EXPECT_NE(both.find("motion.speed': the die's speed follows its 'crank'; give one or the other"), std::string::npos) << both;
  // the start angle in [0, 180) degrees: top dead centre, the usual start and the default, is in (it was refused,
  // the default too); bottom dead centre is not (no stroke left)
  EXPECT_EQ(error_of(replace(text, ", start_angle: 90", "")), "");
  EXPECT_EQ(error_of(replace(text, "start_angle: 90", "start_angle: 0")), "");
  EXPECT_NE(error_of(replace(text, "start_angle: 90", "start_angle: 180")).find("= 180 is out of range [0, 180)"), std::string::npos)
      << error_of(replace(text, "start_angle: 90", "start_angle: 180"));
}

// damage: off without the section; each criterion on where its key is given, with or without a
// critical value; an empty section and an unknown criterion refused by name.
TEST(Scene, DamageCriteriaOnlyWhereNamed) {
  EXPECT_FALSE(rk::load_scene(write_scene(kGood)).damage.on());
  const rk::Scene s = rk::load_scene(write_scene(std::string(kGood) + "damage:\n  brozzo: {}\n  cockcroft_latham: {critical: 0.4}\n"));
  EXPECT_TRUE(s.damage.brozzo && s.damage.cockcroft_latham);
  EXPECT_EQ(s.damage.brozzo_critical, 0.0);
  EXPECT_EQ(s.damage.cockcroft_latham_critical, 0.4);
  const rk::Scene one = rk::load_scene(write_scene(std::string(kGood) + "damage:\n  brozzo:\n"));
  EXPECT_TRUE(one.damage.brozzo && !one.damage.cockcroft_latham);
  EXPECT_NE(error_of(std::string(kGood) + "damage:\n  oyane: {}\n").find("oyane"), std::string::npos);
  EXPECT_NE(error_of(std::string(kGood) + "damage:\n  cockcroft_latham: {critical: -1}\n").find("damage.cockcroft_latham.critical"),
            std::string::npos);
}

}  // namespace

// Settings at the edges that ran without a word (a newcomer's probe, 2026-12-07): a mass-scaling target
// of the whole run scaled the density 4.6e13 times and ran one step with the die through the part; a Gauss
// order with nodal integration was ignored
namespace {
TEST(Scene, AMassScalingStepOfTheWholeRunIsRefusedAndOneOfFewStepsWarnedOf) {
  const auto one = error_of(std::string(kGood), {{"time.mass_scaling_dt", "1e-6"}}, rk::Side::solve);
  EXPECT_NE(one.find("key 'time.mass_scaling_dt' = 1e-06 s is not below time.end = 1e-06 s"), std::string::npos) << one;
  const auto warned = rk::accuracy_warnings(rk::load_scene(write_scene(kGood), {{"time.mass_scaling_dt", "1e-7"}}));
  EXPECT_TRUE(std::any_of(warned.begin(), warned.end(), [](const std::string& w) {
    return w.find("time.mass_scaling_dt = 1e-07 s: the run to time.end = 1e-06 s takes at most 10 steps") != std::string::npos;
  }));
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(kGood), {{"time.mass_scaling_dt", "1e-8"}})).empty());
  // a hammer's blow against a mass-scaled part: its inertia scaled too (the blow's force 3.2x at the density x 1146)
  const std::string hammer = std::string(kGood) + "dies:\n  - {name: ram, cad: die.geo, unit: mm, motion: {direction: [0, 0, -1], "
                             "blow: {energy: 344, ram_mass: 100}}}\n";
  const auto blow = rk::accuracy_warnings(rk::load_scene(write_scene(hammer), {{"time.mass_scaling_dt", "1e-8"}}));
  EXPECT_TRUE(std::any_of(blow.begin(), blow.end(), [](const std::string& w) {
    return w.find("time.mass_scaling_dt with die 'ram''s hammer blow: the blow is dynamic") != std::string::npos;
  })) << (blow.empty() ? "" : blow[0]);
  EXPECT_TRUE(rk::accuracy_warnings(rk::load_scene(write_scene(hammer))).empty());
}

TEST(Scene, AGaussOrderThePointsDoNotUseIsRefused) {
  const auto nodal = error_of(std::string(kGood), {{"discretization.integration", "nodal"}, {"discretization.gauss_order", "3"}});
  EXPECT_NE(nodal.find("key 'discretization.gauss_order' = 3 sets the Gauss cells' points, which "
                       "'discretization.integration' = nodal does not use"), std::string::npos) << nodal;
  // (a four- or six-point rule uses it: the tetrahedra's points)
  EXPECT_EQ(error_of(std::string(kGood), {{"discretization.cell_rule", "six_point"}, {"discretization.gauss_order", "1"}}), "");
  EXPECT_EQ(error_of(std::string(kGood), {{"discretization.integration", "nodal"}, {"discretization.gauss_order", "2"}}), "");
}
}  // namespace
