// The scene: one YAML input deck, validated in one place (scene.cpp), echoed resolved by rkprep.
// Every key is documented in docs/scene.md. Units are SI except geometry.unit (the CAD's length unit).
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>


#include "flow_table.hpp"
#include "piecewise_linear.hpp"
#include "vec3.hpp"

namespace rk {

struct SymmetryPlane {
  Vec3 point{};
  Vec3 normal{};  // unit
};

struct RigidWall {
  std::string name;
  Vec3 point{};
  Vec3 normal{};  // unit, pointing into the workpiece side
};

// A rigid die: its CAD surface becomes triangles (outward normals), moved by a prescribed motion.
struct DieMotion {
  Vec3 direction{};                               // unit: the pressing direction (stroke is along it)
  double speed = 0;                               // m/s, constant (when `curve` is empty)
  PiecewiseLinear curve;                          // (time s, stroke m), or empty
  // a mechanical (crank) press: the slider-crank law s(theta) = r (1 - cos theta) + l (1 - sqrt(1 -
  // (r/l)^2 sin^2 theta)) below top dead centre, theta = start_angle + 2 pi n t / 60; the stroke is
  // s(theta(t)) - s(start_angle), so the die starts where the scene's CAD puts it
  struct Crank {
    double radius = 0, rod = 0, strokes_per_minute = 0, start_angle = 0;  // m, m, 1/min, rad from top dead centre
    double omega() const { return 2 * M_PI * strokes_per_minute / 60; }  // rad/s
    double angle(double t) const { return start_angle + omega() * t; }
    double position(double theta) const;  // s(theta)
    double bottom_dead_centre() const;    // the time theta reaches pi
  } crank;
  bool cranked() const { return crank.radius > 0; }
  // A die driven by its press's energy or force rather than by time (solver/contact/presses.hpp): the
  // ram, of `mass` (kg: ram and upper die), moves under the press's drive and the part's reaction.
  struct Ram {
    double mass = 0;
    // hammer or screw press: `blows` blows in a row, each bringing `efficiency` x `energy` (J) to the
    // part: the ram meets it at v0 = sqrt(2 efficiency energy / mass) and coasts until it stops
    double energy = 0, efficiency = 1;
    int blows = 0;
    // hydraulic press: the motion's `speed` until the load on the whole part reaches `force_limit` (N);
    // at most `power_limit` (W, 0: none); it stops at `stroke` (m, 0: none)
    double force_limit = 0, power_limit = 0, stroke = 0;
    double blow_speed() const { return std::sqrt(2 * efficiency * energy / mass); }  // v0 (m/s)
  } ram;
  bool blows() const { return ram.blows > 0; }
  bool hydraulic() const { return ram.force_limit > 0; }
  bool driven() const { return blows() || hydraulic(); }  // by the part's reaction: stroke(t) and rate(t) do not apply
  // When the motion begins on the run's clock (s): 0, or for a die new to a stage of a chain the
  // stage's start (solver/stage.hpp). The times of `curve` and `crank` count from it.
  double start = 0;
  double stroke(double t) const;                  // m along `direction` (a motion not driven())
  double rate(double t) const;                    // d stroke / dt
  double fastest() const;                         // the largest |rate| over the motion (m/s)
  // the farthest stroke over [start, t_end] (m); infinite for a blow, which goes as far as its energy takes it
  double reach(double t_end) const;
};

struct Die {
  std::string name;
  std::string cad;      // absolute path
  double unit = 1.0;    // metres per CAD unit
  DieMotion motion;
  double friction = 0;  // Coulomb coefficient mu
  // shear factor m in [0, 1]: tau = m k (k the part's shear yield stress there); with friction > 0
  // as well, the hybrid law tau = min(mu p, m k)
  double shear_factor = 0;
  double force_factor = 1;  // full part / modeled part (symmetry)
  // heat exchange with a part that conducts heat (material.conductivity > 0)
  double temperature = 0;    // K, the die's (held constant)
  double heat_transfer = 0;  // W/(m^2 K), the interface's conductance where the part touches it
  double friction_heat_share = 0.5;  // the share of the friction's heat that goes into the die
};

// A face of the part held by an essential boundary condition: the particles on the plane through
// `point` with normal `normal`. Fixed: all three displacement components zero. Prescribed: the
// displacement along motion.direction follows motion.stroke(t); the other components are free.
struct EssentialFace {
  std::string name;
  Vec3 point{};
  Vec3 normal{};  // unit
  DieMotion motion;
};

enum class MaterialModel { elastic, j2_linear, j2_power, johnson_cook, hansel_spittel, table };

struct Material {
  MaterialModel model = MaterialModel::j2_linear;
  double density = 0;            // kg/m3
  double youngs_modulus = 0;     // Pa
  double poisson_ratio = 0;      // -
  double yield_stress = 0;       // Pa (initial)
  double hardening_modulus = 0;  // Pa (linear isotropic)
  double strength = 0, reference_strain = 0, exponent = 0;  // power law K (eps0 + ep)^n
  // Johnson-Cook (yield_stress is A): (A + B ep^n) (1 + C ln max(rate / rate0, 1)) (1 - T*^m)
  double hardening_coefficient = 0, hardening_exponent = 1;  // B (Pa), n
  double rate_coefficient = 0, reference_strain_rate = 1;    // C, rate0 (1/s)
  double thermal_exponent = 1;                               // m
  double room_temperature = 293.15, melting_temperature = 0; // K (0: none given)
  // Hansel-Spittel: A (Pa) and m1 .. m9 (no m6) with T in Celsius in the law; strain and rate minima
  double hs_a = 0, hs_m[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // hs_m[i - 1] = m_i (hs_m[5] unused)
  double minimum_strain = 0.01, minimum_strain_rate = 0.01;
  double strain_offset = 0, strain_rate_offset = 0;  // the law at (strain + offset, rate + offset)
  // a flow stress table (model table): read and checked with the scene
  std::shared_ptr<const FlowTable> table;
  // temperature (any model; Johnson-Cook requires it): heating by plastic work, dT = taylor_quinney
  // dW_p / (rho c); conduction through the part when conductivity > 0 (else adiabatic); the thermal
  // strain alpha (T - T0), T0 the initial temperature
  double specific_heat = 0;      // J/(kg K); 0: no temperature
  double taylor_quinney = 0.9;   // the share of plastic work that becomes heat
  double conductivity = 0;       // W/(m K)
  PiecewiseLinear conductivity_table;    // k(T) instead (W/(m K))
  PiecewiseLinear specific_heat_table;   // c(T) instead (J/(kg K)): the enthalpy its integral
  double conductivity_at(double T) const { return conductivity_table.empty() ? conductivity : conductivity_table.at(T); }
  double thermal_expansion = 0;  // 1/K, linear
  // rho(T) instead: the stress-free stretch is (rho(T0) / rho(T))^(1/3), and `density` is rho(T0)
  PiecewiseLinear density_table;
  bool thermal() const { return specific_heat > 0; }
  bool conducting() const { return conductivity > 0; }
};

// A face of the part held at a temperature (the particles on the plane, as EssentialFace).
struct TemperatureFace {
  std::string name;
  Vec3 point{};
  Vec3 normal{};  // unit
  double temperature = 0;  // K
};

inline constexpr int kMaxBodies = 128;  // the part and the bodies: their ids fill 7 bits (subdomain.hpp)

struct Scene {
  std::filesystem::path file;  // the YAML it was read from
  std::filesystem::path dir;   // folder of that file: CAD paths are relative to it

