// The fluid part of a scene, as read and validated from YAML (section `fluid:`).
// Plain data: the solver never sees YAML.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/config/config.h"
#include "common/eos/stiffened_gas.h"
#include "fluid_solver/physics/granular.h"
#include "fluid_solver/physics/particle_stress.h"

namespace cosim::fluid {

enum class FluxKind { AUFS, HLLC, Rusanov };
enum class Reconstruction { FirstOrder, MUSCL };
enum class Limiter { Minmod, VanLeer, MC };
enum class TimeIntegrator { RK2, RK3 };
enum class BoundaryKind { Transmissive, Wall, Inflow, Periodic };
enum class DragLaw { SchillerNaumann, CliftGauvin, AkhatovVainshtein };
enum class VelocityRelaxation { None, Instant, Drag };

// Primitive state of one phase at a point.
struct PhaseValue {
  double alpha = 1.0;
  double rho = 1.0;
  std::array<double, 3> velocity{0, 0, 0};
  double p = 1.0;
};
using MixtureValue = std::vector<PhaseValue>;  // one entry per phase

struct Phase {
  std::string name;
  std::string material;  // library name or "custom"
  eos::StiffenedGas eos;
  double reference_density = 0;              // [kg/m^3] of a condensed library material (0: not checked)
  bool allow_off_reference_density = false;  // the scene means a state more than 10% from it
};

struct Boundary {
  BoundaryKind kind = BoundaryKind::Transmissive;
  MixtureValue inflow;  // for Inflow
};

struct Region {
  enum class Shape { Box, Sphere, HalfSpace } shape = Shape::Box;
  std::array<double, 3> a{0, 0, 0};  // box lower / sphere centre / half-space point
  std::array<double, 3> b{0, 0, 0};  // box upper / half-space normal
  double radius = 0;
  MixtureValue value;
  bool contains(const std::array<double, 3>& x, int dim) const;
};

struct Profile {
  enum class Kind { None, DensityWave, GreshoVortex } kind = Kind::None;
  // density wave: rho = rho0 (1 + amplitude sin(2 pi sum_d k_d x_d / L_d)), uniform velocity and p
  double rho0 = 1.0, amplitude = 0.2, p0 = 1.0;
  std::array<double, 3> wave_number{1, 0, 0};
  std::array<double, 3> velocity{1, 0, 0};
  // Gresho vortex (2D, in the x-y plane): peak speed `speed` at r = 0.2 radius_scale, Mach from `mach`.
  std::array<double, 3> center{0.5, 0.5, 0.5};
  double radius_scale = 1.0, speed = 1.0, mach = 0.1;
};

struct Exchange {
  bool pressure_relaxation = true;
  VelocityRelaxation velocity = VelocityRelaxation::Instant;
  DragLaw drag_law = DragLaw::SchillerNaumann;
  bool heat_transfer = false;
  double particle_diameter = 1e-4;  // [m]
  double gas_viscosity = 1.8e-5;    // [Pa s]
  double gas_conductivity = 0.026;  // [W/(m K)]
  double alpha_min = 1e-8;          // volume-fraction floor
  double trace_alpha = 1e-3;        // below it a phase is a trace: carrier's pressure, own waves not resolved
  // Phase 1 is a dispersed particle phase: carrier's pressure and no own waves everywhere, collision stress
  // between particles (docs/methods.md §2.8).
  bool dispersed = false;
  ParticleStress particle_stress;
  GranularGas granular;  // the dispersed phase's granular temperature (docs/methods.md §2.9)
};

// A body embedded in the background mesh: a closed surface with a prescribed rigid velocity.
struct EmbeddedBody {
  enum class Shape { Box, Circle, Sphere, Polygon, Step } shape = Shape::Box;
  std::array<double, 3> lower{0, 0, 0}, upper{0, 0, 0};  // box / step corners [m]
  std::array<double, 3> center{0, 0, 0};                 // circle / sphere [m]
  double radius = 0;                                     // [m]
  double rotation_deg = 0;                               // box / polygon rotation about z (2D) [deg]
  int segments = 64;                                     // circle segments / sphere refinement
  std::vector<std::array<double, 2>> vertices;           // polygon, counter-clockwise [m]
  std::array<double, 3> velocity{0, 0, 0};               // rigid velocity [m/s]
};

struct EmbeddedSettings {
  bool second_order = true;  // paper steps 5-6 (face states) on top of the ghost cells
  double band = 3.0;         // narrow-band half-width [cells]
  // Ghost pressure: extrapolated through the wall from the wall pressure p_I (ghost_pressure: interface,
  // default; the coupler's p_I, or for the scene's bodies the fluid's pressure extrapolated to the wall) or
  // the image point's copied (image).
  bool ghost_pressure_from_interface = true;
  // No mass through the walls, covered and uncovered cells' contents redistributed (docs/methods.md §5.8).
  bool conservative = false;
  std::vector<EmbeddedBody> bodies;
};

// This process's block of the mesh when the mesh is split over ranks (set by the run, not read from the scene): its
// cells [first, first + count) in global indices, and per axis and side whether a neighbouring block's cells fill its
// ghost layers (an exchange; a periodic side whose partner is another block too) instead of the boundary condition.
struct MeshBlock {
  std::array<int, 3> first{0, 0, 0};
  std::array<int, 3> count{0, 0, 0};  // 0: the whole mesh
  std::array<std::array<bool, 2>, 3> exchanged{};
  bool whole() const { return count[0] == 0; }
  // At the domain's boundary (a boundary condition's face or the periodic seam), not between two blocks inside.
  bool at_domain_edge(int d, int side, const std::array<int, 3>& cells) const {
    return whole() || (side == 0 ? first[d] == 0 : first[d] + count[d] == cells[d]);
  }
};

struct FluidScene {
  std::string name;
  int dim = 1;
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> lower{0, 0, 0}, upper{1, 1, 1};
  std::vector<Phase> phases;
  // boundaries[d][0] = lower side, [d][1] = upper side
  std::array<std::array<Boundary, 2>, 3> boundaries{};

