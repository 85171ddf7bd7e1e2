// The fluid solver's entries of a checkpoint part (fluid.h5): the conserved variables of the interior cells (the
// ghosts are derived: a restart continues bit for bit), the accounts (boundary inflow, the embedded mass account,
// the wall exchange account; absent from older sets), the time, the steps and the conserved variables per cell. One
// pair of functions for the solver's own state (Solver::save_state / restore_state) and the whole mesh gathered from
// the blocks of a split mesh (block_io.cpp).
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

#include "common/checkpoint/part_file.h"

namespace cosim::fluid {

struct FluidStateEntries {
  std::vector<double> conserved;  // vars arrays of the interior cells, one after the other
  // boundary inflow, the embedded mass account (2 values per phase), then the wall exchange account (a set written
  // before it existed: none; FluidSimulation::restore_progress then starts it from zero)
  std::vector<double> accounts;
  double time = 0;
  long steps = 0;
  int vars = 0;
  std::vector<double> body_vertices;  // the scene's embedded bodies' (FluidSimulation::body_state); empty: none
};

// The account values at the end of `accounts`: `embedded` of the embedded mass account (2 per phase), then `wall`
// of the wall exchange account (phases x (2 + DIM); 0: none written).
inline void write_fluid_state(checkpoint::PartWriter& w, const FluidStateEntries& e, std::size_t embedded,
                              std::size_t wall) {
  if (e.accounts.size() < embedded + wall)
    throw std::logic_error(fmt::format("{} account values, fewer than the {} + {} of the embedded boundary",
                                       e.accounts.size(), embedded, wall));
  const std::size_t inflow = e.accounts.size() - embedded - wall;
  w.put("fluid.conserved_cells", e.conserved);
  w.put("fluid.boundary_inflow", std::span<const double>(e.accounts.data(), inflow));
  w.put("fluid.embedded_mass", std::span<const double>(e.accounts.data() + inflow, embedded));
  if (wall > 0)
    w.put("fluid.embedded_wall_exchange", std::span<const double>(e.accounts.data() + inflow + embedded, wall));
  w.put_scalar("fluid.time", e.time);
  w.put_integer("fluid.steps", e.steps);
  w.put_integer("fluid.conserved_vars", e.vars);
  if (!e.body_vertices.empty()) w.put("fluid.embedded_vertices", e.body_vertices);
}

// Reads what write_fluid_state wrote for `vars` conserved variables of `cells` cells; `inflow`, `embedded` and `wall`
// account values (checkpoint::PartReader::kAny: as many as the part holds; the wall exchange only when the part has
// it, a set from before it existed has none) and `vertices` body vertex values (0: none). Throws naming the file
// when the part does not fit.
inline FluidStateEntries read_fluid_state(const checkpoint::PartReader& r, int vars, std::size_t cells,
                                          std::size_t vertices, std::size_t inflow = checkpoint::PartReader::kAny,
                                          std::size_t embedded = checkpoint::PartReader::kAny,
                                          std::size_t wall = checkpoint::PartReader::kAny) {
  FluidStateEntries e;
  if (r.integer("fluid.conserved_vars") != vars)
    throw std::runtime_error(fmt::format("{}: {} conserved variables per cell, this scene has {}", r.path().string(),
                                         r.integer("fluid.conserved_vars"), vars));
  e.vars = vars;
  e.conserved = r.doubles("fluid.conserved_cells", static_cast<std::size_t>(vars) * cells);
  e.accounts = r.doubles("fluid.boundary_inflow", inflow);
  const std::vector<double> em = r.doubles("fluid.embedded_mass", embedded);
  e.accounts.insert(e.accounts.end(), em.begin(), em.end());
  if (r.has("fluid.embedded_wall_exchange")) {
    const std::vector<double> wx = r.doubles("fluid.embedded_wall_exchange", wall);
    e.accounts.insert(e.accounts.end(), wx.begin(), wx.end());
  }
  e.time = r.scalar("fluid.time");
  e.steps = static_cast<long>(r.integer("fluid.steps"));
  if (vertices > 0) e.body_vertices = r.doubles("fluid.embedded_vertices", vertices);
  return e;
}

}  // namespace cosim::fluid
