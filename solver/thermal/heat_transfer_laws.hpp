// The pointwise laws of heat exchange through the part's surface, apart from the loops over faces
// (thermal/heat_transfer.cpp): the heat flux q (W/m^2) INTO the part at a surface temperature T.
// - Convection to the ambient air at Ta: q = h (Ta - T).
// - Radiation of a grey body of emissivity eps to surroundings at Ta: q = eps sigma (Ta^4 - T^4).
// - Contact with a die at Td through an interface of conductance h (the interface heat transfer
//   coefficient of the forging codes): q = h (Td - T).
// For the explicit step's stability each law has a conductance dq/dT bound (W/m^2 K); radiation's,
// 4 eps sigma max(T, Ta)^3, bounds its slope over [T, Ta].
// Pure functions, unit-tested without particles or MPI (tests/unit/test_heat_transfer_laws.cpp).
#pragma once
#include <algorithm>

namespace rk {

inline constexpr double kStefanBoltzmann = 5.670374419e-8;  // W/(m^2 K^4), CODATA 2018 (exact in SI 2019)

inline double convection_flux(double h, double ambient, double T) { return h * (ambient - T); }

inline double radiation_flux(double emissivity, double ambient, double T) {
  const double a2 = ambient * ambient, t2 = T * T;
  return emissivity * kStefanBoltzmann * (a2 * a2 - t2 * t2);
}

inline double radiation_conductance(double emissivity, double ambient, double T) {
  const double hot = std::max(ambient, T);
  return 4 * emissivity * kStefanBoltzmann * hot * hot * hot;
}

inline double contact_flux(double h, double die_temperature, double T) { return h * (die_temperature - T); }

}  // namespace rk
