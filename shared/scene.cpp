// Scene parsing and validation: every key, type and physical range is checked here and nowhere else.
#include "scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "cad_format.hpp"
#include "error.hpp"
#include "hash.hpp"

namespace rk {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The key paths that --set gave while a scene is read (load_scene_checked), so that where() names them
// (a value parsed on its own is marked at its own line 1: it read as the scene's)
std::set<std::string>& overridden_paths() {
  static std::set<std::string> paths;
  return paths;
}

// Where a node came from: "scene.yaml:12", or "scene.yaml (--set a.b)" for a value given on the command line.
std::string where(const std::string& file, const YAML::Node& node, const std::string& path) {
  if (overridden_paths().count(path)) return file + " (--set " + path + ")";
  if (node && node.Mark().line >= 0) return file + ":" + std::to_string(node.Mark().line + 1);
  return file + " (key '" + path + "')";
}

struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  std::string text() const {
    std::ostringstream s;
    s << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
    return s.str();
  }
  bool holds(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

// A YAML map read strictly: every key must be consumed, each value is typed and range-checked,
// and what was read (defaults included) is recorded in `resolved`.
class Section {
 public:
  Section(std::string file, YAML::Node node, std::string path, YAML::Node resolved)
      : file_(std::move(file)), node_(node), path_(std::move(path)), resolved_(resolved) {
    if (node_ && !node_.IsNull() && !node_.IsMap())
      throw Error(where(file_, node_, path_) + ": '" + path_ + "' must be a map of keys");
    std::set<std::string> keys;  // (YAML leaves a key given twice to the reader, which would take the first)
    if (node_ && node_.IsMap())
      for (const auto& kv : node_)
        if (kv.first.IsScalar() && !keys.insert(kv.first.Scalar()).second)
          throw Error(where(file_, kv.first, key_path(kv.first.Scalar())) + ": key '" + key_path(kv.first.Scalar()) +
                      "' is given twice");
  }

  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  // "file:line: key 'path.key'", for a message about that key
  bool has(const std::string& key) const { return node_ && node_[key] && !node_[key].IsNull(); }

  std::string where_of(const std::string& key) const {
    return where(file_, node_ ? node_[key] : YAML::Node(), key_path(key)) + ": key '" + key_path(key) + "'";
  }

  YAML::Node get(const std::string& key, bool required) {
    seen_.insert(key);
    YAML::Node v = node_ ? node_[key] : YAML::Node();
    if ((!v || v.IsNull()) && required)
      throw Error(where(file_, node_, path_) + ": missing key '" + key_path(key) + "'" + misspelt(key));
    return v;
  }

  double number(const std::string& key, std::optional<double> fallback, Range range) {
    YAML::Node v = get(key, !fallback.has_value());
    double x = fallback.value_or(0.0);
    if (v && !v.IsNull()) x = as_number(v, key);
    if (!std::isfinite(x) || !range.holds(x)) {
      std::ostringstream s;
      s << where(file_, v ? v : node_, key_path(key)) << ": key '" << key_path(key) << "' = " << x
        << " is out of range " << range.text();
      throw Error(s.str());
    }
    resolved_[key] = x;
    return x;
  }

  int integer(const std::string& key, std::optional<int> fallback, int lo, int hi) {
    double x = number(key, fallback ? std::optional<double>(*fallback) : std::nullopt,
                      Range{double(lo), double(hi)});
    if (x != std::floor(x))
      throw Error(where(file_, node_[key], key_path(key)) + ": key '" + key_path(key) +
                  "' must be an integer");
    resolved_[key] = int(x);
    return int(x);
  }

  std::string text(const std::string& key, std::optional<std::string> fallback,
                   const std::vector<std::string>& choices = {}) {
    YAML::Node v = get(key, !fallback.has_value());
    std::string s = fallback.value_or("");
    if (v && !v.IsNull()) {
      if (!v.IsScalar())
        throw Error(where(file_, v, key_path(key)) + ": key '" + key_path(key) + "' must be a string");
      s = v.as<std::string>();
    }
    if (!choices.empty() && std::find(choices.begin(), choices.end(), s) == choices.end()) {
      std::string list;
      for (auto& c : choices) list += (list.empty() ? "" : ", ") + c;
      throw Error(where(file_, v ? v : node_, key_path(key)) + ": key '" + key_path(key) + "' = '" + s +
                  "' is not one of: " + list);
    }
    resolved_[key] = s;
    return s;
  }

  // An entry's `name`: it heads columns of history.csv and tracks.csv and names the entry in messages,
  // so not empty and without a comma, a quote or a control character (a comma split the columns; an
  // empty name gave '.force')
  std::string name(std::optional<std::string> fallback) {
    const std::string n = text("name", std::move(fallback));
    if (n.empty() || std::any_of(n.begin(), n.end(), [](unsigned char c) { return c == ',' || c == '"' || c < 0x20 || c == 0x7f; }))
      throw Error(where_of("name") + " = '" + n +
                  "': a name heads columns of history.csv and tracks.csv: not empty, no comma, quote or control character");
    return n;
  }
  // and one unique among the entries of `lists`: an entry's name heads its own columns, so dies, rigid
  // walls and faces share one set of names. Without a `name` key the entry is called `stem` numbered
  // from `first`, the first such name not taken (a wall named 'wall1' leaves the next unnamed one 'wall2').
  template <class... Lists>
  std::string unique_name(std::optional<std::string> stem, std::size_t first, const std::string& what,
                          const Lists&... lists) {
    auto taken = [&](const std::string& n) {
      return (std::any_of(lists.begin(), lists.end(), [&](const auto& other) { return other.name == n; }) || ...);
    };
    std::optional<std::string> fallback;
    for (std::size_t k = first; stem && !fallback; ++k) {
      std::string n = *stem;  // (appended: stem + to_string() trips GCC 12's -Wrestrict)
      n += std::to_string(k);
      if (!taken(n)) fallback = n;
    }
    const std::string n = name(std::move(fallback));
    if (taken(n)) throw Error(where_of("name") + ": two " + what + " named '" + n + "' (a name heads its own columns)");
    return n;
  }

  Vec3 vec3(const std::string& key, std::optional<Vec3> fallback, bool unit = false) {
    YAML::Node v = get(key, !fallback.has_value());
    Vec3 x = fallback.value_or(Vec3{});
    if (v && !v.IsNull()) {
      if (!v.IsSequence() || v.size() != 3)
        throw Error(where(file_, v, key_path(key)) + ": key '" + key_path(key) +
                    "' must be a list of 3 numbers");
      for (int i = 0; i < 3; ++i) x[i] = as_number(v[i], key);
    }
    if (unit) {
      double n = norm(x);
      // (1e-12: zero up to round-off)
      if (!(n > 1e-12))
        throw Error(where(file_, v ? v : node_, key_path(key)) + ": key '" + key_path(key) +
                    "' must be a non-zero direction");
      for (auto& c : x) c /= n;
    }
    YAML::Node out(YAML::NodeType::Sequence);
    for (double c : x) out.push_back(c);
    out.SetStyle(YAML::EmitterStyle::Flow);
    resolved_[key] = out;
    return x;
  }

  // A list of [a, b] number pairs (`what`: "[time, stroke]"), a strictly ascending (`ascending` names
  // them: "the times"), recorded in flow style; empty when the key is absent.
  std::vector<std::pair<double, double>> pairs(const std::string& key, const std::string& what, const std::string& ascending) {
    std::vector<std::pair<double, double>> out;
    YAML::Node v = get(key, false);
    if (!v || v.IsNull()) return out;
    const std::string at = "key '" + key_path(key) + "'";
    if (!v.IsSequence() || v.size() == 0) throw Error(where(file_, v, key_path(key)) + ": " + at + " must be a list of " + what);
    YAML::Node recorded(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const YAML::Node pt = v[i];
      const std::string entry = where(file_, pt, key_path(key)) + ": " + at + " entry " + std::to_string(i + 1);
      if (!pt.IsSequence() || pt.size() != 2) throw Error(entry + " must be " + what);
      double a = 0, b = 0;
      try {
        a = pt[0].as<double>(), b = pt[1].as<double>();
      } catch (const YAML::Exception&) {
        throw Error(entry + " must hold numbers");
      }
      if (!std::isfinite(a) || !std::isfinite(b)) throw Error(entry + " must hold finite numbers");
      if (!out.empty() && !(a > out.back().first)) throw Error(entry + ": " + ascending + " must ascend");
      out.emplace_back(a, b);
      YAML::Node o(YAML::NodeType::Sequence);
      o.push_back(a), o.push_back(b);
      o.SetStyle(YAML::EmitterStyle::Flow);
      recorded.push_back(o);
    }
    resolved_[key] = recorded;
    return out;
  }

  bool given() const { return node_ && !node_.IsNull() && node_.size() > 0; }
  YAML::Node node() const { return node_; }
  void record(const std::string& key, const std::string& value) { resolved_[key] = value; }
  void record_node(const std::string& key, const YAML::Node& value) { resolved_[key] = value; }

  Section section(const std::string& key, bool required = false) {
    YAML::Node v = get(key, required);
    YAML::Node out(YAML::NodeType::Map);
    resolved_[key] = out;
    return Section(file_, v, key_path(key), out);
  }

  // A list of maps, each read by `read(Section&)`.
  template <class Fn>
  void list(const std::string& key, Fn read) {
    YAML::Node v = get(key, false);
    YAML::Node out(YAML::NodeType::Sequence);
    if (v && !v.IsNull()) {
      if (!v.IsSequence())
        throw Error(where(file_, v, key_path(key)) + ": key '" + key_path(key) + "' must be a list");
      for (std::size_t i = 0; i < v.size(); ++i) {
        YAML::Node item(YAML::NodeType::Map);
        Section s(file_, v[i], key_path(key) + "[" + std::to_string(i) + "]", item);
        read(s);
        s.done();
        out.push_back(item);
      }
    }
    resolved_[key] = out;
  }

  // A key of this section that is close to `key` and not one the section knows (a misspelling of it),
  // on a line of its own: "\n  FILE:LINE: unknown key 'a.b' (did you mean 'c'?)"; "" if none.
  std::string misspelt(const std::string& key) const {
    if (!node_ || !node_.IsMap()) return "";
    auto distance = [](const std::string& a, const std::string& b) {  // Levenshtein
      std::vector<std::size_t> row(b.size() + 1);
      for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
      for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
          const std::size_t up = row[j];
          row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
          diagonal = up;
        }
      }
      return row[b.size()];
    };
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      const std::string k = it->first.as<std::string>();
      if (k != key && !seen_.count(k) && distance(k, key) <= std::max<std::size_t>(2, key.size() / 4))
        return "\n  " + where(file_, it->first, key_path(k)) + ": unknown key '" + key_path(k) + "' (did you mean '" +
               key + "'?)";
    }
    return "";
  }

  void done() const {
    if (!node_ || node_.IsNull()) return;
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      std::string k = it->first.as<std::string>();
      if (!seen_.count(k))
        throw Error(where(file_, it->first, key_path(k)) + ": unknown key '" + key_path(k) + "'");
    }
  }

 private:
  double as_number(const YAML::Node& v, const std::string& key) const {
    try {
      if (!v.IsScalar()) throw YAML::BadConversion(v.Mark());
      return v.as<double>();
    } catch (const YAML::BadConversion&) {
      throw Error(where(file_, v, key_path(key)) + ": key '" + key_path(key) + "' must be a number");
    }
  }

  std::string file_;
  YAML::Node node_;
  std::string path_;
  YAML::Node resolved_;
  std::set<std::string> seen_;
};

