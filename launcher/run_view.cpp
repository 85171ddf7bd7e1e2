#include "launcher/run_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/io/atomic_file.h"
#include "common/io/hdf5_file.h"
#include "launcher/view_script.h"

namespace fs = std::filesystem;

namespace cosim::launcher {

namespace {
// The first of `candidates` (relative to `run_dir`) that exists, or an empty path.
fs::path first_existing(const fs::path& run_dir, std::initializer_list<const char*> candidates) {
  std::error_code ec;
  for (const char* c : candidates)
    if (fs::is_regular_file(run_dir / c, ec)) return c;
  return {};
}

// The newest snapshot of a series: STEM_NNNNNN.h5 beside its index with the largest number; empty when none.
fs::path newest_snapshot(const fs::path& index) {
  const std::string prefix = index.stem().string() + "_";
  fs::path newest;
  std::string newest_number;
  std::error_code ec;
  for (fs::directory_iterator it(index.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (it->path().extension() != ".h5" || name.rfind(prefix, 0) != 0) continue;
    const std::string number = it->path().stem().string().substr(prefix.size());
    if (number.empty() || !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    const auto longer = [](const std::string& a, const std::string& b) {
      return a.size() != b.size() ? a.size() > b.size() : a > b;
    };
    if (newest.empty() || longer(number, newest_number)) {
      newest = it->path();
      newest_number = number;
    }
  }
  return newest;
}

bool has_dataset(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

FluidView fluid_view(const fs::path& file, const fs::path& snapshot) {
  const io::Hdf5File h5(snapshot, io::Hdf5File::Mode::ReadOnly);
  FluidView f;
  f.file = file.string();
  f.dimension = static_cast<int>(h5.read_int64_attribute("/grid", "dim").at(0));
  const std::vector<std::string> names = h5.dataset_names();
  if (has_dataset(names, "/cell/mixture_pressure")) {
    f.pressure = "mixture_pressure";
  } else {
    for (const std::string& n : names)
      if (n.rfind("/cell/", 0) == 0 && n.size() > 15 && n.compare(n.size() - 9, 9, "_pressure") == 0) {
        f.pressure = n.substr(6);
        break;
      }
  }
  f.flow_cells = has_dataset(names, "/cell/embedded_category");
  if (f.dimension == 3) {
    const std::vector<std::int64_t> cells = h5.read_int64_attribute("/grid", "cells");
    const std::vector<double> origin = h5.read_double_attribute("/grid", "origin");
    const std::vector<double> spacing = h5.read_double_attribute("/grid", "spacing");
    for (int d = 0; d < 3; ++d)
      f.slice_origin[d] = origin.at(d) + 0.5 * static_cast<double>(cells.at(d)) * spacing.at(d);
    // z through the middle of a cell layer, not along the faces between two layers (an even number of layers)
    f.slice_origin[2] = origin[2] + (std::floor(0.5 * static_cast<double>(cells[2])) + 0.5) * spacing[2];
  }
  return f;
}

SolidView solid_view(const fs::path& file, const fs::path& snapshot) {
  const io::Hdf5File h5(snapshot, io::Hdf5File::Mode::ReadOnly);
  return {file.string(), has_dataset(h5.dataset_names(), "/cell/von_mises") ? "von_mises" : ""};
}
}  // namespace

RunView read_run_view(const fs::path& run_dir) {
  RunView v;
  if (const fs::path f = first_existing(run_dir, {"fluid/fluid.xmf", "fluid.xmf"}); !f.empty())
    if (const fs::path s = newest_snapshot(run_dir / f); !s.empty()) v.fluid = fluid_view(f, s);
  if (const fs::path f = first_existing(run_dir, {"solid/solid.xmf", "solid.xmf"}); !f.empty())
    if (const fs::path s = newest_snapshot(run_dir / f); !s.empty()) v.solid = solid_view(f, s);
  if (const fs::path f = first_existing(run_dir, {"coupler/interface.xmf"}); !f.empty())
    if (!newest_snapshot(run_dir / f).empty()) v.interface_file = f.string();
  return v;
}

std::string write_run_view(const fs::path& run_dir) {
  try {
    const RunView v = read_run_view(run_dir);
    if (v.empty()) return "the run directory holds no fluid or solid snapshot";
    io::write_file_atomically(run_dir / "view.py", view_script(v, fs::absolute(run_dir)));
    return "";
  } catch (const std::exception& e) { return e.what(); }
}

}  // namespace cosim::launcher
