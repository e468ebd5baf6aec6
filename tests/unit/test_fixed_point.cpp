// The fixed-point force sums cannot overflow (solver/parallel/fixed_point.hpp):
// - at the headroom of T terms, T terms each at the bound (the largest a term can be after the
//   scale, of either sign) sum within int64, for counts from 1 to 2^40 and bounds of any binade,
//   down to 7e-300 (whose scale would pass the largest double);
// - a step's headroom (step_headroom) holds the worst sum of its internal and contact terms, each
//   at its bound and of one sign, where the resolution's headroom would overflow, and is the
//   resolution's wherever that suffices;
// - the contact's count (DieContact::count_terms) holds every term add_to can put on a particle,
//   on the upsetting eighth (one die, three symmetry planes): one per obstacle for every slave
//   whose row holds it, particle slaves spread over their rows N_J(X_I) included;
// - the force loop's conversion of a row to fixed point (rk/row3.hpp round_row: one add of 1.5 2^52
//   without AVX-512, which alone has a packed conversion) is std::llrint's, to the nearest with ties to
//   even, bit for bit, for every magnitude below 2^51 (its range), both signs, zeros, integers and
//   halves, the binades' edges and subnormals; and at the force's headroom (kRowHeadroom at least) a
//   term at its bound, of any binade, is below 2^50 after the scale, however few terms meet;
// - counts and offsets narrowed to 32 bits (shared/checked_int.hpp) pass when they fit and are one
//   error naming what they count when they do not.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "checked_int.hpp"
#include "contact/die_contact.hpp"
#include "die_surface.hpp"
#include "material_above.hpp"
#include "model.hpp"
#include "parallel/fixed_point.hpp"
#include "rk/internal_force.hpp"
#include "rk/row3.hpp"
#include "scene.hpp"
#include "source_dir.hpp"