double unit_length(const std::string& unit) {
  static const std::map<std::string, double> units{{"m", 1.0}, {"mm", 1e-3}, {"cm", 1e-2}, {"in", 0.0254}};
  return units.at(unit);
}

// The unit of a CAD file as the section gives it (`unit`, default `fallback`). OpenCASCADE reads STEP and IGES
// in millimetres, converting from the unit the file declares, so any other unit would scale such a file
// twice: a millimetre STEP at `cm` came out 10x, an inch STEP at `in` 25.4x (6.3 litres for a 20 mm
// billet, accepted). Refused by key.
double cad_unit(Section& s, const std::string& cad, const std::string& fallback, const char* inherited = "the default") {
  const std::string unit = s.text("unit", fallback, {"m", "mm", "cm", "in"});
  if (unit != "mm" && declares_its_unit(lower_extension(cad)))
    throw Error(s.where_of("unit") + " = " + unit + (s.has("unit") ? "" : std::string(" (") + inherited + ")") + ": " +
                std::filesystem::path(cad).filename().string() + " is read in millimetres whatever unit it declares "
                "(OpenCASCADE converts STEP and IGES), so its unit must be mm");
  return unit_length(unit);
}

// --set key.path=value; a list entry is named by its index: dies[0].friction=0.2.
void apply_override(YAML::Node root, const Override& o, const std::string& file) {
  const std::string where = file + ": --set " + o.path;
  std::vector<std::string> keys;
  std::stringstream ss(o.path);
  for (std::string k; std::getline(ss, k, '.');) keys.push_back(k);
  YAML::Node node = root;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    std::string key = keys[i];
    long index = -1;  // key[index]: an entry of the list `key`
    if (const auto open = key.find('['); open != std::string::npos) {
      char* end = nullptr;
      index = std::strtol(key.c_str() + open + 1, &end, 10);
      if (open == 0 || index < 0 || end == key.c_str() + open + 1 || std::string(end) != "]")
        throw Error(where + ": '" + key + "' is not a key or a list entry like dies[0]");
      key = key.substr(0, open);
      const YAML::Node list = node[key];
      if (!list || !list.IsSequence() || std::size_t(index) >= list.size())
        throw Error(where + ": the scene's '" + key + "' has " +
                    std::to_string(list && list.IsSequence() ? list.size() : 0) + " entries (from " + key + "[0])");
    }
    YAML::Node next = index >= 0 ? node[key][std::size_t(index)] : node[key];
    if (i + 1 == keys.size()) {  // the value
      try {
        next = YAML::Load(o.value);  // (a yaml-cpp node assigns through to the deck)
      } catch (const YAML::Exception&) {
        throw Error(where + "=" + o.value + ": not a valid value");
      }
      return;
    }
    if (next && !next.IsNull() && !next.IsMap()) throw Error(where + ": '" + keys[i] + "' is not a section");
    if (!next || next.IsNull()) {
      if (index >= 0) throw Error(where + ": '" + keys[i] + "' is not a section");
      node[key] = YAML::Node(YAML::NodeType::Map);
      next = node[key];
    }
    node.reset(next);
  }
}