  struct Geometry {
    std::string cad;          // path relative to dir
    double unit = 1.0;        // metres per CAD length unit
  } geometry;
  // Further deformable bodies (a striker, an insert, a second billet), of the part's material or their own: each its
  // own CAD (geometry.bodies), meshed at the part's spacing, with its own supports (no shape function
  // spans two bodies) and its own initial velocity (initial_conditions.bodies); the part's geometry.cad
  // is body 0. They meet the part and each other through the part's contact (solver/contact/part_contact.hpp).
  struct Body {
    std::string name;
    std::string cad;    // absolute path
    double unit = 1.0;  // metres per CAD unit
    Vec3 velocity{};    // m/s, uniform
    // its own material (section `bodies`), elastic or J2 without temperature; null: the part's
    std::shared_ptr<const Material> material;
  };
  std::vector<Body> bodies;

  struct Discretization {
    double spacing = 0;       // m, target particle spacing
    double dilation = 2.0;    // support radius / local particle spacing
    std::string kernel = "cubic_bspline";
    std::string basis = "linear";
    std::string integration = "gauss";  // gauss (cells' Gauss points) or nodal (SCNI, one point per particle)
    int gauss_order = 2;      // Gauss points per direction in each cell
    // a hexahedron's points: gauss (gauss_order^3), four_point (degree 2: half of the 2x2x2 points) or
    // six_point (degree 3: the face centres); tetrahedra keep gauss_order's rule
    std::string cell_rule = "gauss";
    std::string volumetric = "fbar";  // fbar (cell-averaged dilatation) or none
    std::string ebc_method = "nodal"; // essential BCs: nodal (on the coefficients) or transformation (exact)
    double jitter = 0;        // interior particles moved randomly by up to this x spacing per axis
  } discretization;

  Material material;

