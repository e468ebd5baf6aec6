// Scatter: f^int_I = sum_g w_g P_g grad_X N_I(X_g) (Wang et al. 2007, eq. (19)) from this rank's own points,
// accumulated in fixed point (parallel/fixed_point.hpp) so the result is independent of summation order.
// The points are added in two groups so that the boundary points' partials can travel while the
// interior points are computed.
#pragma once
#include <span>

#include "contact/die_contact.hpp"
#include "contact/part_contact.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "parallel/fixed_point.hpp"
#include "state.hpp"

namespace rk {

// The fixed-point headroom (parallel/fixed_point.hpp) of sums over this model's points and neighbours: the
// most contributions any particle receives from the points of ALL ranks, `per_column` from each of
// its columns, plus `extra`, so it does not depend on the partition. Collective; set-up only (allocates).
int force_headroom(const Model& md, int per_column, int extra, const Comm& comm);
// The headroom of the internal force's sums: force_headroom's, at least kRowHeadroom (rk/row3.hpp).
int row_headroom(int headroom);
// Every term summed into a particle's force (st.partial), the most over the particles of ALL ranks:
// one from each point whose row holds it (the internal force), and the contact terms
// (DieContact::count_terms, PartContact::count_terms), for step_headroom. Collective; set-up only (allocates).
ForceTerms force_terms(const Model& md, const DieContact& dies, const PartContact& parts, const Comm& comm);

void clear_internal_force(State& st);
void add_internal_force(const Model& md, State& st, const FixedScale& scale, std::span<const std::int32_t> points);
// The same sum of w_g P_g grad_X N_I for any per-point tensors P (9 per point) into `partial`
// (kForceStride per particle, as State::partial).
void add_point_forces(const Model& md, const std::vector<double>& P, std::vector<Fixed>& partial, const FixedScale& scale,
                      std::span<const std::int32_t> points);
// The sums as forces, 3 per particle, from `partial` (kForceStride per particle).
void read_forces(const std::vector<Fixed>& partial, const FixedScale& scale, std::vector<double>& force);

}  // namespace rk
