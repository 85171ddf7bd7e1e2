// Where the Python side of an installation lives, seen from the directory of `cosim`: in a build tree the
// package and scripts are both in BUILD/python; an install (`cmake --install`) has the package in
// PREFIX/lib/python3.X/dist-packages (cmake/install_rules.cmake) and the scripts (rigid_piston.py, plot_run.py) in
// PREFIX/share/cosim/python.
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
  std::filesystem::path package = root / "lib" / "python3" / "dist-packages";  // an older install's place
  std::error_code ec;
  for (std::filesystem::directory_iterator it(root / "lib", ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind("python3.", 0) == 0 &&
        std::filesystem::exists(it->path() / "dist-packages" / "cosim", ec))
      package = it->path() / "dist-packages";
  return {root / "share" / "cosim" / "python", package};
}

}  // namespace cosim::launcher
