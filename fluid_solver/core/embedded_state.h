// What the flow solver needs from the embedded-boundary geometry each cycle (paper sections 6
// and 8, steps 2-6): the category of every cell, the ghost/solid-cut records (image point and
// wall data), and the grid faces between a fluid cell and a ghost/solid-cut cell, per direction.
// Built by fluid_solver/embedded (geometry) and consumed by the solver; plain data.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cosim::fluid {

// Paper Table 1, plus the deep interior of the body, which needs no work.
enum class CellKind : std::uint8_t { Fluid = 0, FluidCut = 1, SolidCut = 2, Ghost = 3, Solid = 4 };

inline bool is_flow_cell(std::uint8_t k) { return k <= static_cast<std::uint8_t>(CellKind::FluidCut); }

// The surface point a record's wall velocity and wall pressure are taken at (EmbeddedState::wall_sources): a coupled
// cycle sets them again in place from the coupler's interface states (FluidSimulation::set_embedded_walls).
struct WallSource {
  int face = -1;                            // the Surface face (-1: none)
  std::array<double, 3> normal{0, 0, 0};    // the normal there
  std::array<double, 3> velocity{0, 0, 0};  // the surface's velocity there
};

// A wall source's values for the records (embedded_bodies.h wall_values).
struct WallValue {
  std::array<double, 3> velocity{0, 0, 0};
  bool has_pressure = false;
  std::array<double, 2> pressure{0, 0};  // [Pa], per phase
};

// A ghost or solid-cut cell: its state comes from the image point (paper step 3, docs/methods.md §5.3).
struct GhostRecord {
  std::size_t cell = 0;                   // padded cell index
  std::array<double, 3> normal{0, 0, 0};  // unit normal at the boundary intercept, solid -> fluid
  std::array<double, 3> wall_velocity{0, 0, 0};
  double distance = 0;                   // |phi| of the cell centre [m]
  double image_distance = 0;             // |x_IP - x_G| [m] (2 |phi| for a mirror image point)
  int stencil_size = 0;                  // flow cells used at the image point
  int wall = -1;                         // its WallSource (-1: none)
  std::array<std::size_t, 8> stencil{};  // padded indices
  std::array<double, 8> weights{};       // sum to 1
  // Interface pressure p_I per phase at the boundary intercept (paper step 5 "p_* = p_I": the coupler's, or
  // the fluid's extrapolated to the wall for the scene's bodies); when present, the ghost pressure is
  // extrapolated through the wall from it (ghost_fill.h).
  bool has_wall_pressure = false;
  std::array<double, 2> wall_pressure{0, 0};  // [Pa], per phase
};

// A grid face between a flow cell and a ghost/solid-cut cell along direction D (paper steps 5-6).
struct WallFace {
  std::size_t fluid_cell = 0;             // cell 1 of the paper's Fig. 4
  std::size_t fluid_cell2 = 0;            // cell 2: the next flow cell away from the wall (== fluid_cell if none)
  std::size_t fluid_cell3 = 0;            // cells 3 and 4 beyond it, for the shock test of the wall velocity
  std::size_t fluid_cell4 = 0;            // extrapolation (each == the one before if none)
  std::size_t solid_cell = 0;             // cell 0: ghost or solid-cut
  bool solid_on_high_side = true;         // the solid cell is at +e_D of the fluid cell
  int wall = -1;                          // the WallSource of its wall velocity (-1: none)
  std::array<double, 3> normal{0, 0, 0};  // interface normal n_I (solid -> fluid)
  std::array<double, 3> wall_velocity{0, 0, 0};  // interface velocity u_I
  double d = 0.5;  // distance from the fluid cell centre to the interface point I, in cells
};

// Thin bodies (fluid_solver/embedded/thin_body.h): the value of the cell across a thin body as the flow cell
// `flow_cell` must see it for its reconstruction along one direction; `ghost.cell` is that cell.
struct SideGhost {
  GhostRecord ghost;
  std::size_t flow_cell = 0;
  bool across_high = true;     // the cell across is at +e_D of the flow cell
  bool blocked = false;        // the cell across is a flow cell: the face between them is a BlockedFace
  double face_distance = 0.5;  // the flow cell's centre to its wall along the line, in cells (WallFace::d)
};

// A grid face between two flow cells with a body thinner than a cell between them: a wall for both. `low` is
// the wall face as the low cell sees it (solid_cell = the high cell), `high` as the high cell sees it.
struct BlockedFace {
  WallFace low, high;
};

struct EmbeddedState {
  bool active = false;
  std::vector<std::uint8_t> kind;                     // per padded cell (CellKind)
  std::vector<GhostRecord> ghosts;                    // ghost and solid-cut cells
  std::array<std::vector<WallFace>, 3> faces;         // per direction
  std::array<std::vector<SideGhost>, 3> side_ghosts;  // per direction, sorted by flow cell then side
  std::array<std::vector<BlockedFace>, 3> blocked;    // per direction
  double max_wall_speed = 0;                          // for the time step
  // The mesh has blocked faces along x (on a block: anywhere in the whole mesh, though the block may have none): the
  // x rows then apply their face fluxes to the cells face by face (solver_sweep.h), on every block as on one rank.
  bool blocked_x = false;
  // On a block of a split mesh: the cells beyond its padded cells that the records read (image-point stencils, the
  // wall limiter's cells). Index total + s (total = the grid's padded cells) is far cell s in the records; its
  // primitives come from its owner every stage (BlockLinks::exchange_far, channel 0).
  std::size_t far_cells = 0;
  std::size_t own_ghosts = 0;  // ghost records of cells the block owns (Grid::owns): the blocks' sum is one rank's
  // Per padded cell, the part of its volume on the fluid side of the surface (the plane through the closest surface
  // point with its normal, docs/methods.md §5.8); computed for embedded.conservative only
  // (add_fluid_fractions; on a block, over its margin grid). Empty: not computed.
  std::vector<double> fluid_fraction;
  // And its rate of change as the surface moves at its velocities [1/s] (d/dt of the plane's fraction:
  // -(u . n) / sum_d |n_d| dx_d where the plane cuts the cell, else 0); empty where no wall moves.
  std::vector<double> fluid_fraction_rate;
  // Where the records' wall velocities and pressures come from (GhostRecord::wall, WallFace::wall); empty for states
  // not built from a surface.
  std::vector<WallSource> wall_sources;
};

// Sets the wall velocities and pressures of every record with a wall source to `values` (one per source).
inline void set_wall_values(EmbeddedState& e, const std::vector<WallValue>& values) {
  const auto ghost = [&](GhostRecord& r) {
    if (r.wall < 0) return;
    const WallValue& v = values[static_cast<std::size_t>(r.wall)];
    r.wall_velocity = v.velocity;
    r.has_wall_pressure = v.has_pressure;
    r.wall_pressure = v.pressure;
  };
  const auto face = [&](WallFace& f) {
    if (f.wall >= 0) f.wall_velocity = values[static_cast<std::size_t>(f.wall)].velocity;
  };
  for (GhostRecord& r : e.ghosts) ghost(r);
  for (int D = 0; D < 3; ++D) {
    for (WallFace& f : e.faces[D]) face(f);
    for (SideGhost& sg : e.side_ghosts[D]) ghost(sg.ghost);
    for (BlockedFace& bf : e.blocked[D]) {
      face(bf.low);
      face(bf.high);
    }
  }
}

}  // namespace cosim::fluid