// A prescribed motion (dies, prescribed faces): `direction` and a constant `speed`, a piecewise-linear
// `curve` of [time, stroke] pairs or a crank press; for a die (`press`) also a hammer's or screw
// press's `blow` or a `hydraulic` press.
DieMotion read_motion(Section& owner, bool press) {
  DieMotion motion;
  Section m = owner.section("motion", true);
  motion.direction = m.vec3("direction", std::nullopt, true);
  motion.curve = PiecewiseLinear(m.pairs("curve", "[time, stroke]", "the times"));
  int kinds = 0;  // curve, crank, blow, hydraulic: one at most
  for (const char* key : {"curve", "crank", "blow", "hydraulic"})
    if (m.get(key, false)) {
      if (!press && (std::string(key) == "blow" || std::string(key) == "hydraulic"))
        throw Error(m.where_of(key) + ": a press drives dies only; a prescribed face follows a time law");
      if (++kinds > 1) throw Error(m.where_of(key) + ": 'curve', 'crank', 'blow' and 'hydraulic' exclude each other");
    }
  // a curve, a crank or a blow sets the die's speed itself: a `speed` beside it is refused by name (0,
  // as the resolved scene records it, is none)
  const auto no_speed = [&](const std::string& by) {
    const double speed = m.number("speed", 0.0, {});
    if (speed != 0) throw Error(m.where_of("speed") + ": the die's speed follows its '" + by + "'; give one or the other");
    return speed;
  };
  if (m.get("blow", false)) {  // a hammer or screw press
    motion.speed = no_speed("blow");
    Section b = m.section("blow", true);
    DieMotion::Ram& r = motion.ram;
    r.energy = b.number("energy", std::nullopt, {0, 1e9, true, false});
    r.mass = b.number("ram_mass", std::nullopt, {0, 1e7, true, false});
    r.efficiency = b.number("efficiency", 1.0, {0, 1, true, false});
    r.blows = b.integer("count", 1, 1, 1000);
    b.done();
  } else if (m.get("hydraulic", false)) {  // a hydraulic press: its speed, up to its force limit
    motion.speed = m.number("speed", std::nullopt, {0, 1e4, true, false});
    Section h = m.section("hydraulic", true);
    DieMotion::Ram& r = motion.ram;
    r.force_limit = h.number("force_limit", std::nullopt, {0, 1e12, true, false});
    r.mass = h.number("ram_mass", std::nullopt, {0, 1e7, true, false});
    r.power_limit = h.number("power_limit", 0.0, {0, 1e12});
    r.stroke = h.number("stroke", 0.0, {0, 100});
    h.done();
  } else if (m.get("crank", false)) {  // a mechanical press
    motion.speed = no_speed("crank");
    Section c = m.section("crank", true);
    DieMotion::Crank& k = motion.crank;
    k.radius = c.number("radius", std::nullopt, {0, 10, true, false});
    k.rod = c.number("rod", std::nullopt, {0, 100, true, false});
    if (!(k.rod > k.radius))
      throw Error(c.where_of("rod") + ": the connecting rod must be longer than the crank radius (" + std::to_string(k.radius) + " m)");
    k.strokes_per_minute = c.number("strokes_per_minute", std::nullopt, {0, 1e4, true, false});
    k.start_angle = c.number("start_angle", 0.0, {0, 180, false, true}) * M_PI / 180;
    c.done();
  } else if (!motion.curve.empty()) {
    motion.speed = no_speed("curve");
  } else {
    motion.speed = m.number("speed", std::nullopt, {0, 1e4});
  }
  m.done();
  return motion;
}

}  // namespace

