// Plain data exchanged through the coupling protocol (proto/coupling.proto), as the solvers and the coupler
// see it: no protobuf or ZeroMQ types. Flat arrays: `dim` values per face for vectors, and face-major
// `f * phases + k` for per-face-per-phase data. SI units.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cosim::coupling {

enum class Role { Coupler, Fluid, Solid };
const char* role_name(Role r);  // "coupler", "fluid", "solid"

enum class Mode { Impedance, Standard, Characteristic, Robin };
const char* mode_name(Mode m);  // "impedance", "standard", "characteristic", "robin"

// Order of the cycle (docs/protocol.md, "Schemes"). Pipelined: the fluid proposes its next step from t^n right
// after its samples, so the coupler decides the next step before the fluid advances and the solid's step n+1
// runs while the fluid advances step n (the fluid's proposal lags one step). Sequential: the fluid proposes
// from t^{n+1} after its advance; the solvers work one after the other.
enum class Scheme { Pipelined, Sequential };
const char* scheme_name(Scheme s);  // "pipelined", "sequential"

// Solid -> fluid: the solid's exterior faces (solid_solver/core/boundary_faces.h).
struct Faces {
  int dim = 3;
  int count = 0;
  std::vector<double> centre;              // [m], dim per face
  std::vector<double> normal;              // unit, out of the solid, dim per face
  std::vector<double> area;                // [m^2]
  std::vector<double> velocity;            // [m/s], dim per face
  std::vector<double> normal_stress;       // n.sigma.n [Pa], tension positive
  std::vector<double> impedance;           // rho c [Pa s/m], +inf for rigid
  int nodes_per_face = 0;                  // 0: no vertex data
  std::vector<double> vertex_position;     // [m], dim per vertex
  std::vector<std::uint32_t> face_vertex;  // nodes_per_face per face
};

// Fluid -> coupler: fluid state next to each face, per phase.
struct FluidSamples {
  int count = 0;
  int phases = 1;
  std::vector<double> alpha, rho, normal_velocity, pressure, impedance;  // count * phases each
  std::vector<char> wetted;                                              // count
};

// Coupler -> fluid (pressure, normal_velocity per face and phase) and -> solid (face_* per face).
struct InterfaceStates {
  int count = 0;
  int phases = 0;
  std::vector<double> pressure, normal_velocity;            // count * phases [Pa], [m/s]
  std::vector<double> face_pressure, face_normal_velocity;  // count [Pa], [m/s]
  std::vector<char> face_wetted;                            // count (with face_pressure)
  std::vector<double> face_impedance;  // count [Pa s/m] (mode Robin): d(face pressure)/d(face normal velocity)
  Mode mode = Mode::Robin;
};

// What the coupler asks a solver to do next (Client::next()).
struct Directive {
  enum class Kind { Advance, Output, Checkpoint, Stop };
  Kind kind = Kind::Stop;
  long cycle = 0;
  double time = 0;        // t^n [s] (Output: the snapshot time)
  double dt = 0;          // Advance: the step [s]; 0 in cycle 0 (exchange only, no advance)
  int output_index = 0;   // Output: snapshot index
  std::string reason;     // Stop: why
  std::string directory;  // Checkpoint: the set directory to write this solver's part into
};

}  // namespace cosim::coupling
