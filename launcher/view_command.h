// `cosim view RUN`: opens the run in ParaView with its state, `paraview --state=RUN/view.py` (written first when
// the run has none: a run of an older cosim, a solver run alone into RUN). `cosim view RUN --write` writes it anew
// and opens nothing.
#pragma once

#include <filesystem>

namespace cosim::launcher {

// Replaces this process with ParaView; returns only on failure: 2 when RUN holds no run or there is no display,
// 127 when `paraview` is not on PATH (the message names Debian's package), 4 when view.py cannot be written.
// With `write_only`, returns 0 once view.py is written (its path on stdout). Messages go to stderr.
int view(const std::filesystem::path& run_dir, bool write_only = false);

}  // namespace cosim::launcher