  FluxKind flux = FluxKind::AUFS;
  Reconstruction reconstruction = Reconstruction::MUSCL;
  Limiter limiter = Limiter::VanLeer;
  bool low_mach = false;
  double low_mach_cutoff = 0.0;
  TimeIntegrator integrator = TimeIntegrator::RK2;
  double cfl = 0.4;
  double t_end = 0.0;
  long max_steps = 100000000;
  Exchange exchange;

  EmbeddedSettings embedded;

  MixtureValue background;
  std::vector<Region> regions;
  Profile profile;

  std::vector<double> output_times;         // sorted, in (0, t_end]; a coupled run's come from the coupler
  bool coupled = false;                     // the scene has a coupling: section
  int threads = 0;                          // 0: OpenMP default
  std::array<int, 3> parallel_ranks{0, 0, 0};  // fluid.parallel.ranks: blocks per axis under MPI; 0: chosen
  MeshBlock block;                             // this rank's block (the whole mesh on one rank)
  checkpoint::CheckpointPolicy checkpoint;  // fluid.checkpoint (fluid-only runs); off unless given

  int num_phases() const { return static_cast<int>(phases.size()); }
};

// Read the `fluid:` section of a scene document. Throws config::ConfigError.
// coupled_end > 0 (a coupled scene): fluid.time is optional, its end defaults to coupled_end.
FluidScene read_fluid_scene(config::Node& root, double coupled_end = 0.0);
// Read the whole document (top-level `name`, `description` and `fluid`), rejecting unknown sections.
FluidScene load_fluid_scene(const std::string& file, const std::vector<std::string>& overrides = {});
FluidScene parse_fluid_scene(const std::string& yaml_text, const std::vector<std::string>& overrides = {});

const char* to_string(FluxKind);
const char* to_string(Limiter);

}  // namespace cosim::fluid
