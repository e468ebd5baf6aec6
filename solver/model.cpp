// Builds a rank's offline data (model.hpp) from its subdomain: the RK shape functions at the points
// (Wang et al. 2007, eq. (3)), or their gradients smoothed over the nodal-integration cells (SCNI, Chen et al. 2001),
// the cells' edges for the stable step, and the owned particles' material rows N_J(X_I).
#include "model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "boundary/constraints.hpp"
#include "checked_int.hpp"
#include "error.hpp"
#include "rk/local_shapes.hpp"

namespace rk {
namespace {

void require_regular(const Model& md, const RkResult& r, const double* x, std::size_t support, const char* where) {
  if (r.regular) return;
  std::ostringstream s;
  s << "rank " << md.rank << ": the RK moment matrix is singular at the " << where << " at (" << x[0] << ", " << x[1]
    << ", " << x[2] << ") m with " << support << " particles in its support (rcond " << r.rcond
    << "); increase discretization.dilation";
  throw Error(s.str());
}

void bound_gradients(Model& md) {
  md.dN_max.assign(md.m, 0.0);
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      md.dN_max[g] = std::max(md.dN_max[g], std::sqrt(md.dN[3 * k] * md.dN[3 * k] + md.dN[3 * k + 1] * md.dN[3 * k + 1] +
                                                      md.dN[3 * k + 2] * md.dN[3 * k + 2]));
}

// Gauss points: N_I and grad N_I at each point. One support search per cell (its points share most
// of their particles), each point's columns picked from it, then the shape functions into arrays sized
// once (ascending global id).
void build_shape_functions(Model& md, const LocalShapes& shapes) {
  md.nbr_offsets.assign(1, 0);
  std::vector<std::int32_t> candidates;
  for (std::size_t c = 0; c < md.cells; ++c) {
    const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
    shapes.near_group(&md.point_X[3 * g0], g1 - g0, cell_body(md, c), candidates);
    for (auto g = g0; g < g1; ++g) {
      shapes.covering_among(&md.point_X[3 * g], candidates, md.nbr);
      md.nbr_offsets.push_back(std::int64_t(md.nbr.size()));
    }
  }
  md.N.resize(md.nbr.size()), md.dN.resize(3 * md.nbr.size());
  for (std::size_t g = 0; g < md.m; ++g) {
    const auto k0 = std::size_t(md.nbr_offsets[g]), count = std::size_t(md.nbr_offsets[g + 1]) - k0;
    const RkResult r = shapes.evaluate(&md.point_X[3 * g], {md.nbr.data() + k0, count}, md.N.data() + k0, md.dN.data() + 3 * k0);
    require_regular(md, r, &md.point_X[3 * g], count, "integration point");
  }
}

// Adds sign * src (columns src_cols, a subset of the row's ascending columns) into the row at k0.
void add_into_row(const Model& md, std::size_t k0, const std::vector<std::int32_t>& src_cols, const double* src,
                  int width, double* row) {
  std::size_t k = k0;
  for (std::size_t j = 0; j < src_cols.size(); ++j) {
    while (md.nbr[k] != src_cols[j]) ++k;
    for (int i = 0; i < width; ++i) row[width * k + i] += src[width * j + i];
  }
}

// Nodal integration (prep/nodal_integration.hpp): grad N_I at point L smoothed over its dual cell,
// 1/V_L sum_q +-N_I(x_q) nA_q over its face points; N_I at the point itself. A point's columns are
// the particles whose supports cover the point or any of its face points. Every face point is
// evaluated once, in the subdomain's order (the same for every partition).
void build_smoothed_gradients(Model& md, const Subdomain& sub, const LocalShapes& shapes) {
  const std::size_t nf = sub.face_count();
  std::vector<std::int32_t> face_offsets(md.m + 1, 0), face_of;  // point -> its face points
  for (std::size_t q = 0; q < nf; ++q) {
    ++face_offsets[sub.face_plus[q] + 1];
    if (sub.face_minus[q] >= 0) ++face_offsets[sub.face_minus[q] + 1];
  }
  for (std::size_t g = 0; g < md.m; ++g) face_offsets[g + 1] += face_offsets[g];
  face_of.resize(face_offsets.back());
  std::vector<std::int32_t> fill(face_offsets.begin(), face_offsets.end() - 1);
  for (std::size_t q = 0; q < nf; ++q) {
    face_of[fill[sub.face_plus[q]]++] = std::int32_t(q);
    if (sub.face_minus[q] >= 0) face_of[fill[sub.face_minus[q]]++] = std::int32_t(q);
  }
  md.nbr_offsets.assign(1, 0);
  std::vector<std::int32_t> found;
  std::vector<std::uint8_t> mark(md.n, 0);
  for (std::size_t g = 0; g < md.m; ++g) {
    found.clear();
    shapes.covering(&md.point_X[3 * g], 0, found);  // one body: the scene refuses bodies with nodal integration
    for (auto k = face_offsets[g]; k < face_offsets[g + 1]; ++k) shapes.covering(&sub.face_X[3 * face_of[k]], 0, found);
    const std::size_t k0 = md.nbr.size();
    for (auto I : found)
      if (!mark[I]) mark[I] = 1, md.nbr.push_back(I);
    std::sort(md.nbr.begin() + std::ptrdiff_t(k0), md.nbr.end());
    for (auto k = k0; k < md.nbr.size(); ++k) mark[md.nbr[k]] = 0;
    md.nbr_offsets.push_back(std::int64_t(md.nbr.size()));
  }
  md.N.assign(md.nbr.size(), 0.0);
  md.dN.assign(3 * md.nbr.size(), 0.0);
  std::vector<std::int32_t> cols;
  std::vector<double> N, terms;
  auto evaluate = [&](const double* x, const char* where) {
    cols.clear(), N.clear();
    require_regular(md, shapes.append(x, 0, cols, N), x, cols.size(), where);
  };
  for (std::size_t g = 0; g < md.m; ++g) {
    evaluate(&md.point_X[3 * g], "integration point");
    add_into_row(md, md.nbr_offsets[g], cols, N.data(), 1, md.N.data());
  }
  for (std::size_t q = 0; q < nf; ++q) {
    evaluate(&sub.face_X[3 * q], "nodal-integration face point");
    const double* nA = &sub.face_nA[3 * q];
    for (const double sign : {1.0, -1.0}) {
      const std::int32_t g = sign > 0 ? sub.face_plus[q] : sub.face_minus[q];
      if (g < 0) continue;
      terms.resize(3 * cols.size());
      for (std::size_t j = 0; j < cols.size(); ++j)
        for (int i = 0; i < 3; ++i) terms[3 * j + i] = sign * N[j] * nA[i];
      add_into_row(md, md.nbr_offsets[g], cols, terms.data(), 3, md.dN.data());
    }
  }
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = 3 * std::size_t(md.nbr_offsets[g]); k < 3 * std::size_t(md.nbr_offsets[g + 1]); ++k)
      md.dN[k] /= md.weight[g];
}

// The shortest edge of each cell through the particles at `x` (hexahedra: 12 edges, tetrahedra: 6).
std::vector<double> shortest_edges(const Model& md, const std::vector<double>& x) {
  static constexpr int kHex[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                      {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static constexpr int kTet[12][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::vector<double> h0(md.cells, std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < md.cells; ++c) {
    const std::int32_t* nodes = &md.cell_nodes[md.cell_node_offsets[c]];
    const bool hex = md.cell_node_offsets[c + 1] - md.cell_node_offsets[c] == 8;
    for (int e = 0; e < (hex ? 12 : 6); ++e) {
      const int a = nodes[hex ? kHex[e][0] : kTet[e][0]], b = nodes[hex ? kHex[e][1] : kTet[e][1]];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (x[3 * a + i] - x[3 * b + i]) * (x[3 * a + i] - x[3 * b + i]);
      h0[c] = std::min(h0[c], std::sqrt(d2));
    }
  }
  return h0;
}

// The owned particles' rows N_J(X_I): rkprep made the whole support of an owned particle local.
void build_material_rows(Model& md, const LocalShapes& shapes) {
  md.material_offsets.assign(1, 0);
  md.material_cols.clear(), md.material_N.clear();
  for (std::size_t I = 0; I < md.n; ++I) {
    const std::size_t k0 = md.material_cols.size();
    if (md.owned[I] && !shapes.append(&md.Xr[3 * I], md.body[I], md.material_cols, md.material_N).regular) {
      md.material_cols.resize(k0), md.material_N.resize(k0);  // a particle left alone: its coefficient
      md.material_cols.push_back(std::int32_t(I)), md.material_N.push_back(1.0);
    }
    md.material_offsets.push_back(std::int32_t(md.material_cols.size()));
  }
  // the offsets grow with I: the last fits in 32 bits only if every one does
  checked_int(std::int64_t(md.material_cols.size()), "rank " + std::to_string(md.rank) + ": the particles' material rows (entries)");
}

// The J2 law of a material of the scene.
J2Params law_of(const Material& mat) {
  J2Params law;
  if (mat.model == MaterialModel::johnson_cook) {
    law = J2Params::johnson_cook_law(mat.youngs_modulus, mat.poisson_ratio, mat.yield_stress, mat.hardening_coefficient,
                                     mat.hardening_exponent, mat.rate_coefficient, mat.reference_strain_rate,
                                     mat.thermal_exponent, mat.room_temperature, mat.melting_temperature);
  } else if (mat.model == MaterialModel::table) {
    law = J2Params::from(mat.youngs_modulus, mat.poisson_ratio, 0, 0, true);
    law.table = mat.table;
    law.yield0 = law.yield(0);
  } else if (mat.model == MaterialModel::hansel_spittel) {
    const double a_m[9] = {mat.hs_a, mat.hs_m[0], mat.hs_m[1], mat.hs_m[2], mat.hs_m[3], mat.hs_m[4], mat.hs_m[6], mat.hs_m[7], mat.hs_m[8]};
    law = J2Params::hansel_spittel_law(mat.youngs_modulus, mat.poisson_ratio, a_m, mat.minimum_strain,
                                       mat.minimum_strain_rate, mat.strain_offset, mat.strain_rate_offset);
  } else {
    law = mat.model == MaterialModel::j2_power
              ? J2Params::power(mat.youngs_modulus, mat.poisson_ratio, mat.strength, mat.reference_strain, mat.exponent)
              : J2Params::from(mat.youngs_modulus, mat.poisson_ratio, mat.yield_stress, mat.hardening_modulus,
                               mat.model == MaterialModel::j2_linear);
  }
  return law;
}

// The scene's materials as Model::materials orders them (the part's, then the bodies' own), and each
// body's index among them in `body_material` (body 0 the part).
std::vector<Solid> solids(const Scene& scene, std::vector<std::uint8_t>& body_material) {
  std::vector<Solid> out{Solid::of(law_of(scene.material), scene.material.density)};
  body_material.assign(scene.bodies.size() + 1, 0);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (const auto& mat = scene.bodies[b].material) {
      body_material[b + 1] = std::uint8_t(out.size());
      out.push_back(Solid::of(law_of(*mat), mat->density));
    }
  return out;
}

}  // namespace

Model build_model(const Subdomain& sub, const Scene& scene, const std::vector<double>* initial_X, Model* previous) {
  Model md;
  if (previous) {
    md.nbr = std::move(previous->nbr), md.N = std::move(previous->N), md.dN = std::move(previous->dN);
    md.nbr.clear(), md.N.clear(), md.dN.clear();
    std::vector<std::int64_t>().swap(previous->nbr_offsets);
  }
  md.rank = int(sub.rank);
  md.ranks = int(sub.ranks);
  md.n = sub.particle_count();
  md.global_id = sub.global_id;
  md.X = initial_X ? *initial_X : sub.X;
  md.Xr = sub.X;
  md.volume = sub.volume;
  md.spacing = sub.spacing;
  md.spacing0 = sub.spacing;
  md.owner = sub.owner;
  std::vector<std::uint8_t> body_material;  // body -> index in md.materials
  md.materials = solids(scene, body_material);
  md.mass.resize(md.n);
  md.owned.resize(md.n);
  md.surface.resize(md.n);
  md.body.resize(md.n);
  for (std::size_t I = 0; I < md.n; ++I) {
    md.owned[I] = sub.owner[I] == sub.rank;
    md.surface[I] = (sub.flags[I] & kSurface) != 0;
    md.body[I] = std::uint8_t(body_of(sub.flags[I]));
    if (md.body[I] >= body_material.size())
      throw Error("subdomain of rank " + std::to_string(md.rank) + ": particle " + std::to_string(md.global_id[I]) +
                  " is of body " + std::to_string(md.body[I]) + ", which the scene does not have; re-run rkprep");
    md.mass[I] = md.materials[body_material[md.body[I]]].density * sub.volume[I];
  }
  build_constraints(md, sub, scene);

  md.m = sub.point_count();
  md.weight = sub.point_weight;
  md.point_X = sub.point_X;
  md.cells = sub.cell_count();
  md.cell_global_id = sub.cell_global_id;
  md.cell_node_offsets = sub.cell_node_offsets;
  md.cell_nodes = sub.cell_nodes;
  md.cell_points.assign(md.cells + 1, 0);
  for (std::size_t g = 0; g < md.m; ++g) {
    if (g > 0 && sub.point_cell[g] < sub.point_cell[g - 1])
      throw Error("subdomain of rank " + std::to_string(md.rank) + ": integration points are not grouped by cell");
    ++md.cell_points[sub.point_cell[g] + 1];
  }
  for (std::size_t c = 0; c < md.cells; ++c) md.cell_points[c + 1] += md.cell_points[c];
  md.cell_material.resize(md.cells);
  md.point_material.resize(md.m);
  for (std::size_t c = 0; c < md.cells; ++c) {
    md.cell_material[c] = body_material[std::size_t(cell_body(md, c))];
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) md.point_material[std::size_t(g)] = md.cell_material[c];
  }
  // The time step's length: the shortest edge at t = 0 (the supports keep their t = 0 size, so a cell
  // compressed before an update does not stiffen the material as much as its edge shrank), and after a
  // reference update also the shorter of that and the edge on the new reference, for the step the
  // contact's stiffness keeps to (it follows the points' stretch since the update, which alone would
  // forget a cell's compression before it; a stretched cell does not lengthen either); the step's own
  // edge at most step_growth times that one.
  md.cell_h0 = shortest_edges(md, md.X);
  md.cell_h_reference.clear();
  if (initial_X) {
    md.cell_h_reference = shortest_edges(md, md.Xr);
    // the growth bounded so that the step stays within step_growth times the new reference's step at the
    // default CFL, at any time.cfl (not below the reference's own step): the contact's springs, whose
    // stiffness does not follow the CFL, soften no more than there, and the step stays within the one the
    // stability study's reference updates at CFL 2.0 hold stable (docs/decisions.md)
    const double growth = std::max(1.0, scene.reference_updates.step_growth * Scene::default_cfl() / scene.time.cfl);
    for (std::size_t c = 0; c < md.cells; ++c) {
      md.cell_h_reference[c] = std::min(md.cell_h0[c], md.cell_h_reference[c]);
      md.cell_h0[c] = std::min(md.cell_h0[c], growth * md.cell_h_reference[c]);
    }
  }
  const LocalShapes shapes(md.Xr, sub.volume, md.spacing, md.body, scene);
  if (scene.discretization.integration == "nodal" && md.m > 0 && sub.face_count() == 0)
    throw Error("subdomain of rank " + std::to_string(md.rank) + " holds no nodal-integration faces; re-run rkprep");
  if (scene.discretization.integration == "nodal") build_smoothed_gradients(md, sub, shapes);
  else build_shape_functions(md, shapes);
  bound_gradients(md);

  md.dies = sub.dies;
  md.surface_face_offsets = sub.surface_face_offsets;
  md.surface_face_nodes = sub.surface_face_nodes;
  md.surface_face_cell = sub.surface_face_cell;
  build_material_rows(md, shapes);
  md.neighbour_ranks = sub.neighbour_ranks;
  md.overlap = sub.overlap;
  std::vector<std::uint8_t> shared(md.n, 0);
  for (const auto& list : md.overlap)
    for (auto I : list) shared[I] = 1;
  for (std::size_t g = 0; g < md.m; ++g) {
    bool touches = false;
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1] && !touches; ++k) touches = shared[md.nbr[k]];
    (touches ? md.boundary_points : md.interior_points).push_back(std::int32_t(g));
  }

