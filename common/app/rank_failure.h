// What a rank of a run on several ranks writes when the run fails: the summary of the rank that noticed another one
// fall silent (RankWatchdog), and whether a rank that was interrupted leaves the summary of the rank whose failure
// ended the run. The same for every solver on ranks.
#pragma once

#include <filesystem>
#include <string>

namespace cosim::app {

// summary.json of a run stopped because rank `silent` fell silent, written by rank `noticed_by` (from the watchdog's
// thread: only what it is given). A summary that cannot be written is logged.
void write_silent_rank_summary(const std::filesystem::path& out_dir, const std::string& scene,
                               const std::string& message, int ranks, int silent, int noticed_by, int exit_code);

// A rank interrupted (exit code 130) by the abort of another rank that failed, or by the rank whose watchdog noticed
// a silent one: the summary that rank wrote before its abort is the run's, and this rank leaves it.
bool keeps_another_ranks_summary(int exit_code, int ranks, const std::filesystem::path& out_dir);

}  // namespace cosim::app
