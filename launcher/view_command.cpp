#include "launcher/view_command.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>

#include "common/app/errors.h"
#include "common/io/atomic_file.h"
#include "launcher/run_view.h"
#include "launcher/view_script.h"

namespace fs = std::filesystem;

namespace cosim::launcher {

namespace {
// `program` found on PATH as execvp would find it; empty when it is not there.
fs::path on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path p = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(p.c_str(), X_OK) == 0 && !fs::is_directory(p)) return p;
  }
  return {};
}
}  // namespace

int view(const fs::path& run_dir, bool write_only) {
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) {
    std::cerr << fmt::format("cosim view: {} is not a directory (the run directory of cosim run)\n", run_dir.string());
    return app::kExitInput;
  }
  const fs::path state = fs::absolute(run_dir) / "view.py";
  if (write_only || !fs::is_regular_file(state, ec)) {
    RunView v;
    try {
      v = read_run_view(run_dir);
    } catch (const std::exception& e) {
      std::cerr << fmt::format("cosim view: {}: {}\n", run_dir.string(), e.what());
      return app::kExitInput;
    }
    if (v.empty()) {
      std::cerr << fmt::format(
          "cosim view: {} holds no run: no fluid/fluid.xmf or solid/solid.xmf with a snapshot (the run directory "
          "of cosim run, or of a solver run alone)\n",
          run_dir.string());
      return app::kExitInput;
    }
    try {
      io::write_file_atomically(state, view_script(v, fs::absolute(run_dir)));
    } catch (const std::exception& e) {
      std::cerr << fmt::format("cosim view: cannot write {}: {}\n", state.string(), e.what());
      return app::kExitIo;
    }
    if (write_only) {
      std::cout << state.string() << "\n";
      return 0;
    }
  }
  if (on_path("paraview").empty()) {
    std::cerr << fmt::format(
        "cosim view: paraview is not installed (on Debian: apt-get install paraview); the run's ParaView state is "
        "{} (paraview --state={}, or File > Load State)\n",
        state.string(), state.string());
    return 127;
  }
  // Without a display ParaView's Qt aborts with a message about platform plugins: say what to do instead.
  const auto set = [](const char* name) { return std::getenv(name) && *std::getenv(name); };
  if (!set("DISPLAY") && !set("WAYLAND_DISPLAY") && !set("QT_QPA_PLATFORM")) {
    std::cerr << fmt::format(
        "cosim view: no display to open ParaView on (DISPLAY is not set); a picture without one: "
        "COSIM_VIEW_SCREENSHOT=view.png pvbatch {}\n",
        state.string());
    return app::kExitInput;
  }
  const std::string arg = "--state=" + state.string();
  ::execlp("paraview", "paraview", arg.c_str(), static_cast<char*>(nullptr));
  std::cerr << fmt::format("cosim view: cannot start paraview: {}\n", std::strerror(errno));
  return 127;
}

}  // namespace cosim::launcher