namespace {

using rk::test::kSource;
__extension__ typedef __int128 Wide;  // the exact sums to check int64's against (a GCC extension: no -Wpedantic)

TEST(FixedPoint, EveryTermAtTheBoundSumsWithinInt64) {
  for (const std::int64_t terms : {std::int64_t(1), std::int64_t(2), std::int64_t(3), std::int64_t(500),
                                   std::int64_t(1) << 20, (std::int64_t(1) << 20) - 1, (std::int64_t(1) << 40) + 7}) {
    const int h = rk::headroom_bits(terms);
    for (const double bound : {1.0, 0.75, 1.0 - 1e-16, 3.1e5, std::ldexp(1.0, -30), 7e-300}) {
      const rk::FixedScale scale = rk::FixedScale::for_bound(bound, h);
      for (const double x : {bound, -bound}) {
        const rk::Fixed term = scale.fixed(x);
        const Wide sum = Wide(term) * terms;  // every term at the bound, the same sign
        EXPECT_LE(sum, Wide(std::numeric_limits<rk::Fixed>::max())) << terms << " terms at " << x;
        EXPECT_GE(sum, Wide(std::numeric_limits<rk::Fixed>::min())) << terms << " terms at " << x;
      }
    }
  }
}

TEST(FixedPoint, TheForceRowsConversionRoundsToTheNearest) {
  std::vector<double> xs = {0.0, -0.0, 0.5, 1.5, 2.5, 1.0, 2.0, 3.999999, 1e-310, 4.9e-324, std::ldexp(1.0, 31) + 0.5,
                            std::ldexp(1.0, 50) + 0.5, std::ldexp(1.0, 50) - 0.5, std::ldexp(1.0, 51) - 0.5, std::ldexp(1.0, 51) - 1};
  std::uint64_t seed = 88172645463325252ull;  // xorshift: mantissas over every binade from 2^-1080 to 2^50
  for (int k = 0; k < 200000; ++k) {
    seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
    xs.push_back(std::ldexp(1.0 + double(seed >> 12) * 0x1p-52, int(seed % 1131) - 1080));
  }
  int mismatches = 0;
  for (const double a : xs)
    for (const double x : {a, -a}) {
      const double lanes[3] = {x, -0.5 * x, std::nextafter(x, 0.0)};
      const rk::FixedRow3 row = rk::round_row(rk::make_row3(lanes[0], lanes[1], lanes[2]));
      for (int i = 0; i < 3; ++i)
        if (row[i] != std::llrint(lanes[i]) && ++mismatches <= 5)
          ADD_FAILURE() << "lane " << i << " of " << lanes[i] << ": " << row[i] << " against " << std::llrint(lanes[i]);
    }
  EXPECT_EQ(mismatches, 0);
}

TEST(FixedPoint, TheForceScaleKeepsATermAtItsBoundWithinTheRowsRange) {
  for (const int counted : {0, 1, 9, rk::kRowHeadroom, 20})  // force_headroom's count, then the floor
    for (const double bound : {1.0, 0.75, 1.0 - 1e-16, 3.1e5, std::ldexp(1.0, -30), 7e-300}) {
      const rk::FixedScale scale = rk::FixedScale::for_bound(bound, rk::row_headroom(counted));
      EXPECT_LT(std::abs(bound * scale.to_fixed), std::ldexp(1.0, 50)) << bound << " at " << counted << " counted bits";
    }
}

// The worst sum of a step at the headroom step_headroom gives, every term at its bound and of one sign.
Wide worst_sum(const rk::ForceTerms& terms, double bound, double contact_bound, int headroom) {
  const rk::FixedScale scale = rk::FixedScale::for_bound(bound, headroom);
  return Wide(scale.fixed(bound)) * terms.internal + Wide(scale.fixed(contact_bound)) * terms.contact;
}

TEST(FixedPoint, AStepsHeadroomHoldsItsWorstSum) {
  const Wide most = std::numeric_limits<rk::Fixed>::max();
  // a resolution's headroom from the points' columns alone (2^10 > 601) and a particle that takes
  // 2 700 terms with the contacts: at a bound just below a power of two they could pass 2^63
  const rk::ForceTerms terms{300, 2400};
  const int resolution = rk::headroom_bits(2 * 300 + 1);
  ASSERT_EQ(resolution, 10);
  const double top = std::nextafter(1.0, 0.0);
  EXPECT_GT(worst_sum(terms, top, top, resolution), most) << "the resolution's headroom alone overflows";
  EXPECT_EQ(rk::step_headroom(resolution, terms, top, top), 11);
  EXPECT_LE(worst_sum(terms, top, top, 11), most);
  // at the bottom of the bound's binade, or with small contact forces, they fit: the headroom (and so
  // every force) is the resolution's
  EXPECT_LE(worst_sum(terms, 1.0, 1.0, resolution), most);
  EXPECT_EQ(rk::step_headroom(resolution, terms, 1.0, 1.0), resolution);
  EXPECT_EQ(rk::step_headroom(resolution, terms, top, 1e-3 * top), resolution);
  EXPECT_EQ(rk::step_headroom(resolution, terms, top, 0.0), resolution);
  EXPECT_EQ(rk::step_headroom(resolution, {1023, 0}, top, top), resolution);
  // any counts: the worst sum at the step's headroom fits
  for (const std::int64_t n : {std::int64_t(1), std::int64_t(777), std::int64_t(1) << 30, (std::int64_t(1) << 45) + 3})
    for (const double share : {0.0, 0.1, 0.5, 1.0}) {
      const rk::ForceTerms t{n, 3 * n + 5};
      const int h = rk::step_headroom(rk::headroom_bits(n), t, 2.5, share * 2.5);
      EXPECT_LE(worst_sum(t, 2.5, share * 2.5, h), most) << n << " " << share;
      EXPECT_GE(-worst_sum(t, 2.5, share * 2.5, h), -most - 1) << n << " " << share;
    }
  // nothing to scale: the headroom as given
  EXPECT_EQ(rk::step_headroom(9, {100, 100}, 0.0, 0.0), 9);
}

TEST(FixedPoint, TheContactCountHoldsEveryObstacleOfEverySlaveRow) {
  const rk::Scene scene = rk::load_scene(kSource + "/geometry/upsetting/scene.yaml", {{"discretization.spacing", "2.5e-3"}});
  const std::vector<rk::DieSurface> dies{rk::mesh_die(scene.dies[0], scene.discretization.spacing)};
  const rk::Model md = one_rank_model(scene, dies);
  const rk::DieContact contact(md, scene, dies);
  const auto obstacles = rk::Fixed(scene.dies.size() + scene.rigid_walls.size() + scene.symmetry_planes.size());
  ASSERT_EQ(obstacles, 4);
  std::vector<rk::Fixed> expected(md.n, 0), counted(md.n, 0);
  for (std::size_t g = 0; g < md.m; ++g)  // the points are slaves
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) expected[std::size_t(md.nbr[k])] += obstacles;
  for (std::size_t I = 0; I < md.n; ++I)  // and so are the owned particles, at u^h(X_I)
    if (md.owned[I])
      for (auto k = md.material_offsets[I]; k < md.material_offsets[I + 1]; ++k)
        expected[std::size_t(md.material_cols[std::size_t(k)])] += obstacles;
  contact.count_terms(md, counted);
  EXPECT_EQ(counted, expected);
}

TEST(CheckedInt, NarrowsWhatFitsAndNamesWhatDoesNot) {
  EXPECT_EQ(rk::checked_int(0, "x"), 0);
  EXPECT_EQ(rk::checked_int(INT_MAX, "x"), INT_MAX);
  EXPECT_EQ(rk::checked_int(INT_MIN, "x"), INT_MIN);
  try {
    rk::checked_int(std::int64_t(INT_MAX) + 1, "rank 3: the particles' material rows (entries)");
    FAIL() << "2^31 passed";
  } catch (const rk::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "rank 3: the particles' material rows (entries): 2147483648 exceeds the 2147483647 a 32-bit int holds");
  }
  EXPECT_THROW(rk::checked_int(std::int64_t(1) << 40, "x"), rk::Error);
  EXPECT_THROW(rk::checked_int(std::int64_t(INT_MIN) - 1, "x"), rk::Error);
}

}  // namespace
