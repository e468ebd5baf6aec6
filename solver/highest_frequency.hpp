// The highest frequency of the discrete system, omega_max^2 = lambda_max(M^-1 K), by power iteration
// on the linearized internal force at the current configuration: the central-difference step is
// stable for dt < 2 / omega_max. K is the elastic tangent (Lame constants of the material, on the
// current gradients grad_x N = grad_X N F^-1, with the F-bar cell average of the volumetric strain
// where the model uses F-bar); the plastic tangent is softer, so the elastic one bounds it.
// Sums are in fixed point (parallel/fixed_point.hpp) and the start vector comes from the particles'
// global ids, so the estimate is bitwise the same on any number of ranks.
#pragma once
#include <vector>

#include "model.hpp"
#include "parallel/comm.hpp"
#include "parallel/overlap_exchange.hpp"
#include "state.hpp"

namespace rk {

class HighestFrequency {
 public:
  HighestFrequency(const Model& md, const Comm& comm);  // set-up: allocates; collective
  // The ratio of the step 2 / omega_max to the cells' estimate without bulk viscosity (time_step.hpp),
  // kept in st.step_ratio: refreshed by kStart power iterations where there is none (the start, a
  // reference update), else by one every kEvery steps, warm-started from st.stiff_mode. Collective.
  double step_ratio(const Model& md, State& st, const Comm& comm);
  static constexpr int kStart = 40, kEvery = 10;

 private:
  double iterate(const Model& md, State& st, const Comm& comm, int iterations);  // omega_max^2
  void apply(const Model& md, const State& st, const Comm& comm);  // Kv_ = K st.stiff_mode
  double dot(const Model& md, const std::vector<double>& a, const std::vector<double>& b, bool by_mass,
             const Comm& comm) const;

  OverlapExchange exchange_;
  int headroom_ = 0, sum_headroom_ = 0;
  std::vector<double> Kv_, P_;
  std::vector<Fixed> partial_;
};

}  // namespace rk
