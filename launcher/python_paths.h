// Where the Python side of an installation lives, seen from the directory of `cosim`: in a build tree the
// package and scripts are both in BUILD/python; an install (`cmake --install`) has the package in
// PREFIX/lib/python3/dist-packages and the scripts (rigid_piston.py, plot_run.py) in PREFIX/share/cosim/python.
#pragma once

#include <filesystem>

namespace cosim::launcher {

struct PythonPaths {
  std::filesystem::path scripts;  // what {python} expands to in a scene's launcher commands
  std::filesystem::path package;  // the directory holding cosim/, put on the started processes' PYTHONPATH
};

inline PythonPaths python_paths(const std::filesystem::path& bin_dir) {
  const std::filesystem::path root = bin_dir.parent_path();
  if (std::filesystem::exists(root / "python" / "cosim")) return {root / "python", root / "python"};
  return {root / "share" / "cosim" / "python", root / "lib" / "python3" / "dist-packages"};
}

}  // namespace cosim::launcher
