#include "contact/presses.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rk {

Presses::Presses(const Scene& scene, double h_min, int headroom) : h_min_(h_min), headroom_(headroom) {
  for (std::size_t k = 0; k < scene.dies.size(); ++k) {
    const Die& d = scene.dies[k];
    if (!d.motion.driven()) continue;
    rams_.push_back({k, d.motion.ram, d.motion.blows() ? d.motion.ram.blow_speed() : d.motion.speed, d.force_factor});
  }
  sums_.assign(rams_.size(), 0);
}

void Presses::start(State& st) const {
  st.rams.assign(rams_.size(), State::Ram{});
  for (std::size_t r = 0; r < rams_.size(); ++r) {
    st.rams[r].speed = rams_[r].nominal;
    st.rams[r].blows = rams_[r].press.blows > 0 ? 1 : 0;
  }
}

void Presses::place(const State& st, DieContact& dies, bool stepped) const {
  for (std::size_t r = 0; r < rams_.size(); ++r)
    dies.drive(rams_[r].die, st.rams[r].stroke, stepped ? rams_[r].vbar : st.rams[r].speed);
}

double Presses::reaction_bound(const DieContact& dies) const {
  double bound = 0;
  for (const Ram& ram : rams_) bound = std::max(bound, dies.reaction_bound(ram.die));
  return bound;
}

void Presses::advance(State& st, const DieContact& dies, double bound, double dt_avg, const Comm& comm) {
  const FixedScale scale = FixedScale::for_bound(bound, headroom_);
  for (std::size_t r = 0; r < rams_.size(); ++r) sums_[r] = dies.reaction(rams_[r].die, scale);
  comm.sum(sums_.data(), int(sums_.size()));
  for (std::size_t r = 0; r < rams_.size(); ++r) {
    Ram& ram = rams_[r];
    State::Ram& s = st.rams[r];
    const double R = ram.force_factor * scale.real(sums_[r]);  // the whole part's reaction at t^n
    double next = 0;
    if (s.stopped == 0) {
      const DieMotion::Ram& p = ram.press;
      if (p.blows > 0) {
        next = s.speed - dt_avg * R / p.mass;  // the ram coasts against the part
        if (next <= 0) {                       // this blow is spent
          next = 0;
          if (s.blows < p.blows) s.blows += 1, next = ram.nominal;  // the next one at once
          else s.stopped = 1;
        }
      } else {
        double cap = ram.nominal;  // the pump's speed, and the power it can give at this load
        if (p.power_limit > 0 && R > 0) cap = std::min(cap, p.power_limit / R);
        next = std::clamp(s.speed + dt_avg * (p.force_limit - R) / p.mass, 0.0, cap);
      }
    }
    ram.vbar = 0.5 * (s.speed + next);
    s.delivered += dt_avg * R * ram.vbar;
    s.speed = next;
  }
}

void Presses::move(State& st, double dt) const {
  const double t = st.t + dt;
  for (std::size_t r = 0; r < rams_.size(); ++r) {
    const Ram& ram = rams_[r];
    State::Ram& s = st.rams[r];
    const double limit = ram.press.stroke;
    if (limit > 0 && s.stroke + dt * s.speed >= limit) {  // the hydraulic press's end of stroke
      s.stroke = limit, s.speed = 0, s.stopped = 1;
      continue;
    }
    s.stroke += dt * s.speed;
    if (ram.press.blows > 0 || s.stopped > 0) continue;
    // a stalled hydraulic press: its mean speed under 1 % of its nominal one over the time that moves
    // it a tenth of a spacing
    if ((t - s.since_t) * ram.nominal >= 0.1 * h_min_) {
      if (std::abs(s.stroke - s.since_s) < 1e-3 * h_min_) s.stopped = 1;
      s.since_t = t, s.since_s = s.stroke;
    }
  }
}

bool Presses::stopped(const State& st) const {
  if (empty()) return false;
  for (const State::Ram& s : st.rams)
    if (s.stopped == 0) return false;
  return true;
}

std::vector<std::string> Presses::outcome(const State& st, const std::vector<Die>& dies) const {
  std::vector<std::string> lines;
  for (std::size_t r = 0; r < rams_.size(); ++r) {
    const Ram& ram = rams_[r];
    const State::Ram& s = st.rams[r];
    const std::string& name = dies[ram.die].name;
    char text[400];
    if (ram.press.blows > 0)
      std::snprintf(text, sizeof text, "die '%s': %s after %d of %d blows, %.4g J delivered of %.4g J, stroke %.4g mm",
                    name.c_str(), s.stopped > 0 ? "stopped" : "still moving", int(s.blows), ram.press.blows, s.delivered,
                    ram.press.blows * ram.press.efficiency * ram.press.energy, 1e3 * s.stroke);
    else if (stalled(st, r))
      std::snprintf(text, sizeof text,
                    "die '%s' stalled at stroke %.4g mm: the part needs more than its force limit of %.4g kN%s",
                    name.c_str(), 1e3 * s.stroke, 1e-3 * ram.press.force_limit,
                    ram.press.power_limit > 0 ? " (or its power limit)" : "");
    else
      std::snprintf(text, sizeof text, "die '%s': %s at stroke %.4g mm, %.4g J delivered", name.c_str(),
                    s.stopped > 0 ? "reached its stroke" : "still pressing", 1e3 * s.stroke, s.delivered);
    lines.push_back(text);
  }
  return lines;
}

bool Presses::stalled(const State& st, std::size_t r) const {
  const State::Ram& s = st.rams[r];
  const DieMotion::Ram& p = rams_[r].press;
  return p.blows == 0 && s.stopped > 0 && !(p.stroke > 0 && s.stroke >= p.stroke);
}

}  // namespace rk
