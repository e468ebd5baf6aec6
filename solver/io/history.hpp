// The history (CASE/history.csv, columns: shared/history_columns.hpp): one row at t^n every
// time.end / 500 and at the end, gathered over the ranks in one reduction: the energies and their
// balance (docs/scene.md, "Energy"), the contacts, the volume, the constraint error, and per wall,
// die and face its forces. Rank 0 writes.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "boundary/essential_bc.hpp"
#include "contact/die_contact.hpp"
#include "contact/part_contact.hpp"
#include "energy.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class HistoryWriter {  // rank 0 only: one header row, then one row of numbers per call
 public:
  // resume_time >= 0: keep the existing rows before that time (restart), else start a new file.
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns, double resume_time = -1);
  ~HistoryWriter();
  void write(const std::vector<double>& values);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

// The global sums of one row that are not per wall, die or face (they travel first in the reduction).
struct HistorySums {
  double contacts = 0, point_contacts = 0, spring_energy = 0, friction_work = 0, contact_work = 0;
  double volume = 0;        // sum_g w_g J_g, the part's current volume (m^3)
  double ebc_work = 0;      // work of the essential BCs' reactions this step
  double update_work = 0, viscous_work = 0;
  double heat = 0;          // sum_g w_g T_g (K m^3), with a temperature
  double ambient_heat = 0;  // given to the ambient air (J), with conduction
  double part_contacts = 0;  // slaves of the part's contact with itself or between bodies
};

// What a row tells the time loop.
struct HistoryRow {
  Energies energies;           // with the contact work; the EBCs' work is in `external`
  double energy_error = 0;     // |E - E0 - W| / scale (energy_error), reference updates' smoothing excluded
  double kinetic_internal = 0; // KE / internal energy (0 before any internal energy)
  double ebc_error = 0;        // the essential BCs' largest violation (m)
  double penetration = 0;      // the material's deepest point inside a die or rigid wall (m)
};

class History {
 public:
  // Collective. resume_time >= 0: a restart (rank 0 keeps the rows before it).
  History(const std::string& case_dir, const Scene& scene, const Model& md, double resume_time, const Comm& comm);

  // One row at t^n (v_old = v^{n-1/2}; st.v = v^{n+1/2}; dt the step from t^n). Collective: a write
  // that fails on rank 0 (a full disk) stops every rank.
  // `filled`: each die's filled fraction (contact/die_fill.hpp); `energy_scale`: the energy error's
  // scale so far (energy_error), updated
  HistoryRow record(const Model& md, const State& st, const DieContact& dies, const PartContact& parts,
                    const std::vector<double>& filled,
                    const EssentialBcs& ebc,
                    const std::vector<double>& v_old, double dt, double kinetic0, double& energy_scale,
                    const Comm& comm);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<double>& row() const { return row_; }  // the last row written

 private:
  const Scene& scene_;
  std::vector<std::string> columns_;
  std::unique_ptr<HistoryWriter> writer_;  // rank 0
  double volume0_ = 0;                     // the points' reference volumes, summed over ranks
  std::vector<double> sums_, row_;         // sized once: no allocation per row
};

}  // namespace rk
