// The text of RUN/view.py: a ParaView Python state (File > Load State, `paraview --state=view.py`, `pvbatch
// view.py`) that shows a run at its last time step: the fluid coloured by pressure (1D and 2D as the slab's surface,
// 3D as a mid-plane slice), the solid by von Mises stress on its deformed mesh, the interface faces, with colour
// ranges fitted to that time and the camera on everything. With COSIM_VIEW_SCREENSHOT=PNG it also saves a picture.
#pragma once

#include <filesystem>
#include <string>

#include "launcher/run_view.h"

namespace cosim::launcher {

// The script for `v`; series are found beside the script, or in `run_dir` when it is run without a file name.
std::string view_script(const RunView& v, const std::filesystem::path& run_dir);

}  // namespace cosim::launcher
