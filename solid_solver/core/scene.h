// The solid part of a scene (section `solid:`), read and validated from YAML. Plain data.
// Every key, its unit and its default are listed in docs/scene-keys.md.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/config/config.h"
#include "solid_solver/materials/material.h"
#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct BlockSpec {
  std::string name;
  MaterialModel material;
  double energy = 0.0;  // initial specific internal energy [J/kg]
  bool has_pressure = false;
  double pressure = 0.0;                             // initial pressure [Pa] (sets the energy)
  std::array<double, 3> velocity{0, 0, 0};           // initial velocity [m/s]
  std::array<double, 3> angular_velocity{0, 0, 0};   // initial spin about the block's centre of mass [rad/s]
  bool rigid = false;                                // rigid body: no stress, EOS or hourglass work
  bool has_eos = true;                               // false: a rigid block given without an eos
  std::array<double, 6> deviator{0, 0, 0, 0, 0, 0};  // initial deviatoric stress (xx,yy,zz,xy,yz,zx) [Pa]
};

struct RegionSpec {  // elements whose centroid lies in [lower, upper] (or the sphere) belong to `block`
  std::string block;
  std::array<double, 3> lower{0, 0, 0}, upper{0, 0, 0};
  bool sphere = false;  // a circle (2D) / sphere (3D) of `radius` about `center` instead of the box
  std::array<double, 3> center{0, 0, 0};
  double radius = 0.0;
  bool contains(const std::array<double, 3>& c, int dim) const {
    double r2 = 0;
    bool in = true;
    for (int d = 0; d < dim; ++d) {
      in = in && c[d] >= lower[d] && c[d] <= upper[d];
      r2 += (c[d] - center[d]) * (c[d] - center[d]);
    }
    return sphere ? r2 <= radius * radius : in;
  }
};

// NonReflecting: the first-order absorbing condition of a free field (Lysmer and Kuhlemeyer 1969): the face
// pressure p_ambient + rho c v.n of the element behind it, so that a plane wave leaving normally is not sent back.
enum class BcKind { Fixed, Symmetry, Velocity, Pressure, NonReflecting };

struct BoundarySpec {
  std::string set;        // a face/node set of the mesh, or empty with a node box
  bool node_box = false;  // Fixed/Velocity: the nodes in [lower, upper] (e.g. a clamped edge inside the mesh)
  std::array<double, 3> lower{0, 0, 0}, upper{0, 0, 0};
  BcKind kind = BcKind::Fixed;
  std::array<bool, 3> component{false, false, false};  // Velocity: which components are prescribed
  std::array<double, 3> velocity{0, 0, 0};             // [m/s]
  double pressure = 0.0;                               // [Pa]
  double ramp = 0.0;                                   // [s] linear ramp from 0 (0: applied at once)
};

struct DepositSpec {  // energy [J] added to the element nearest `point`, or split by mass over a box
  bool is_point = true;
  std::array<double, 3> point{0, 0, 0}, lower{0, 0, 0}, upper{0, 0, 0};
  double energy = 0.0;
};

struct Numerics {
  double cfl = 0.5;          // safety factor on the element stable time step
  double q_quadratic = 1.5;  // C_q in q = rho L (C_q^2 L |div v| + C_l c) |div v| (compression only)
  double q_linear = 0.06;    // C_l
  double hourglass = 0.03;   // kappa in the FB viscous hourglass coefficient kappa rho c V^((D-1)/D)
  double dt_growth = 1.2;    // largest ratio of successive time steps
  double dt_initial = 0.0;   // [s] first time step (0: the stable step)
  double dt_min = 0.0;       // [s] a step below this is a numerical failure
  int max_subcycles = 1;     // coupled runs: up to this many solid steps per coupled cycle, the interface
                             // pressure held (1: the solid's stable step limits the coupled step)
};

// ALE gas blocks (solid_solver/ale/): Lagrange + rezone + remap every `every` steps.
struct AleSpec {
  std::vector<std::string> blocks;  // relaxed blocks (gas: an eos, no strength, not rigid); empty: no ALE
  int every = 1;                    // steps between remaps
  int sweeps = 4;                   // Jacobi sweeps of the mesh Laplacian per rezone
};

struct SolidScene {
  std::string name = "scene";
  int dim = 3;
  // Gmsh mesh (mesh.type: gmsh), read while the scene is read, its blocks already in solid.blocks order;
  // null for the built-in box generator.
  std::shared_ptr<const Mesh> file_mesh;
  std::string mesh_file;
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> lower{0, 0, 0}, upper{1, 1, 1};
  std::vector<RegionSpec> regions;
  std::vector<BlockSpec> blocks;
  std::vector<BoundarySpec> boundaries;
  std::vector<DepositSpec> deposits;
  Numerics numerics;
  AleSpec ale;
  double t_end = 0.0;
  long max_steps = 100000000L;
  std::vector<double> output_times;  // always ends with t_end
  bool write_snapshots = true;
  // Rows of block_history.csv also every this many steps (standalone) or coupled cycles; 0: at outputs only.
  int history_every = 0;
  checkpoint::CheckpointPolicy checkpoint;  // solid.checkpoint: sets of a standalone run (any rank count)
  int threads = 0;
};

// How a scene gets the mesh of mesh.type: gmsh from the file's path (resolved against the scene's folder): read_gmsh
// when empty; on several ranks, rank 0 reads it and every rank gets its copy (app/rank_mesh.h). Throws MeshError.
using MeshLoader = std::function<Mesh(const std::string& path)>;

// Reads the `solid:` section of a scene; skips fluid, coupling and launcher. Throws config::ConfigError.
// Relative mesh file names are resolved against base_dir (the scene file's directory).
SolidScene read_solid_scene(config::Node& root, const std::string& base_dir = "", const MeshLoader& load_mesh = {});
SolidScene load_solid_scene(const std::string& file, const std::vector<std::string>& overrides = {},
                            const MeshLoader& load_mesh = {});
SolidScene parse_solid_scene(const std::string& yaml_text, const std::vector<std::string>& overrides = {});

}  // namespace cosim::solid
