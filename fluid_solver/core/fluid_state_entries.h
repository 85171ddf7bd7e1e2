// The fluid solver's entries of a checkpoint part (fluid.h5): the conserved variables of the interior cells (the
// ghosts are derived: a restart continues bit for bit), the accounts (boundary inflow, the embedded mass account,
// the wall exchange account; absent from older sets), the time, the steps and the conserved variables per cell. One
// pair of functions for the solver's own state (Solver::save_state / restore_state) and the blocks of a split mesh,
// which write their cells into one array of the whole mesh together and each read its block back (block_io.cpp).
// The cells are an array of vars x nz x ny x nx (a set written before it had a shape: one axis, read the same).
#pragma once

#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "common/checkpoint/part_file.h"

namespace cosim::fluid {

// Cells [first, first + count) along x, y, z of a mesh of `mesh` cells per axis: the cells a process holds.
struct CellRange {
  std::array<std::uint64_t, 3> mesh{1, 1, 1}, first{0, 0, 0}, count{1, 1, 1};
  static CellRange of(const std::array<int, 3>& mesh, const std::array<int, 3>& first,
                      const std::array<int, 3>& count) {
    CellRange r;
    for (int d = 0; d < 3; ++d) {
      r.mesh[d] = static_cast<std::uint64_t>(mesh[d]);
      r.first[d] = static_cast<std::uint64_t>(first[d]);
      r.count[d] = static_cast<std::uint64_t>(count[d]);
    }
    return r;
  }
  static CellRange whole(const std::array<int, 3>& n) { return of(n, {0, 0, 0}, n); }
  std::size_t cells() const { return static_cast<std::size_t>(count[0] * count[1] * count[2]); }
  // The array of `vars` variables (slowest) over the mesh, z, y, x, and this range's part of it.
  io::Hdf5Shape shape(int vars) const { return {static_cast<std::uint64_t>(vars), mesh[2], mesh[1], mesh[0]}; }
  io::Hdf5Shape offset() const { return {0, first[2], first[1], first[0]}; }
  io::Hdf5Shape part(int vars) const { return {static_cast<std::uint64_t>(vars), count[2], count[1], count[0]}; }
};

struct FluidStateEntries {
  std::vector<double> conserved;  // vars arrays of the interior cells, one after the other
  // boundary inflow, the embedded mass account (2 values per phase), then the wall exchange account (a set written
  // before it existed: none; FluidSimulation::restore_progress then starts it from zero)
  std::vector<double> accounts;
  double time = 0;
  long steps = 0;
  int vars = 0;
  std::vector<double> body_vertices;  // the scene's embedded bodies' (FluidSimulation::body_state); empty: none
  CellRange range;                    // the cells of `conserved` within the mesh
};

// The account values at the end of `accounts`: `embedded` of the embedded mass account (2 per phase), then `wall`
// of the wall exchange account (phases x (2 + DIM); 0: none written).
inline void write_fluid_state(checkpoint::PartWriter& w, const FluidStateEntries& e, std::size_t embedded,
                              std::size_t wall) {
  if (e.accounts.size() < embedded + wall)
    throw std::logic_error(fmt::format("{} account values, fewer than the {} + {} of the embedded boundary",
                                       e.accounts.size(), embedded, wall));
  const std::size_t inflow = e.accounts.size() - embedded - wall;
  if (e.conserved.size() != static_cast<std::size_t>(e.vars) * e.range.cells())
    throw std::logic_error(
        fmt::format("{} conserved values for {} variables of {} cells", e.conserved.size(), e.vars, e.range.cells()));
  w.put_part("fluid.conserved_cells", e.conserved, e.range.shape(e.vars), e.range.offset(), e.range.part(e.vars));
  w.put("fluid.boundary_inflow", std::span<const double>(e.accounts.data(), inflow));
  w.put("fluid.embedded_mass", std::span<const double>(e.accounts.data() + inflow, embedded));
  if (wall > 0)
    w.put("fluid.embedded_wall_exchange", std::span<const double>(e.accounts.data() + inflow + embedded, wall));
  w.put_scalar("fluid.time", e.time);
  w.put_integer("fluid.steps", e.steps);
  w.put_integer("fluid.conserved_vars", e.vars);
  if (!e.body_vertices.empty()) w.put("fluid.embedded_vertices", e.body_vertices);
}

// Reads what write_fluid_state wrote for `vars` conserved variables of the cells `range`; `inflow`, `embedded` and
// `wall` account values (checkpoint::PartReader::kAny: as many as the part holds; the wall exchange only when the part
// has it, a set from before it existed has none) and `vertices` body vertex values (0: none). Throws naming the file
// when the part does not fit.
inline FluidStateEntries read_fluid_state(const checkpoint::PartReader& r, int vars, const CellRange& range,
                                          std::size_t vertices, std::size_t inflow = checkpoint::PartReader::kAny,
                                          std::size_t embedded = checkpoint::PartReader::kAny,
                                          std::size_t wall = checkpoint::PartReader::kAny) {
  FluidStateEntries e;
  if (r.integer("fluid.conserved_vars") != vars)
    throw std::runtime_error(fmt::format("{}: {} conserved variables per cell, this scene has {}", r.path().string(),
                                         r.integer("fluid.conserved_vars"), vars));
  e.vars = vars;
  e.range = range;
  e.conserved = r.doubles_part("fluid.conserved_cells", range.shape(vars), range.offset(), range.part(vars));
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
