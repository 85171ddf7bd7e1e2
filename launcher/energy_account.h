// The energy account of a coupled run, DIR/energy_account.json, from the summaries the processes wrote: the
// fluid's flow-cell energy (all phases) and the solid's internal + kinetic energy at the start and the end, the
// solid's boundary work (interface pressures included) and ALE inflow, and their sum. For a closed fluid domain
// the total change is what the interface created (> 0) or lost (< 0); with open fluid boundaries it also holds
// the energy that crossed them. Per unit depth (J/m) in 2D.
#pragma once

#include <filesystem>
#include <string>

namespace cosim::launcher {

// Writes DIR/energy_account.json (atomically); returns an empty string, or why it could not (a summary missing
// or unreadable), in which case nothing is written.
std::string write_energy_account(const std::filesystem::path& run_dir);

}  // namespace cosim::launcher
