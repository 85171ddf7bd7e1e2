// DIR/block_history.csv: one row per block at each record (every output, and every `output.history_every`
// steps or coupled cycles): what a structure's response is judged by (paper Fig. 9b: the panel's mean velocity).
//   time [s], step, block (name), mass [kg], velocity_x/y/z (mass-averaged, nodal velocities with each element's
//   mass lumped equally to its corners) [m/s], kinetic_energy, internal_energy, plastic_work [J],
//   max_von_mises [Pa], max_plastic_strain [-]
// Per unit depth (kg/m, J/m) in 2D. Each record's rows reach the file whole or not at all (a full disk leaves a
// valid table); a run into the same directory replaces the file.
#pragma once

#include <filesystem>
#include <vector>

#include "common/checkpoint/part_file.h"
#include "common/io/line_log.h"
#include "solid_solver/core/simulation.h"

namespace cosim::solid {

struct BlockTotals {
  double mass = 0, momentum[3] = {0, 0, 0}, kinetic = 0, internal = 0, plastic_work = 0;
  double max_von_mises = 0, max_plastic_strain = 0;
};

// Totals of every block (mesh.block_names order) at the current state.
std::vector<BlockTotals> block_totals(const Simulation& sim);

class BlockHistory {
 public:
  // Throws std::runtime_error naming the file. With `resume`, the table continues from the checkpoint (save()).
  explicit BlockHistory(const std::filesystem::path& dir, const checkpoint::PartReader* resume = nullptr);
  void save(checkpoint::PartWriter& w) const;
  // Appends the rows of the current state, once per step (a second call at the same step writes nothing).
  void record(const Simulation& sim);

 private:
  io::LineLog out_;
  long last_step_ = -1;
};

}  // namespace cosim::solid