  struct Initial {
    Vec3 velocity{};          // m/s, at X = 0
    std::array<double, 9> velocity_gradient{};  // 1/s, row-major d v_i / d X_j: v = velocity + G X
    double temperature = 0;   // K, uniform (with a temperature; default the room temperature)
    // boxes of another starting temperature (K), by the material's position at t = 0; a later box wins
    struct Region {
      Vec3 lo{}, hi{};
      double temperature = 0;
    };
    std::vector<Region> temperature_regions;
    double temperature_at(const double X[3]) const {
      double T = temperature;
      for (const Region& r : temperature_regions)
        if (X[0] >= r.lo[0] && X[0] <= r.hi[0] && X[1] >= r.lo[1] && X[1] <= r.hi[1] && X[2] >= r.lo[2] && X[2] <= r.hi[2])
          T = r.temperature;
      return T;
    }
  } initial;

  struct Loads {
    Vec3 gravity{};           // m/s^2, body force per unit mass
  } loads;

  std::vector<SymmetryPlane> symmetry_planes;
  std::vector<EssentialFace> fixed_faces, prescribed_faces;
  std::vector<RigidWall> rigid_walls;
  std::vector<Die> dies;

  // Heat transfer (solver/thermal/): where the part conducts heat (material.conductivity > 0), its free
  // surface exchanges heat with the ambient by convection and radiation, and the thermal update runs
  // every few mechanical steps, as its own stable step allows, at most every max_steps_per_update
  // (0: as the stable step allows), and before each frame.
  struct Thermal {
    double ambient_temperature = 293.15;  // K
    double convection = 0;                // W/(m^2 K)
    double emissivity = 0;                // -, grey body
    int max_steps_per_update = 20;
    std::vector<TemperatureFace> fixed_faces;
  } thermal;

  // Ductile damage integrated at the integration points (solver/material/damage.hpp), each criterion
  // only where its key is given; a critical value > 0 marks where a crack is predicted.
  struct Damage {
    bool cockcroft_latham = false, brozzo = false, oyane = false;
    double cockcroft_latham_critical = 0, brozzo_critical = 0, oyane_critical = 0;
    double oyane_a = 0;  // Oyane's material constant a
    bool on() const { return cockcroft_latham || brozzo || oyane; }
  } damage;

  struct Contact {
    double penalty_scale = 0.25;  // k_I = scale * m_I / dt^2 (< 1: contact never limits the step)
    // fraction of critical damping, 2 sqrt(k m), of a penalty spring held at its step's limit (k = m / dt^2,
    // where the step has grown past the one its stiffness was set at: contact/contact_laws.hpp)
    double damping = 0.2;
    // the part's contact with itself (a fold's faces; solver/contact/part_contact.hpp): off unless
    // asked (it costs every step). Between bodies it is always on.
    bool self = false;
  } contact;

  // Reference-configuration updates (solver/rk/reference_update.hpp): when the Green strain of any
  // integration point since the last update exceeds `strain` (norm of E), the shape functions are
  // rebuilt on the current configuration. 0: total Lagrangian throughout.
  // After an update the step may grow to `step_growth` times the cells' estimate on the new reference's
  // edges at the default CFL (0.9; at a larger time.cfl no further than that CFL's estimate), at most
  // their estimate on the t = 0 edges (time_step.hpp); the contact's stiffness keeps to the new
  // reference's estimate. 1: the step is that estimate.
  struct ReferenceUpdates {
    double strain = 0;
    double step_growth = 2;
  } reference_updates;

  // Bulk viscosity (solver/material/bulk_viscosity.hpp): in compression the pressure q = rho l |e| (quadratic
  // l |e| + linear c), e = tr D. Defaults 1.5 and 0.06 (LS-DYNA's), 0 with mass scaling; both 0: off,
  // at no cost.
  struct BulkViscosity {
    double quadratic = 0;
    double linear = 0;
    bool on() const { return quadratic > 0 || linear > 0; }
  } bulk_viscosity;

  struct Time {
    double end = 0;                // s
    double start = 0;              // s: a stage's start on its chain's clock (set by rksolve; 0 in a scene)
    double cfl = 0.9;              // fraction of the stable step (default 0.5 when the scene has dies)
    // the stable step's estimate (solver/time_step.hpp): "cells" from each cell's edge and its points'
    // stretch, or "frequency" from the highest frequency of the discrete system (solver/highest_frequency.hpp)
    std::string stable_step = "cells";
    double output_interval = 0;    // s
    double mass_scaling_dt = 0;    // s; > 0: density scaled so that the stable step is at least this
    // multi-rate steps (solver/subcycles.hpp): the largest ratio of a particle's step to the smallest,
    // a power of two up to 16; 1: every particle takes the smallest step. A scene file's "auto" (its
    // default) reads 16 where the scene allows multi-rate steps and 1 where it does not.
    int subcycling = 1;
    // a stage of a chain without dies, loads or moving faces: "auto" a dwell (the part set down, its
    // temperature alone; solver/stage.hpp), "off" the part's motion goes on (an impact, a flight)
    std::string dwell = "auto";
  } time;

