#include "common/app/rank_failure.h"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "common/io/atomic_file.h"

namespace cosim::app {

void write_silent_rank_summary(const std::filesystem::path& out_dir, const std::string& scene,
                               const std::string& message, int ranks, int silent, int noticed_by, int exit_code) {
  spdlog::error("{}", message);
  const nlohmann::json j{{"status", "failed"},
                         {"error", message},
                         {"scene", scene},
                         {"exit_code", exit_code},
                         {"parallel", {{"ranks", ranks}, {"failed_rank", silent}, {"noticed_by", noticed_by}}}};
  try {
    io::write_file_atomically(out_dir / "summary.json", j.dump(2) + "\n");
  } catch (const std::exception& e) { spdlog::error("cannot write summary.json: {}", e.what()); }
}

bool keeps_another_ranks_summary(int exit_code, int ranks, const std::filesystem::path& out_dir) {
  std::error_code ec;
  return exit_code == 130 && ranks > 1 && std::filesystem::exists(out_dir / "summary.json", ec);
}

}  // namespace cosim::app
