// Per-cycle records of a coupled run in the output directory:
//   interface_history.csv  cycle, time [s], dt [s], force on the solid F = -sum p_face A n [N] (x, y, z),
//                          area-weighted mean face velocity [m/s] and centre [m] (x, y, z), mean face pressure [Pa]
//   timing.csv             cycle, wall [s] (DtDecision n sent .. DtDecision n+1 sent, or the end of cycle n's
//                          checkpoint), solid and fluid step work (reported with the messages received in that
//                          window, outputs excluded), coupler work (interface conditions, history, snapshots),
//                          output (the solvers' snapshots and checkpoint parts on the critical path),
//                          communication/wait [s] (CycleTiming::comm)
//   interface_phases.csv   with two or more fluid phases: cycle, time [s], and per phase k the share of the force
//                          on the solid that phase delivers, F_k = -sum_faces (alpha_k / sum_j alpha_j) p_I,k A n
//                          [N] (x, y, z; columns <phase>_force_x ...): the face pressure the solid receives is
//                          sum_k alpha_k p_I,k / sum_j alpha_j, so the F_k add up to interface_history's force
//   progress.txt           one line "cycle time t_end", replaced at most twice a second (the launcher reads it)
//   interface_NNNNNN.h5 + interface.xmf   at every output request: the interface faces (segments in 2D, quads
//                          in 3D, as the solid sent them) with cell fields pressure, normal_velocity (u_I . n),
//                          normal_stress, impedance, wetted, normal, velocity (ParaView: Xdmf3 reader)
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "common/checkpoint/part_file.h"
#include "common/io/line_log.h"

#include "common/coupling/types.h"
#include "common/io/snapshot_writer.h"

namespace cosim::coupler {

struct CycleTiming {
  double wall = 0, solid = 0, fluid = 0, coupler = 0;
  double output = 0;        // snapshots and checkpoint parts on the cycle's critical path (output_on_path)
  bool overlapped = false;  // pipelined scheme: the solid's step runs during the fluid's
  // Of each solver's work reported in this cycle, what it may have done before the cycle began: the pipelined
  // fluid steps as soon as it has the states, while the cycle before still waits for the solid's proposal; in the
  // first cycle, each may work from its Hello on [s].
  double solid_spill = 0, fluid_spill = 0;
  double solid_on_path() const { return std::max(0.0, solid - solid_spill); }
  double fluid_on_path() const { return std::max(0.0, fluid - fluid_spill); }
  // The solvers' steps on the critical path: sequential, one after the other; pipelined, they overlap.
  double steps() const {
    return overlapped ? std::max(solid_on_path(), fluid_on_path()) : solid_on_path() + fluid_on_path();
  }
  // Everything that is not solver, output or coupler work: communication and waiting.
  double comm() const { return wall - coupler - output - steps(); }
};

// The wall time outputs add to a cycle whose solvers stepped for `t.solid`, `t.fluid` (their outputs excluded) and
// wrote outputs for `solid_out`, `fluid_out` at its start: each solver's output precedes its own step, both
// solvers write at once, and the critical path is at least each solver's output plus its step.
double output_on_path(const CycleTiming& t, double solid_out, double fluid_out);

class History {
 public:
  // Throws CouplingError naming the file. With `resume`, the tables and the interface series continue from the
  // checkpoint (save()).
  explicit History(const std::filesystem::path& dir, const checkpoint::PartReader* resume = nullptr);
  void save(checkpoint::PartWriter& w) const;
  void record(long cycle, double time, double dt, const coupling::Faces& faces, const coupling::InterfaceStates& st);
  // interface_phases.csv's row (nothing with one phase); `names`: the fluid's phases, for the header.
  void record_phases(long cycle, double time, const coupling::Faces& faces, const coupling::FluidSamples& samples,
                     const coupling::InterfaceStates& st, const std::vector<std::string>& names);
  void record_timing(long cycle, const CycleTiming& timing);
  void progress(long cycle, double time, double t_end, double dt, bool force = false);
  // One interface snapshot; skipped when the faces carry no vertex data (or triangles).
  void snapshot(long cycle, double time, const coupling::Faces& faces, const coupling::InterfaceStates& st);

 private:
  std::filesystem::path dir_;
  io::LineLog hist_, timing_;
  std::optional<io::LineLog> phases_;  // interface_phases.csv, opened at the first two-phase row
  double last_progress_ = -1e300;
  io::SnapshotSeries interface_;
};

}  // namespace cosim::coupler