  struct Output {
    std::int64_t checkpoint_steps = 5000;  // steps between checkpoints (0: only at the end)
    double checkpoint_minutes = 0;         // wall-clock minutes between checkpoints (0: off)
    // material points followed in CASE/tracks.csv (solver/io/point_tracks.hpp): the particle nearest
    // each point at t = 0
    struct Track {
      std::string name;
      Vec3 point{};
    };
    std::vector<Track> track;
    // material lines that rkpost draws through the deformed part (post/flow_lines.hpp), the picture
    // forgers call grain flow: the particles within half a spacing of the plane (point, normal) at
    // t = 0, in lines along `direction` (in the plane) `spacing` apart
    struct FlowLines {
      std::string name;
      Vec3 point{}, normal{}, direction{};
      double spacing = 0;  // m
    };
    std::vector<FlowLines> flow_lines;
  } output;

  // The bounds' reasons (docs/scene.md): 0.05 lies above the method's error on the shipped scenes
  // (docs/validation.md); a step 1e-3 of the first would never end the run; 0.25 spacings is far past
  // any penalty spring's depth; 20 is about twice the largest pressure ratio of the shipped scenes.
  struct Health {
    double max_energy_error = 0.05;  // fraction of the energy scale; past it the run stops
    double min_dt_ratio = 1e-3;      // stable step / initial step below which the run stops
    double max_symmetry_depth = 0.25;  // material past a symmetry plane, in spacings, that stops the run
    double max_pressure_ratio = 20;  // |p| / (rho0 c_L v_max + sigma_y) that stops the run (0: no bound)
  } health;

  // The part's contact with itself or between its bodies (solver/contact/part_contact.hpp) is modeled.
  bool part_contact() const { return contact.self || !bodies.empty(); }
  // time.cfl's default (docs/decisions.md, "CFL default: 0.9")
  static constexpr double default_cfl() { return 0.9; }
  // the CFL at which contact.penalty_scale holds: 0.5 with dies, 0.9 without (the defaults the penalty's
  // scale was measured at; docs/decisions.md, "Contact laws")
  double penalty_cfl() const { return dies.empty() ? 0.9 : 0.5; }
  // contact.penalty_scale as the contact laws take it at this run's CFL: k = s m / dt_min^2 with dt_min
  // proportional to the CFL, so s follows CFL^2 and a CFL changes the step, not the contact's stiffness
  // (at most m / dt^2 all the same: contact/contact_laws.hpp)
  double penalty_scale_at_cfl() const {
    const double r = time.cfl / penalty_cfl();
    return contact.penalty_scale * r * r;
  }
  std::string resolved_yaml;     // the deck with every default filled in
  std::string prep_hash;         // hash of the scene keys rkprep depends on (geometry, discretization, the dies'
                                 // names, CAD paths and units; not the CAD files' contents)
};

// One "key.path=value" override from the command line (--set).
struct Override {
  std::string path;
  std::string value;
};
Override parse_override(const std::string& text);

enum class Side { prep, solve };

// Reads, applies overrides, validates and fills defaults. Throws rk::Error naming file, line and key.
// With Side::solve, an override of a key that prep depends on is refused (re-run rkprep instead).
Scene load_scene(const std::filesystem::path& file, const std::vector<Override>& overrides = {},
                 Side side = Side::prep);

// Suspicious but legal temperatures (kelvin expected): one below 273.15 K, freezing (a die at 250 C
// written as 250 is -23 C; no forging runs below freezing), a die or the air at or above the material's melting temperature
// (Johnson-Cook), a part temperature beyond a property table (its end value held), a mass density
// 2 % off the density table at the initial temperature. Each names its key.
std::vector<std::string> temperature_warnings(const Scene& scene);

// Legal settings that cost accuracy where a user may not expect it, each with what was measured: one
// Gauss point per cell (under-integrated), a plastic part without F-bar (locked), the step from the
// highest frequency with a penalty contact (softer springs). Printed by rkprep and rksolve, kept in
// solve.json's warnings.
std::vector<std::string> accuracy_warnings(const Scene& scene);

// Material constants no metal has (a value in another unit, most often): youngs_modulus below 1 GPa, a
// density outside 500-25000 kg/m^3, a yield stress or power-law strength above 5 % of youngs_modulus.
std::vector<std::string> material_warnings(const Scene& scene);

// More than 1000 frames asked (time.end / time.output_interval).
std::vector<std::string> output_warnings(const Scene& scene);

// Every warning the scene alone gives (the lists above), as rksolve prints and reports them.
std::vector<std::string> scene_warnings(const Scene& scene);

// Basis requirements: the smallest dilation with which the moment matrix stays regular.
double minimum_dilation(const std::string& basis);

}  // namespace rk
