// Whether a process that outlives the others is still at work: the files under its output folder grow or change
// (a final snapshot of a large mesh can take longer than the launcher's grace after the others ended).
#pragma once

#include <cstdint>
#include <filesystem>

namespace cosim::launcher {

struct OutputActivity {
  std::uintmax_t bytes = 0;                  // sum of the files' sizes
  std::filesystem::file_time_type latest{};  // the newest modification time
  std::uintmax_t files = 0;
  bool operator==(const OutputActivity&) const = default;
};

// The files under dir, recursively; an empty record where dir is missing or unreadable (never throws).
OutputActivity output_activity(const std::filesystem::path& dir);

// Seconds a process may go on after the others ended cleanly without writing to its output folder before it is
// stopped: COSIM_END_GRACE_S where set to a positive number, else 10.
double end_grace_seconds();

}  // namespace cosim::launcher
