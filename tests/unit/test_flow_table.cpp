// Flow stress tables (shared/flow_table.hpp): read with every bad file refused by its row; trilinear
// in (strain, ln rate, temperature), held at the edges; the rate-dependent return lands on them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "error.hpp"
#include "flow_table.hpp"
#include "material/j2_plasticity.hpp"
#include "return_check.hpp"

namespace {

namespace fs = std::filesystem;

// sigma = 100 MPa + 50 MPa ep + 5 MPa ln(rate) - 0.1 MPa/K (T - 1000): linear in each coordinate
double linear_law(double ep, double rate, double T) { return 100e6 + 50e6 * ep + 5e6 * std::log(rate) - 0.1e6 * (T - 1000); }

std::string table_file(const std::string& name, const std::string& body) {
  const auto path = (fs::temp_directory_path() / ("rk_table_" + name + ".csv")).string();
  std::ofstream(path) << "strain,strain_rate,temperature,stress\n" << body;
  return path;
}

std::string grid(double (*law)(double, double, double), const std::vector<double>& eps,
                 const std::vector<double>& rates, const std::vector<double>& temps) {
  std::ostringstream out;
  out.precision(17);
  for (double T : temps)
    for (double r : rates)
      for (double e : eps) out << e << "," << r << "," << T << "," << law(e, r, T) << "\n";
  return out.str();
}

std::string error_of(const std::string& path) {
  try {
    rk::read_flow_table(path);
  } catch (const rk::Error& e) {
    return e.what();
  }
  return "";
}

TEST(FlowTable, ALawLinearInEachCoordinateIsReproducedAndHeldAtTheEdges) {
  const rk::FlowTable t = rk::read_flow_table(table_file("linear", grid(linear_law, {0, 0.5, 1, 2}, {0.1, 1, 10}, {900, 1100, 1300})));
  ASSERT_EQ(t.stress.size(), 36u);
  double y, h, hr;
  for (double ep : {0.2, 0.7, 1.9})
    for (double r : {0.3, 2.0, 7.0})
      for (double T : {950.0, 1200.0}) {
        t.at(ep, r, T, y, h, hr);
        EXPECT_NEAR(y, linear_law(ep, r, T), 1e-6) << ep << " " << r << " " << T;
        EXPECT_NEAR(h, 50e6, 1e-3);
        EXPECT_NEAR(hr, 5e6 / r, 1e-6 / r);
      }
  t.at(3.0, 100.0, 2000, y, h, hr);  // past every edge: the corner's value, no slope
  EXPECT_NEAR(y, linear_law(2, 10, 1300), 1e-6);
  EXPECT_EQ(h, 0.0);
  EXPECT_EQ(hr, 0.0);
  t.at(1.0, 0.01, 800, y, h, hr);  // below the least rate and temperature
  EXPECT_NEAR(y, linear_law(1, 0.1, 900), 1e-6);
}

TEST(FlowTable, BadTablesAreRefusedByTheirRow) {
  const std::string good = grid(linear_law, {0, 1}, {1, 10}, {1000, 1200});
  EXPECT_EQ(error_of(table_file("good", good)), "");
  std::string negative = good;
  negative.replace(negative.find("1,1,1000,") + 9, std::string::npos, "-5\n" + good.substr(good.find('\n', good.find("1,1,1000,")) + 1));
  EXPECT_NE(error_of(table_file("negative", negative)).find(":3: a negative stress"), std::string::npos) << error_of(table_file("negative", negative));
  std::string gap = good;
  gap.erase(gap.find("1,10,1000,"), gap.find('\n', gap.find("1,10,1000,")) - gap.find("1,10,1000,") + 1);
  EXPECT_NE(error_of(table_file("gap", gap)).find("a gap"), std::string::npos) << error_of(table_file("gap", gap));
  // rates out of ascending order
  const std::string swapped = grid(linear_law, {0, 1}, {10, 1}, {1000, 1200});
  EXPECT_NE(error_of(table_file("order", swapped)).find(":2: expected strain 0, rate 1, temperature 1000"), std::string::npos)
      << error_of(table_file("order", swapped));
  const auto header = (fs::temp_directory_path() / "rk_table_header.csv").string();
  std::ofstream(header) << "eps,rate,T,sigma\n0,1,1000,1e8\n";
  EXPECT_NE(error_of(header).find(":1: the header must be"), std::string::npos);
  EXPECT_NE(error_of(table_file("text", "0,1,1000,hard\n")).find(":2: expected four numbers"), std::string::npos);
}

TEST(FlowTable, TheReturnLandsOnTheTablesFlowStress) {
  rk::J2Params law = rk::J2Params::from(200e9, 0.3, 0, 0, true);
  law.table = std::make_shared<const rk::FlowTable>(
      rk::read_flow_table(table_file("return", grid(linear_law, {0, 0.5, 1, 2}, {0.01, 1, 100}, {900, 1300}))));
  int plastic = 0;  // strain 0-1.5, 900-1300 K, increments of 0.1 us to 1 ms
  const double worst = worst_return(law, 3, [](double a, double b, double c, double& ep0, double& T, double& dt) {
    ep0 = 1.5 * a, T = 900 + 400 * b, dt = std::pow(10, -7 + 4 * c);
  }, plastic, 5000);
  EXPECT_GT(plastic, 2500);
  // measured 2.0e-9: the round-off of the test's recomputed rate (ep - ep0) / dt at large strains
  EXPECT_LT(worst, 4e-9);
}

}  // namespace