Override parse_override(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw Error("--set '" + text + "': expected key.path=value");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

double minimum_dilation(const std::string& basis) { return basis == "quadratic" ? 2.5 : 1.5; }

namespace {
Scene load_scene_checked(const std::filesystem::path& file, const std::vector<Override>& overrides, Side side);
}

Scene load_scene(const std::filesystem::path& file, const std::vector<Override>& overrides, Side side) {
  struct Paths {  // this read's --set paths only
    Paths() { overridden_paths().clear(); }
    ~Paths() { overridden_paths().clear(); }
  } paths;
  try {
    return load_scene_checked(file, overrides, side);
  } catch (const YAML::Exception& e) {  // anything yaml-cpp refuses that the checks above did not name
    throw Error(file.string() + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

namespace {
// The body of geometry.bodies that the list entry `b` names by its key `name`; one error naming the key if none.
Scene::Body& named_body(Scene& s, Section& b) {
  const std::string named = b.text("name", std::nullopt);
  auto it = std::find_if(s.bodies.begin(), s.bodies.end(), [&](const Scene::Body& o) { return o.name == named; });
  if (it == s.bodies.end()) throw Error(b.where_of("name") + ": no body '" + named + "' in geometry.bodies");
  return *it;
}

// The material keys of the map `key` of `parent` (the part's `material`, a body's own), read over the
// keys of the file its `library` names (geometry/materials/, relative to the scene's folder `dir`).
Material read_material(Section& parent, const std::string& key, const std::filesystem::path& dir, const std::string& name) {
  std::string library;
  const std::string path = parent.key_path(key);
  YAML::Node mat = parent.node() ? parent.node()[key] : YAML::Node();
  if (mat && mat.IsMap() && mat["library"]) {
    std::filesystem::path p(mat["library"].as<std::string>());
    library = (p.is_absolute() ? p : (dir / p)).lexically_normal().string();
    YAML::Node keys;
    try {
      keys = YAML::LoadFile(library);
    } catch (const YAML::Exception&) {
      throw Error(where(name, mat["library"], path + ".library") + ": key '" + path + ".library': cannot read '" + library + "'");
    }
    if (!keys.IsMap() || !keys["material"] || !keys["material"].IsMap())
      throw Error(library + ": a material library file holds one map, 'material:' with its keys");
    for (auto it = keys["material"].begin(); it != keys["material"].end(); ++it)
      if (!mat[it->first.as<std::string>()]) mat[it->first.as<std::string>()] = it->second;
  }
  try {
    Section m = parent.section(key, true);
    Material o;
    if (!library.empty()) m.text("library", std::nullopt), m.record("library", library);
    std::string model =
        m.text("model", std::nullopt, {"elastic", "j2_linear", "j2_power", "johnson_cook", "hansel_spittel", "table"});
    o.model = model == "elastic"          ? MaterialModel::elastic
              : model == "j2_power"       ? MaterialModel::j2_power
              : model == "johnson_cook"   ? MaterialModel::johnson_cook
              : model == "hansel_spittel" ? MaterialModel::hansel_spittel
              : model == "table"          ? MaterialModel::table
                                          : MaterialModel::j2_linear;
    o.density = m.number("density", std::nullopt, {0, 1e6, true, false});
    o.youngs_modulus = m.number("youngs_modulus", std::nullopt, {0, 1e13, true, false});
    o.poisson_ratio = m.number("poisson_ratio", std::nullopt, {-1, 0.5, true, true});
    if (o.model == MaterialModel::j2_linear) {
      o.yield_stress = m.number("yield_stress", std::nullopt, {0, 1e12, true, false});
      o.hardening_modulus = m.number("hardening_modulus", 0.0, {0, 1e13});
    }
    if (o.model == MaterialModel::j2_power) {
      o.strength = m.number("strength", std::nullopt, {0, 1e12, true, false});
      o.reference_strain = m.number("reference_strain", std::nullopt, {0, 10, true, false});
      o.exponent = m.number("exponent", std::nullopt, {0, 1});
      o.yield_stress = o.strength * std::pow(o.reference_strain, o.exponent);
    }
    if (o.model == MaterialModel::johnson_cook) {  // Johnson & Cook (1983); temperatures in kelvin
      o.yield_stress = m.number("yield_stress", std::nullopt, {0, 1e12, true, false});
      o.hardening_coefficient = m.number("hardening_coefficient", std::nullopt, {0, 1e12});
      o.hardening_exponent = m.number("hardening_exponent", std::nullopt, {0, 1, true, true});
      o.rate_coefficient = m.number("rate_coefficient", std::nullopt, {0, 1});
      o.reference_strain_rate = m.number("reference_strain_rate", 1.0, {0, 1e9, true, false});
      o.thermal_exponent = m.number("thermal_exponent", std::nullopt, {0, 10, true, false});
      o.melting_temperature = m.number("melting_temperature", std::nullopt, {0, 5000, true, false});
      o.room_temperature = m.number("room_temperature", 293.15, {0, o.melting_temperature, true, false});
    }
    if (o.model == MaterialModel::hansel_spittel) {  // Hansel & Spittel (1979), T in Celsius in the law
      o.hs_a = m.number("coefficient", std::nullopt, {0, 1e13, true, false});
      const char* names[9] = {"m1", "m2", "m3", "m4", "m5", "", "m7", "m8", "m9"};
      for (int i = 0; i < 9; ++i)
        if (i != 5) o.hs_m[i] = m.number(names[i], i < 3 ? std::nullopt : std::optional<double>(0.0), {-100, 100});
      o.minimum_strain = m.number("minimum_strain", 0.01, {0, 1, true, false});
      o.minimum_strain_rate = m.number("minimum_strain_rate", 0.01, {0, 1e6, true, false});
      o.strain_offset = m.number("strain_offset", 0.0, {0, 1});
      o.strain_rate_offset = m.number("strain_rate_offset", 0.0, {0, 100});
      o.melting_temperature = m.number("melting_temperature", 0.0, {0, 5000});
      o.room_temperature = m.number("room_temperature", 293.15, {0, 1e4, true, false});
    }
    if (o.model == MaterialModel::table) {  // shared/flow_table.hpp: the file's checks name its rows
      std::filesystem::path p(m.text("table", std::nullopt));
      const std::string file = (p.is_absolute() ? p : (dir / p)).lexically_normal().string();
      m.record("table", file);
      o.table = std::make_shared<const FlowTable>(read_flow_table(file));
      o.melting_temperature = m.number("melting_temperature", 0.0, {0, 5000});
      o.room_temperature = m.number("room_temperature", 293.15, {0, 1e4, true, false});
    }
    // the thermal keys of every model: the rate-dependent laws' flow stress needs the temperature
    const bool jc = o.model == MaterialModel::johnson_cook || o.model == MaterialModel::hansel_spittel ||
                    o.model == MaterialModel::table;
    // a property as a table of temperature, [[T K, value], ...], or none; `plain` the constant's key
    auto table = [&](const std::string& key, const std::string& what, double most, const char* plain) {
      const auto points = m.pairs(key, "[temperature K, " + what + "]", "the temperatures");
      const std::string at = name + ": key '" + m.key_path(key) + "'";
      for (const auto& [T, v] : points)
        if (!(T > 0 && v > 0 && v <= most))
          throw Error(at + ": temperatures must be positive (kelvin), each " + what + " in (0, " + std::to_string(long(most)) + "]");
      if (!points.empty() && plain && m.get(plain, false))
        throw Error(at + " and '" + m.key_path(plain) + "' exclude each other");
      return PiecewiseLinear(points);
    };
    o.specific_heat_table = table("specific_heat_table", "specific heat J/(kg K)", 1e5, "specific_heat");
    o.specific_heat = o.specific_heat_table.empty()
                          ? m.number("specific_heat", jc ? std::nullopt : std::optional<double>(0.0), {0, 1e5, jc, false})
                          : o.specific_heat_table.front();  // temperature on
    if (o.thermal()) {
      o.taylor_quinney = m.number("taylor_quinney", 0.9, {0, 1});
      o.conductivity_table = table("conductivity_table", "conductivity W/(m K)", 1e4, "conductivity");
      o.conductivity = o.conductivity_table.empty() ? m.number("conductivity", 0.0, {0, 1e4})
                                                    : o.conductivity_table.front();  // conduction on
      o.density_table = table("density_table", "density kg/m^3", 1e6, "thermal_expansion");
      if (o.density_table.empty()) o.thermal_expansion = m.number("thermal_expansion", 0.0, {0, 1e-3});
    } else {
      for (const char* key : {"taylor_quinney", "conductivity", "conductivity_table", "thermal_expansion", "density_table"})
        if (m.get(key, false))
          throw Error(name + ": key '" + m.key_path(key) + "' needs '" + m.key_path("specific_heat") + "' (the temperature it acts on)");
    }
    m.done();
    return o;
  } catch (const Error& e) {  // a key the library gave: name the library too
    if (library.empty()) throw;
    throw Error(std::string(e.what()) + " (with " + path + ".library " + library + ")");
  }
}

// Multi-rate steps hold each point's state over its own step; what needs the state of every point at
// every step, or the length of a point's own step, is not built for them yet. The reason a scene cannot
// take them, or "" where it can.
std::string subcycling_refusal(const Scene& s) {
  if (s.discretization.integration != "gauss" || s.discretization.volumetric != "fbar")
    return "'discretization.integration' other than gauss with 'volumetric' = fbar";
  if (s.time.stable_step != "cells") return "'time.stable_step' = " + s.time.stable_step;
  if (s.reference_updates.strain > 0) return "'reference_updates.strain' > 0";
  if (!s.bodies.empty() || s.contact.self) return "'geometry.bodies' or 'contact.self' (the part's own contact)";
  auto rate_or_heat = [](const Material& m) {
    return m.thermal() || m.model == MaterialModel::johnson_cook || m.model == MaterialModel::hansel_spittel ||
           m.model == MaterialModel::table;
  };
  if (rate_or_heat(s.material)) return "a rate-dependent material or a temperature ('material')";
  if (!s.dies.empty() || !s.rigid_walls.empty()) return "dies or rigid walls (a particle's first touch)";
  return "";
}

// time.subcycling "auto" (0 here, the default) takes the largest ratio, 16, where the scene allows
// multi-rate steps and 1 where it does not; a ratio asked for where it cannot be is one error naming the key.
// The resolved deck keeps "auto", so that a case's deck read again with other keys set resolves again.
void resolve_subcycling(Scene& s, YAML::Node resolved_time) {
  const std::string why_not = subcycling_refusal(s);
  if (s.time.subcycling == 0) {
    s.time.subcycling = why_not.empty() ? 16 : 1;
    resolved_time["subcycling"] = "auto";
  } else if (s.time.subcycling > 1 && !why_not.empty()) {
    throw Error(s.file.string() + ": key 'time.subcycling' = " + std::to_string(s.time.subcycling) +
                " cannot be combined with " + why_not + " (not built yet; docs/scene.md)");
  }
}

Scene load_scene_checked(const std::filesystem::path& file, const std::vector<Override>& overrides, Side side) {
  const std::string name = file.string();
  YAML::Node root;
  require_file(name, "scene file");
  try {
    root = YAML::LoadFile(name);
  } catch (const YAML::BadFile&) {
    throw Error(name + ": cannot open the scene file");
  } catch (const YAML::ParserException& e) {
    throw Error(name + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw Error(name + ": the scene must be a YAML map of sections");
  for (const auto& o : overrides) {
    // rkprep's keys: the part, its discretization, and which dies there are and their CAD (prep_hash);
    // a die's friction, motion and force factor are the solver's
    const std::string& k = o.path;
    const bool die_key = k.rfind("dies", 0) == 0;
    const bool die_solver_key = die_key && (k.find("].friction") != std::string::npos ||
                                            k.find("].shear_factor") != std::string::npos ||
                                            k.find("].motion") != std::string::npos ||
                                            k.find("].force_factor") != std::string::npos ||
                                            k.find("].temperature") != std::string::npos ||
                                            k.find("].heat_transfer") != std::string::npos ||
                                            k.find("].friction_heat_share") != std::string::npos);
    const bool prep_key = k.rfind("geometry.", 0) == 0 || k.rfind("discretization.", 0) == 0 || (die_key && !die_solver_key);
    if (side == Side::solve && prep_key)
      throw Error("--set " + o.path + ": this key is used by rkprep; re-run rkprep with it");
    apply_override(root, o, name);
    overridden_paths().insert(o.path);
  }

  Scene s;
  s.file = file;
  s.dir = std::filesystem::absolute(file).parent_path();
  YAML::Node resolved(YAML::NodeType::Map);
  Section top(name, root, "", resolved);

  {
    Section g = top.section("geometry", true);
    std::string cad = g.text("cad", std::nullopt);
    std::filesystem::path p(cad);
    s.geometry.cad = (p.is_absolute() ? p : (s.dir / p)).lexically_normal().string();
    g.record("cad", s.geometry.cad);  // the resolved deck holds the absolute path
    const std::string unit = g.text("unit", "m", {"m", "mm", "cm", "in"});
    s.geometry.unit = cad_unit(g, s.geometry.cad, "m");
    g.list("bodies", [&](Section& b) {
      Scene::Body body;
      body.name = b.name(std::nullopt);
      if (body.name == "part" || std::any_of(s.bodies.begin(), s.bodies.end(), [&](const Scene::Body& o) { return o.name == body.name; }))
        throw Error(b.where_of("name") + ": '" + body.name + "' names the part or another body");
      std::filesystem::path c(b.text("cad", std::nullopt));
      body.cad = (c.is_absolute() ? c : (s.dir / c)).lexically_normal().string();
      b.record("cad", body.cad);
      body.unit = cad_unit(b, body.cad, unit, "from geometry.unit");
      s.bodies.push_back(body);
    });
    if (s.bodies.size() + 1 > std::size_t(kMaxBodies))  // the part's and the bodies' ids in 7 bits of particles/flags
      throw Error(g.where_of("bodies") + ": at most " + std::to_string(kMaxBodies - 1) + " bodies beside the part");
    g.done();
  }
  {
    Section d = top.section("discretization", true);
    auto& o = s.discretization;
    o.spacing = d.number("spacing", std::nullopt, {0, 10, true, false});
    o.kernel = d.text("kernel", o.kernel, {"cubic_bspline", "quartic_spline"});
    o.basis = d.text("basis", o.basis, {"linear", "quadratic"});
    o.dilation = d.number("dilation", o.dilation, {0, 10, true, false});
    if (o.dilation < minimum_dilation(o.basis))
      throw Error(name + ": key 'discretization.dilation' = " + std::to_string(o.dilation) +
                  " gives a support too small for the " + o.basis + " basis (minimum " +
                  std::to_string(minimum_dilation(o.basis)) + ")");
    o.integration = d.text("integration", o.integration, {"gauss", "nodal"});
    o.gauss_order = d.integer("gauss_order", o.gauss_order, 1, 3);
    o.cell_rule = d.text("cell_rule", o.cell_rule, {"gauss", "four_point", "six_point"});
    if (o.integration == "nodal" && o.cell_rule != "gauss")
      throw Error(name + ": key 'discretization.cell_rule' = " + o.cell_rule + " places the points of Gauss cells, "
                  "which 'discretization.integration' = nodal does not use; leave it out or use gauss");
    // (2, the default, is what a resolved scene records whatever the integration: only another order is
    // refused; with a four- or six-point rule the order is the tetrahedra's, so used)
    if (o.gauss_order != 2 && o.integration == "nodal")
      throw Error(name + ": key 'discretization.gauss_order' = " + std::to_string(o.gauss_order) + " sets the Gauss cells' "
                  "points, which 'discretization.integration' = nodal does not use; leave it out or use gauss");
    o.volumetric = d.text("volumetric", o.volumetric, {"fbar", "none"});
    o.ebc_method = d.text("ebc_method", o.ebc_method, {"nodal", "transformation"});
    o.jitter = d.number("jitter", o.jitter, {0, 0.5, false, true});
    if (!s.bodies.empty() && o.integration == "nodal")
      throw Error(name + ": key 'geometry.bodies' cannot be combined with 'discretization.integration' = nodal (its "
                  "smoothing cells do not know the bodies); use gauss");
    d.done();
  }
  s.material = read_material(top, "material", s.dir, name);
  top.list("bodies", [&](Section& b) {  // a body's own material (the part's where it names none)
    Scene::Body& body = named_body(s, b);
    if (body.material) throw Error(b.where_of("name") + ": body '" + body.name + "' is listed twice");
    body.material = std::make_shared<const Material>(read_material(b, "material", s.dir, name));
    if (s.material.thermal() || body.material->thermal())  // (the rate- and temperature-dependent laws need it)
      throw Error(b.where_of("material") + ": a body's own material is offered without temperature only "
                  "(material.specific_heat and the laws that need it): the heat model holds one material; "
                  "leave it out and the body takes the part's");
  });
  {
    Section ic = top.section("initial_conditions");
    s.initial.velocity = ic.vec3("velocity", Vec3{0, 0, 0});
    ic.list("bodies", [&](Section& b) {  // each body's own velocity (the part's is `velocity` above)
      named_body(s, b).velocity = b.vec3("velocity", Vec3{0, 0, 0});
    });
    Section grad = ic.section("velocity_gradient");  // rows: the gradients of v_x, v_y, v_z
    for (int i = 0; i < 3; ++i) {
      const Vec3 row = grad.vec3(std::string(1, char('x' + i)), Vec3{0, 0, 0});
      for (int j = 0; j < 3; ++j) s.initial.velocity_gradient[3 * i + j] = row[j];
    }
    grad.done();
    if (s.material.thermal()) {
      // kelvin: a billet at 1150 C written as 1150 would be 877 C, and one at 1250 C as 1250 K is
      // below the melting point of steel, so only the melting point catches a Celsius slip there
      const bool melts = s.material.melting_temperature > 0;
      s.initial.temperature = ic.number("temperature", s.material.room_temperature,
                                        {0, melts ? s.material.melting_temperature : 1e4, true, false});
      ic.list("temperature_regions", [&](Section& p) {
        Scene::Initial::Region r;
        r.lo = p.vec3("lo", std::nullopt), r.hi = p.vec3("hi", std::nullopt);
        for (int i = 0; i < 3; ++i)
          if (!(r.hi[i] > r.lo[i]))
            throw Error(name + ": key 'initial_conditions.temperature_regions': a box's hi must exceed its lo on every axis");
        r.temperature = p.number("temperature", std::nullopt, {0, melts ? s.material.melting_temperature : 1e4, true, false});
        s.initial.temperature_regions.push_back(r);
      });
    } else {  // (else 'unknown key', for keys that scene.md lists)
      for (const char* key : {"temperature", "temperature_regions"})
        if (const YAML::Node v = ic.get(key, false); v && !v.IsNull())
          throw Error(ic.where_of(key) + " needs a temperature: 'material.specific_heat' (or a material library with it)");
    }
    ic.done();
  }
  {
    Section l = top.section("loads");
    s.loads.gravity = l.vec3("gravity", Vec3{0, 0, 0});
    l.done();
  }
  {
    Section b = top.section("boundaries");
    b.list("symmetry_planes", [&](Section& p) {
      s.symmetry_planes.push_back({p.vec3("point", std::nullopt), p.vec3("normal", std::nullopt, true)});
    });
    auto face = [&](Section& p, const std::string& kind, std::size_t count) {
      EssentialFace f;
      f.name = p.unique_name(kind, count, "faces", s.fixed_faces, s.prescribed_faces);
      f.point = p.vec3("point", std::nullopt);
      f.normal = p.vec3("normal", std::nullopt, true);
      return f;
    };
    b.list("fixed_faces", [&](Section& p) { s.fixed_faces.push_back(face(p, "fixed", s.fixed_faces.size())); });
    b.list("prescribed_faces", [&](Section& p) {
      EssentialFace f = face(p, "prescribed", s.prescribed_faces.size());
      f.motion = read_motion(p, false);
      s.prescribed_faces.push_back(f);
    });
    b.list("rigid_walls", [&](Section& p) {
      RigidWall w;
      w.name = p.unique_name("wall", s.rigid_walls.size(), "rigid walls or faces", s.rigid_walls, s.fixed_faces,
                             s.prescribed_faces);
      w.point = p.vec3("point", std::nullopt);
      w.normal = p.vec3("normal", std::nullopt, true);
      s.rigid_walls.push_back(w);
    });
    b.done();
  }
  std::vector<SymmetryPlane> planes = s.symmetry_planes;
  top.list("dies", [&](Section& d) {
    Die die;
    die.name = d.unique_name(std::nullopt, 0, "dies, rigid walls or faces", s.dies, s.rigid_walls, s.fixed_faces,
                             s.prescribed_faces);
    std::filesystem::path p(d.text("cad", std::nullopt));
    die.cad = (p.is_absolute() ? p : (s.dir / p)).lexically_normal().string();
    d.record("cad", die.cad);
    die.unit = cad_unit(d, die.cad, "m");
    die.friction = d.number("friction", 0.0, {0, 10});
    die.shear_factor = d.number("shear_factor", 0.0, {0, 1});
    die.motion = read_motion(d, true);
    // A ram's mass meets the whole part's reaction; a symmetry plane across its motion would halve
    // the travel it sees (the modeled die moves half the ram's stroke)
    for (const auto& pl : planes)
      if (die.motion.driven() && std::abs(dot(pl.normal, die.motion.direction)) > 1e-9)
        throw Error(where(name, d.get("name", false), "dies") + ": die '" + die.name +
                    "' is driven by its press; a symmetry plane across its motion cannot model it: model the full "
                    "height on a rigid wall or a second die");
    // Full part / modeled part: each symmetry plane whose normal is normal to the motion mirrors the
    // die force; two orthogonal such planes make a quarter (x4). Other sectors must say it. (Normal:
    // a dot product of unit vectors under 1e-9, their round-off.)
    std::vector<Vec3> mirror;
    for (const auto& pl : planes)
      if (std::abs(dot(pl.normal, die.motion.direction)) < 1e-9) mirror.push_back(pl.normal);
    double factor = mirror.size() == 0 ? 1 : mirror.size() == 1 ? 2 : 0;
    if (mirror.size() == 2 && std::abs(dot(mirror[0], mirror[1])) < 1e-9) factor = 4;
    YAML::Node given = d.get("force_factor", false);
    if (given && !given.IsNull()) factor = d.number("force_factor", std::nullopt, {1, 1e6});
    else if (factor == 0)
      throw Error(where(name, d.get("name", false), "dies") + ": die '" + die.name +
                  "': the symmetry planes make a sector; give dies[].force_factor (full part / modeled part)");
    else d.number("force_factor", factor, {1, 1e6});
    die.force_factor = factor;
    if (!s.material.conducting())
      for (const char* key : {"heat_transfer", "temperature", "friction_heat_share"})
        if (d.get(key, false))
          throw Error(where(name, d.get(key, false), "dies") + ": key 'dies[]." + key +
                      "' needs 'material.conductivity' (heat transfer through the part)");
    if (s.material.conducting()) {
      die.heat_transfer = d.number("heat_transfer", 0.0, {0, 1e7});
      die.temperature = d.number("temperature", s.material.room_temperature, {0, 1e4, true, false});
      die.friction_heat_share = d.number("friction_heat_share", 0.5, {0, 1});
    }
    s.dies.push_back(die);
  });
  {
    Section t = top.section("thermal");
    auto& o = s.thermal;
    if (!s.material.conducting() && t.given())
      throw Error(name + ": section 'thermal' needs 'material.conductivity' (heat transfer through the part)");
    if (s.material.conducting()) {
      o.ambient_temperature = t.number("ambient_temperature", s.material.room_temperature, {0, 1e4, true, false});
      o.convection = t.number("convection", 0.0, {0, 1e7});
      o.emissivity = t.number("emissivity", 0.0, {0, 1});
      // 20 by default (docs/decisions.md, "The thermal update's interval"): within 0.022 K of an
      // update every step in hot upsetting, the thermal phase 2.4 % of the step
      o.max_steps_per_update = t.integer("max_steps_per_update", 20, 0, 1000000);
      t.list("fixed_faces", [&](Section& p) {
        TemperatureFace f;
        f.name = p.name("temperature" + std::to_string(o.fixed_faces.size()));
        f.point = p.vec3("point", std::nullopt);
        f.normal = p.vec3("normal", std::nullopt, true);
        f.temperature = p.number("temperature", std::nullopt, {0, 1e4, true, false});
        o.fixed_faces.push_back(f);
      });
      t.done();
    }
  }
  {
    Section d = top.section("damage");
    auto criterion = [&](const char* key, bool& on, double& critical) {
      if (!d.given() || !d.get(key, false)) return;  // get() of an absent section is a null node
      on = true;
      Section c = d.section(key);
      critical = c.number("critical", 0.0, {0, 1e3});
      c.done();
    };
    criterion("cockcroft_latham", s.damage.cockcroft_latham, s.damage.cockcroft_latham_critical);
    criterion("brozzo", s.damage.brozzo, s.damage.brozzo_critical);
    if (d.given() && d.get("oyane", false)) {  // with its material constant
      s.damage.oyane = true;
      Section c = d.section("oyane");
      s.damage.oyane_a = c.number("a", std::nullopt, {0, 100, true, false});
      s.damage.oyane_critical = c.number("critical", 0.0, {0, 1e3});
      c.done();
    }
    d.done();
    if (d.given() && !s.damage.on())
      throw Error(name + ": section 'damage' names no criterion (cockcroft_latham, brozzo, oyane)");
  }
  {
    Section c = top.section("contact");
    s.contact.penalty_scale = c.number("penalty_scale", s.contact.penalty_scale, {0, 1, true, false});
    s.contact.self = c.text("self", "false", {"true", "false"}) == "true";
    s.contact.damping = c.number("damping", s.contact.damping, {0, 1, false, true});
    c.done();
  }
  {
    Section r = top.section("reference_updates");
    s.reference_updates.strain = r.number("strain", s.reference_updates.strain, {0, 10});
    s.reference_updates.step_growth = r.number("step_growth", s.reference_updates.step_growth, {1, 10});
    if (s.reference_updates.strain > 0 && s.discretization.ebc_method == "transformation")
      throw Error(name + ": key 'reference_updates.strain' cannot be combined with 'discretization.ebc_method' = "
                  "transformation (its constraint rows are not rebuilt at an update); use nodal");
    if (s.reference_updates.strain > 0 && s.discretization.integration == "nodal")
      throw Error(name + ": key 'reference_updates.strain' cannot be combined with 'discretization.integration' = "
                  "nodal (the smoothing cells are not rebuilt at an update); use gauss");
    r.done();
  }
  {
    Section t = top.section("time", true);
    s.time.end = t.number("end", std::nullopt, {0, 1e6, true, false});
    s.time.cfl = t.number("cfl", s.default_cfl(), {0, 2, true, false});
    // (docs/decisions.md, "The stable step from the highest frequency": not the default yet)
    s.time.stable_step = t.text("stable_step", "cells", {"cells", "frequency"});
    s.time.dwell = t.text("dwell", "auto", {"auto", "off"});
    s.time.output_interval = t.number("output_interval", s.time.end / 10, {0, 1e6, true, false});
    s.time.mass_scaling_dt = t.number("mass_scaling_dt", 0.0, {0, 1});
    // (a step of the whole run scaled the density 4.6e13 times: one step, the die through the part, exit 0)
    if (s.time.mass_scaling_dt >= s.time.end) {
      char text[200];
      std::snprintf(text, sizeof text, " = %g s is not below time.end = %g s: the run would be one step; a quasi-static run "
                    "takes thousands (the upsetting's 3.6e-7 s of 5.1e-3 s)", s.time.mass_scaling_dt, s.time.end);
      throw Error(t.where_of("mass_scaling_dt") + text);
    }
    const YAML::Node ratio = t.get("subcycling", false);
    const bool automatic = !ratio || ratio.IsNull() || (ratio.IsScalar() && ratio.Scalar() == "auto");
    const std::vector<std::string> ratios = {"1", "2", "4", "8", "16"};
    if (!automatic && !(ratio.IsScalar() && std::find(ratios.begin(), ratios.end(), ratio.Scalar()) != ratios.end()))
      throw Error(t.where_of("subcycling") + ": must be auto, 1, 2, 4, 8 or 16 (the largest ratio of a particle's step to the smallest)");
    s.time.subcycling = automatic ? 0 : t.integer("subcycling", std::nullopt, 1, 16);  // 0: auto, resolved once the scene is read
    t.done();
    for (const Die& d : s.dies)  // past bottom dead centre a crank press's ram rises off the part
      if (d.motion.cranked() && s.time.end > d.motion.crank.bottom_dead_centre() * (1 + 1e-12)) {
        char text[200];
        std::snprintf(text, sizeof text, "key 'time.end' = %g s runs past the bottom dead centre of die '%s' at %.9g s; end there or before",
                      s.time.end, d.name.c_str(), d.motion.crank.bottom_dead_centre());
        throw Error(name + ": " + text);
      }
  }
  {
    // on by default (LS-DYNA's 1.5 and 0.06) where compression can be fast; off in a mass-scaled
    // (quasi-static) run, which has no shocks and whose scaled density would inflate q
    Section b = top.section("bulk_viscosity");
    const bool dynamic = s.time.mass_scaling_dt == 0;
    s.bulk_viscosity.quadratic = b.number("quadratic", dynamic ? 1.5 : 0.0, {0, 10});
    s.bulk_viscosity.linear = b.number("linear", dynamic ? 0.06 : 0.0, {0, 1});
    b.done();
  }
  {
    Section o = top.section("output");
    s.output.checkpoint_steps = o.integer("checkpoint_steps", int(s.output.checkpoint_steps), 0, 1000000000);
    s.output.checkpoint_minutes = o.number("checkpoint_minutes", s.output.checkpoint_minutes, {0, 1e6});
    o.list("track", [&](Section& p) {
      Scene::Output::Track t;
      t.name = p.unique_name("p", s.output.track.size(), "tracks", s.output.track);
      t.point = p.vec3("point", std::nullopt);
      s.output.track.push_back(t);
    });
    o.list("flow_lines", [&](Section& p) {
      Scene::Output::FlowLines f;
      f.name = p.unique_name("flow_lines", s.output.flow_lines.size(), "flow lines", s.output.flow_lines);
      f.point = p.vec3("point", std::nullopt);
      f.normal = p.vec3("normal", std::nullopt, true);
      f.direction = p.vec3("direction", std::nullopt, true);
      if (std::abs(dot(f.normal, f.direction)) > 1e-6)
        throw Error(p.where_of("direction") + ": the lines' direction must lie in their plane (normal to 'normal')");
      f.spacing = p.number("spacing", 2 * s.discretization.spacing, {0, 1e3, true, false});
      s.output.flow_lines.push_back(f);
    });
    o.done();
  }
  {
    Section h = top.section("health");
    s.health.max_energy_error = h.number("max_energy_error", s.health.max_energy_error, {0, 1e3, true, false});
    s.health.min_dt_ratio = h.number("min_dt_ratio", s.health.min_dt_ratio, {0, 1});
    s.health.max_symmetry_depth = h.number("max_symmetry_depth", s.health.max_symmetry_depth, {0, 1e3, true, false});
    s.health.max_pressure_ratio = h.number("max_pressure_ratio", s.health.max_pressure_ratio, {0, 1e6});
    h.done();
  }
  top.done();
  resolve_subcycling(s, resolved["time"]);

  YAML::Emitter all;
  all << resolved;
  s.resolved_yaml = std::string(all.c_str()) + "\n";
  YAML::Emitter prep;
  prep << resolved["geometry"] << resolved["discretization"];
  for (const auto& d : s.dies) prep << d.name << d.cad << d.unit;
  s.prep_hash = fnv1a_hex(prep.c_str());
  return s;
}
}  // namespace

}  // namespace rk

namespace rk {

std::vector<std::string> temperature_warnings(const Scene& s) {
  std::vector<std::string> out;
  if (!s.material.thermal()) return out;
  const double melt = s.material.melting_temperature;
  auto check = [&](const std::string& key, double T) {
    char text[240];
    if (T < 273.15) {
      std::snprintf(text, sizeof text, "%s = %g K is %.0f C: temperatures are in kelvin (a Celsius value?)", key.c_str(), T,
                    T - 273.15);
      out.push_back(text);
    } else if (melt > 0 && T >= melt) {
      std::snprintf(text, sizeof text, "%s = %g K is at or above the material's melting temperature %g K (a slip of units?)",
                    key.c_str(), T, melt);
      out.push_back(text);
    }
  };
  // the part's temperatures beyond a property table, whose end values are then held
  const std::pair<const char*, const PiecewiseLinear*> tables[] = {{"specific_heat_table", &s.material.specific_heat_table},
                                                                    {"conductivity_table", &s.material.conductivity_table},
                                                                    {"density_table", &s.material.density_table}};
  auto covered = [&](const std::string& key, double T) {
    for (const auto& [table_key, t] : tables)
      if (!t->empty() && (T < t->points().front().first || T > t->points().back().first)) {
        char text[240];
        std::snprintf(text, sizeof text, "%s = %g K lies outside material.%s (%g to %g K): the table's end value is held",
                      key.c_str(), T, table_key, t->points().front().first, t->points().back().first);
        out.push_back(text);
      }
  };
  auto part = [&](const std::string& key, double T) { check(key, T), covered(key, T); };
  part("initial_conditions.temperature", s.initial.temperature);
  for (std::size_t k = 0; k < s.initial.temperature_regions.size(); ++k)
    part("initial_conditions.temperature_regions[" + std::to_string(k) + "].temperature", s.initial.temperature_regions[k].temperature);
  if (!s.material.density_table.empty()) {
    const double table = s.material.density_table.at(s.initial.temperature);
    if (std::abs(table / s.material.density - 1) > 0.02) {
      char text[240];
      std::snprintf(text, sizeof text,
                    "material.density = %g kg/m^3 is the part's mass density (its CAD's shape at the initial temperature); "
                    "material.density_table gives %g there",
                    s.material.density, table);
      out.push_back(text);
    }
  }
  if (!s.material.conducting()) return out;
  part("thermal.ambient_temperature", s.thermal.ambient_temperature);
  for (const auto& f : s.thermal.fixed_faces) part("thermal.fixed_faces '" + f.name + "'.temperature", f.temperature);
  for (const auto& d : s.dies) part("dies '" + d.name + "'.temperature", d.temperature);
  return out;
}

std::vector<std::string> accuracy_warnings(const Scene& s) {
  std::vector<std::string> out;
  if (s.time.mass_scaling_dt > s.time.end / 100) {
    char text[400];
    std::snprintf(text, sizeof text, "time.mass_scaling_dt = %g s: the run to time.end = %g s takes at most %.0f steps, "
                  "too few for the energy check, which starts at step 100, and for a quasi-static answer (the upsetting "
                  "takes 3.6e-7 s of 5.1e-3 s)", s.time.mass_scaling_dt, s.time.end, std::ceil(s.time.end / s.time.mass_scaling_dt));
    out.push_back(text);
  }
  // A hammer's blow is dynamic: the ram's energy goes into the part in a few milliseconds against the part's own
  // inertia, which mass scaling multiplies
  for (const Die& d : s.dies)
    if (d.motion.blows() && s.time.mass_scaling_dt > 0)
      out.push_back("time.mass_scaling_dt with die '" + d.name + "''s hammer blow: the blow is dynamic, and the scaled density "
                    "changes the part's inertia against the ram; measured (2026-12-08), the shipped blow at 2.5 mm read its "
                    "largest force 587 kN (2.975 mm stroke) at mass_scaling_dt = 5e-6 s (the density x 1146) against 181 kN "
                    "(3.044 mm) without; leave time.mass_scaling_dt at 0 for hammers");
  // (with a four- or six-point rule the order is a tetrahedron's alone, one point or four)
  if (s.discretization.integration == "gauss" && s.discretization.gauss_order == 1 && s.discretization.cell_rule == "gauss")
    out.push_back("discretization.gauss_order = 1: one integration point per cell leaves the cells' hourglass modes "
                  "unresisted; measured (2026-12-06), the frictionless upsetting at 1.25 mm reads its die force 16 % low "
                  "at 50 % reduction and its diameter 19 % large (gauss_order 2: 0.5 % and 0.1 %), and the Taylor bar's "
                  "footprint radius jumps between +0.7 and +2.3 % as the spacing falls from 0.9 to 0.3 mm; gauss_order 2 "
                  "(the default) for forces and shapes");
  if (s.discretization.integration == "gauss" && s.discretization.gauss_order > 1 &&
      s.discretization.volumetric == "none" && s.material.model != MaterialModel::elastic)
    out.push_back("discretization.volumetric = none: without F-bar each cell's points constrain the volume of the "
                  "plastic (isochoric) flow and lock it; measured (2026-12-06), the Taylor bar's footprint radius reads "
                  "5.64 mm against the converged 7.22 mm (-22 %); fbar (the default) for plastic parts");
  if (s.discretization.cell_rule != "gauss" && !s.dies.empty())
    out.push_back("discretization.cell_rule = " + s.discretization.cell_rule + " with dies: validated on the Taylor "
                  "bar's footprint and the upsetting's force (within 0.63 % of the closed form), but it moves die loads "
                  "from the Gauss rule's; measured (2026-12-07) at 2.5 mm, full strokes, the back extrusion's punch work "
                  "-1.3 % (four_point) and -2.3 % (six_point), the wheel forging's -2.3 % and +4.9 % (six_point's points on "
                  "the part's faces touch the dies: 4.6x the Gauss points' contacts); gauss (the default) for die loads");
  const bool penalty = !s.dies.empty() || !s.rigid_walls.empty() || !s.bodies.empty() || s.contact.self;
  if (s.time.stable_step == "frequency" && penalty)
    out.push_back("time.stable_step = frequency with dies, rigid walls, bodies or self-contact: the penalty contact's "
                  "stiffness (contact.penalty_scale x m / dt^2) follows the longer step and softens; measured "
                  "(2026-12-06), the back extrusion at 2.5 mm took 2.6x fewer steps but read its punch work 1.7 % low and "
                  "its 1-mm force means -6.7 to +1.1 % from the cells' step's; `cells` (the default) for die loads");
  return out;
}

// Elastic constants, densities and strengths no metal has: almost always a value in another unit (E in GPa,
// the density in g/cm^3), which runs and gives a wrong answer (E = 71 Pa: the whole run in one step).
std::vector<std::string> material_warnings(const Scene& s) {
  std::vector<std::string> out;
  auto check = [&](const std::string& at, const Material& m) {
    char text[320];
    if (m.youngs_modulus < 1e9) {
      std::snprintf(text, sizeof text, "%s.youngs_modulus = %g Pa is below any metal's (lead: 16 GPa, hot steel near "
                    "its melting point: about 30 GPa): in Pa, not GPa or MPa?", at.c_str(), m.youngs_modulus);
      out.push_back(text);
    }
    if (m.density < 500 || m.density > 25000) {
      std::snprintf(text, sizeof text, "%s.density = %g kg/m^3 is outside any metal's (magnesium 1740, osmium 22590): "
                    "in kg/m^3, not g/cm^3 or kg/mm^3?", at.c_str(), m.density);
      out.push_back(text);
    }
    // A Poisson ratio near 1/2 stiffens the volumetric wave, c^2 = E (1 - nu) / ((1 + nu) (1 - 2 nu) rho), and
    // the explicit step falls as 1/c: legal, but slow for no gain in a J2 material, whose plastic flow keeps
    // its volume whatever the elastic nu (and F-bar holds the volume of the cells' points)
    if (m.poisson_ratio > 0.45) {
      const auto wave = [](double nu) { return std::sqrt((1 - nu) / ((1 + nu) * (1 - 2 * nu))); };
      const double faster = wave(m.poisson_ratio) / wave(0.3);
      std::snprintf(text, sizeof text, "%s.poisson_ratio = %g: the volumetric wave runs %.3gx as fast as at 0.3, so the "
                    "run takes about %.3gx the steps; metals are 0.27-0.35 elastically, and the plastic flow keeps its "
                    "volume at any value", at.c_str(), m.poisson_ratio, faster, faster);
      out.push_back(text);
    }
    // the flow stress's scale: the initial yield (linear, Johnson-Cook's A) or the power law's K
    const double strength = m.model == MaterialModel::j2_power ? m.strength
                            : m.model == MaterialModel::j2_linear || m.model == MaterialModel::johnson_cook ? m.yield_stress
                                                                                                             : 0.0;
    const char* key = m.model == MaterialModel::j2_power ? "strength" : "yield_stress";
    if (m.youngs_modulus >= 1e9 && strength > 0.05 * m.youngs_modulus) {
      std::snprintf(text, sizeof text, "%s.%s = %g Pa is %.2g of youngs_modulus = %g Pa, where no metal's exceeds 0.02: "
                    "is one of them in another unit?", at.c_str(), key, strength, strength / m.youngs_modulus, m.youngs_modulus);
      out.push_back(text);
    }
  };
  check("material", s.material);
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].material) check("the material of body '" + s.bodies[b].name + "'", *s.bodies[b].material);
  return out;
}

// More frames than anyone looks at: an interval in another unit, or a slip of the exponent (1e-12 s
// wrote a frame every step, 2 905 frames and 444 MB for 185 particles)
std::vector<std::string> output_warnings(const Scene& s) {
  std::vector<std::string> out;
  const double frames = (s.time.end - s.time.start) / s.time.output_interval;  // (a stage's own)
  if (frames > 1000) {
    char text[320];
    std::snprintf(text, sizeof text, "time.output_interval = %g s asks for %.3g frames over the run's %g s (a frame is "
                  "written at most once a step, each of every particle's fields): a slip of units or of the exponent?",
                  s.time.output_interval, frames, s.time.end - s.time.start);
    out.push_back(text);
  }
  return out;
}

std::vector<std::string> scene_warnings(const Scene& s) {
  std::vector<std::string> out = temperature_warnings(s);
  for (std::string& w : material_warnings(s)) out.push_back(std::move(w));
  for (std::string& w : output_warnings(s)) out.push_back(std::move(w));
  for (std::string& w : accuracy_warnings(s)) out.push_back(std::move(w));
  return out;
}

double DieMotion::Crank::position(double theta) const {
  const double lambda = radius / rod, s = std::sin(theta);
  return radius * (1 - std::cos(theta)) + rod * (1 - std::sqrt(1 - lambda * lambda * s * s));
}

double DieMotion::Crank::bottom_dead_centre() const { return (M_PI - start_angle) / omega(); }

double DieMotion::fastest() const {
  double v = std::abs(speed);
  if (blows()) v = std::max(v, ram.blow_speed());
  for (const auto& [t, s] : curve.points()) v = std::max(v, std::abs(rate(t)));
  if (cranked())  // |ds/dtheta| <= r (1 + r / l) (the rod's term at most r/l of the crank's); times omega
    v = std::max(v, crank.radius * (1 + crank.radius / crank.rod) * crank.omega());
  return v;
}

double DieMotion::reach(double t_end) const {
  if (blows()) return std::numeric_limits<double>::infinity();
  t_end -= start;
  if (hydraulic()) return ram.stroke > 0 ? std::min(ram.stroke, speed * t_end) : speed * t_end;
  if (cranked()) return stroke(std::min(t_end, crank.bottom_dead_centre()));  // rising to bottom dead centre
  double s = stroke(t_end);  // piecewise linear: the farthest at a corner or at the end
  for (const auto& [t, x] : curve.points())
    if (t <= t_end) s = std::max(s, x);
  return s;
}

double DieMotion::stroke(double t) const {
  t -= start;
  if (cranked()) return crank.position(crank.angle(t)) - crank.position(crank.start_angle);
  return curve.empty() ? speed * t : curve.at(t);
}

double DieMotion::rate(double t) const {
  t -= start;
  if (cranked()) {  // ds/dtheta dtheta/dt
    const double theta = crank.angle(t), lambda = crank.radius / crank.rod, s = std::sin(theta);
    return crank.radius * s * (1 + lambda * std::cos(theta) / std::sqrt(1 - lambda * lambda * s * s)) * crank.omega();
  }
  return curve.empty() ? speed : curve.slope_after(t);
}

}  // namespace rk
