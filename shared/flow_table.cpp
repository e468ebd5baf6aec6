#include "flow_table.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "error.hpp"

namespace rk {
namespace {

// The cell [k, k + 1] of a strictly ascending axis holding x, and x's weight toward k + 1 in it
// (held at the ends: weight 0 or 1, `inside` false there). An axis of one value has no cells.
struct Bracket {
  std::size_t k = 0;
  double w = 0;
  bool inside = false;
  double width = 1;  // of the cell, in x
};
Bracket bracket(const std::vector<double>& axis, double x) {
  Bracket b;
  if (axis.size() < 2) return b;
  if (x <= axis.front()) return b;
  if (x >= axis.back()) return {axis.size() - 2, 1.0, false, axis.back() - axis[axis.size() - 2]};
  b.k = std::size_t(std::upper_bound(axis.begin(), axis.end(), x) - axis.begin()) - 1;
  b.width = axis[b.k + 1] - axis[b.k];
  b.w = (x - axis[b.k]) / b.width;
  b.inside = true;
  return b;
}

}  // namespace

FlowTable read_flow_table(const std::string& path) {
  require_file(path, "flow stress table");
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot read the flow stress table");
  FlowTable t;
  t.file = path;
  std::string line;
  int row = 1;
  if (!std::getline(in, line) || line.find("strain,strain_rate,temperature,stress") != 0)
    throw Error(path + ":1: the header must be strain,strain_rate,temperature,stress (-, 1/s, K, Pa)");
  std::vector<double> rows;  // 4 per row
  while (std::getline(in, line)) {
    ++row;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::stringstream ss(line);
    double v[4];
    char comma;
    for (int i = 0; i < 4; ++i)
      if (!(ss >> v[i]) || (i < 3 && !(ss >> comma && comma == ',')) || !std::isfinite(v[i]))
        throw Error(path + ":" + std::to_string(row) + ": expected four numbers separated by commas");
    if (v[0] < 0 || v[1] <= 0 || v[2] <= 0 || v[3] < 0)
      throw Error(path + ":" + std::to_string(row) + ": " +
                  (v[3] < 0 ? "a negative stress" : v[1] <= 0 ? "a strain rate that is not positive"
                                                    : v[2] <= 0 ? "a temperature that is not positive (kelvin)"
                                                                : "a negative strain"));
    rows.insert(rows.end(), v, v + 4);
  }
  const std::size_t n = rows.size() / 4;
  if (n == 0) throw Error(path + ": the table holds no rows");
  auto axis = [&](int c) {
    std::vector<double> a;
    for (std::size_t i = 0; i < n; ++i) a.push_back(rows[4 * i + c]);
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    return a;
  };
  t.strain = axis(0), t.rate = axis(1), t.temperature = axis(2);
  const std::size_t ns = t.strain.size(), nr = t.rate.size(), nt = t.temperature.size();
  // the rows must walk the grid in order: temperature, then rate, then strain, each ascending
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = i / (nr * ns), j = (i / ns) % nr, s = i % ns;
    const double* v = &rows[4 * i];
    if (i >= ns * nr * nt || v[0] != t.strain[s] || v[1] != t.rate[j] || v[2] != t.temperature[k]) {
      std::ostringstream why;
      why << path << ":" << (i + 2) << ": ";
      if (i >= ns * nr * nt) {
        why << "more rows than the grid of " << ns << " strains x " << nr << " rates x " << nt << " temperatures";
      } else {
        why << "expected strain " << t.strain[s] << ", rate " << t.rate[j] << ", temperature " << t.temperature[k]
            << " here: the rows must cover every combination once (a gap, or an axis out of ascending order), sorted by "
               "temperature, then strain rate, then strain";
      }
      throw Error(why.str());
    }
    t.stress.push_back(v[3]);
  }
  if (n != ns * nr * nt)
    throw Error(path + ": " + std::to_string(n) + " rows for a grid of " + std::to_string(ns * nr * nt) + " (a gap)");
  return t;
}

void FlowTable::at(double ep, double r, double T, double& y, double& dy_dep, double& dy_drate) const {
  const std::size_t ns = strain.size(), nr = rate.size();
  const Bracket e = bracket(strain, ep), tk = bracket(temperature, T);
  // ln rate: the axis in logs
  Bracket q;
  if (nr >= 2 && r > rate.front()) {
    if (r >= rate.back()) {
      q = {nr - 2, 1.0, false, std::log(rate.back() / rate[nr - 2])};
    } else {
      q.k = std::size_t(std::upper_bound(rate.begin(), rate.end(), r) - rate.begin()) - 1;
      q.width = std::log(rate[q.k + 1] / rate[q.k]);
      q.w = std::log(r / rate[q.k]) / q.width;
      q.inside = true;
    }
  }
  auto value = [&](std::size_t k, std::size_t j, std::size_t s) {
    return stress[(std::min(k, temperature.size() - 1) * nr + std::min(j, nr - 1)) * ns + std::min(s, ns - 1)];
  };
  y = dy_dep = dy_drate = 0;
  for (int a = 0; a < 2; ++a) {      // temperature
    const double wa = a ? tk.w : 1 - tk.w;
    if (wa == 0) continue;
    for (int b = 0; b < 2; ++b) {    // rate
      const double wb = b ? q.w : 1 - q.w;
      const double s0 = value(tk.k + a, q.k + b, e.k), s1 = value(tk.k + a, q.k + b, e.k + 1);
      y += wa * wb * ((1 - e.w) * s0 + e.w * s1);
      if (e.inside) dy_dep += wa * wb * (s1 - s0) / e.width;
      if (q.inside) {  // d/d ln rate of the strain-interpolated value
        const double v = (1 - e.w) * s0 + e.w * s1;
        dy_drate += wa * (b ? 1.0 : -1.0) * v / q.width;
      }
    }
  }
  if (q.inside) dy_drate /= r;
}

}  // namespace rk