  const auto& mat = scene.material;
  if (mat.thermal()) {
    md.heat_capacity = mat.density * mat.specific_heat;
    md.taylor_quinney = mat.taylor_quinney;
    md.specific_heat_table = mat.specific_heat_table;
    md.mass_density = mat.density;
    md.thermal_expansion = mat.thermal_expansion;
    md.density_table = mat.density_table;
    md.initial_temperature = scene.initial.temperature;
  }
  md.damage_cockcroft_latham = scene.damage.cockcroft_latham, md.damage_brozzo = scene.damage.brozzo;
  md.damage_oyane = scene.damage.oyane, md.oyane_a = scene.damage.oyane_a;
  md.green_strain = scene.reference_updates.strain > 0;
  // F-bar averages the dilatation over a cell's points: the identity where every cell has one point
  // (Gauss order 1) and meaningless for nodal points; without it the stress update batches points
  // across cells
  bool shared_cells = false;
  for (std::size_t c = 0; c < md.cells; ++c) shared_cells |= md.cell_points[c + 1] - md.cell_points[c] > 1;
  md.fbar = scene.discretization.volumetric == "fbar" && scene.discretization.integration == "gauss" && shared_cells;
  return md;
}

}  // namespace rk

namespace rk {

void scale_mass(Model& md, double factor) {
  md.mass_scaling *= factor;
  for (auto& s : md.materials) s.density *= factor;
  for (auto& m : md.mass) m *= factor;
}

void single_material(Model& md, const J2Params& law, double density) {
  md.materials = {Solid::of(law, density)};
  md.cell_material.assign(md.cells, 0);
  md.point_material.assign(md.m, 0);
}

}  // namespace rk
