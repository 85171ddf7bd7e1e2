// The energy account of a coupled run, DIR/energy_account.json, from the summaries the processes wrote: the
// fluid's flow-cell energy (all phases) and the solid's internal + kinetic energy at the start and the end, the
// solid's boundary work (interface pressures included) and ALE inflow, and their sum. For a closed fluid domain
// the total change is what the interface created (> 0) or lost (< 0); with open fluid boundaries it also holds
// the energy that crossed them. Per unit depth (J/m) in 2D.
#pragma once

#include <filesystem>
#include <string>

namespace cosim::launcher {

// Writes DIR/energy_account.json (atomically) from what the summaries hold: a solver's summary.json without its
// block (fluid: "totals", solid: "energy"; docs/protocol.md, "summary.json") leaves that part null, without totals,
// and prints a one-line notice on stderr. Returns an empty string, or why nothing could be written (neither part
// readable, or the write failed).
std::string write_energy_account(const std::filesystem::path& run_dir);

}  // namespace cosim::launcher
