// What a run directory holds for its ParaView view (RUN/view.py, view_script.h): the fluid, solid and interface
// series, the fluid's dimension and pressure array and the solid's stress array, read from the newest snapshot of
// each series. The series of `cosim run` (fluid/fluid.xmf, solid/solid.xmf, coupler/interface.xmf) or those of a
// solver run alone into the directory itself (fluid.xmf, solid.xmf).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace cosim::launcher {

struct FluidView {
  std::string file;         // the XDMF index, relative to the run directory
  int dimension = 0;        // 1, 2 or 3 (the snapshot's /grid dim)
  std::string pressure;     // <phase>_pressure with one phase, mixture_pressure with two; empty when none
  bool flow_cells = false;  // embedded_category is written: cells inside bodies can be left out
  // 3D: the mid-plane slice (normal z) through the centre of the cell layer at the domain's centre.
  std::array<double, 3> slice_origin{};
};

struct SolidView {
  std::string file;
  std::string stress;  // von_mises, or empty when the snapshot has none
};

struct RunView {
  std::optional<FluidView> fluid;
  std::optional<SolidView> solid;
  std::string interface_file;  // empty when the run has no interface series
  bool empty() const { return !fluid && !solid; }
};

// The view of the series in `run_dir`; empty when it holds neither a fluid nor a solid series with a snapshot.
// Throws std::runtime_error naming the file when a newest snapshot cannot be read.
RunView read_run_view(const std::filesystem::path& run_dir);

// Writes RUN/view.py (atomically) for what the run holds. Returns an empty string, or why nothing was written (no
// series, a snapshot that cannot be read, a write that failed).
std::string write_run_view(const std::filesystem::path& run_dir);

}  // namespace cosim::launcher
