// A run's history on disk across restarts: a restart appends to the logs after a marked header line (the lines
// that explained a crash stay), run_summary.json describes the latest attempt and run_history.json every one; a
// restart that fails, before or after its processes start, never erases the earlier attempts' summary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "coupled_test_util.h"

using namespace cosim::test;

namespace {
nlohmann::json json_of(const fs::path& p) { return nlohmann::json::parse(read_text(p)); }

int shell(const std::string& cmd, const fs::path& log) {
  const int rc = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

TEST(RunHistory, RestartsAppendToTheLogsAndKeepEveryAttempt) {
  const std::string args = "--set coupling.time.end=0.06 --set coupling.checkpoint.interval=0.03";
  const fs::path dir = run_dir("history");
  fs::remove_all(dir);
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, args), 0) << run_logs(dir);
  const std::string first_fluid_log = read_text(dir / "fluid.log");
  ASSERT_FALSE(first_fluid_log.empty());
  const std::string base =
      bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " + dir.string() + " --quiet ";

  // A restart from a set that does not exist is refused before anything is touched.
  EXPECT_EQ(shell(base + args + " --from 999999", fs::path(dir.string() + ".r0.log")), 2);
  EXPECT_EQ(json_of(dir / "run_summary.json")["status"], "completed");
  EXPECT_EQ(read_text(dir / "fluid.log"), first_fluid_log);

  // A restart to a later end time: the logs gain a second part after a header, both attempts are in the history.
  ASSERT_EQ(shell(base + args + " --set coupling.time.end=0.08", fs::path(dir.string() + ".r1.log")), 0)
      << read_text(dir.string() + ".r1.log") << run_logs(dir);
  for (const char* log : {"fluid.log", "solid.log", "coupler.log"}) {
    const std::string text = read_text(dir / log);
    EXPECT_EQ(count(text, "===== cosim restart at "), 1u) << log << ":\n" << text;
    EXPECT_NE(text.find("(attempt 2) ====="), std::string::npos) << text;
    if (log != std::string("coupler.log")) {  // --quiet: the coupler logs only warnings and errors
      EXPECT_NE(text.find("restarted from cycle"), std::string::npos) << log << ":\n" << text;
    }
  }
  EXPECT_EQ(read_text(dir / "fluid.log").rfind(first_fluid_log, 0), 0u) << "the first attempt's log was lost";
  nlohmann::json s = json_of(dir / "run_summary.json");
  EXPECT_EQ(s["status"], "completed");
  EXPECT_EQ(s["attempt"], 2);
  EXPECT_EQ(s["kind"], "restart");
  EXPECT_NE(s["restart_set"].get<std::string>().find("checkpoints"), std::string::npos) << s.dump(2);
  nlohmann::json h = json_of(dir / "run_history.json");
  ASSERT_EQ(h["attempts"].size(), 2u) << h.dump(2);
  EXPECT_EQ(h["attempts"][0]["kind"], "run");
  EXPECT_EQ(h["attempts"][0]["status"], "completed");
  EXPECT_EQ(h["attempts"][1]["kind"], "restart");
  EXPECT_EQ(h["attempts"][1]["status"], "completed");
  EXPECT_FALSE(h["attempts"][1]["started"].get<std::string>().empty());
  EXPECT_FALSE(h["attempts"][1]["ended"].get<std::string>().empty());

  // A launcher that died without a watcher (the machine stopped) left "running": the next restart says so first.
  s["status"] = "running";
  s["launcher_pid"] = 999999999;
  std::ofstream(dir / "run_summary.json") << s.dump(2);
  // A restart whose processes fail (an end time before the checkpoint's): a third attempt, failed; the earlier
  // ones and their log lines stay.
  EXPECT_NE(shell(base + args + " --set coupling.time.end=0.01", fs::path(dir.string() + ".r2.log")), 0);
  s = json_of(dir / "run_summary.json");
  EXPECT_EQ(s["status"], "failed") << s.dump(2);
  EXPECT_EQ(s["attempt"], 3);
  h = json_of(dir / "run_history.json");
  ASSERT_EQ(h["attempts"].size(), 3u) << h.dump(2);
  EXPECT_EQ(h["attempts"][0]["status"], "completed");
  EXPECT_EQ(h["attempts"][1]["status"], "failed");
  EXPECT_NE(h["attempts"][1]["reason"].get<std::string>().find("ended without writing its summary"), std::string::npos)
      << h.dump(2);
  EXPECT_EQ(h["attempts"][2]["status"], "failed");
  const std::string coupler_log = read_text(dir / "coupler.log");
  EXPECT_EQ(count(coupler_log, "===== cosim restart at "), 2u) << coupler_log;
  EXPECT_NE(coupler_log.find("at or after the scene's end time"), std::string::npos) << coupler_log;
  EXPECT_EQ(read_text(dir / "fluid.log").rfind(first_fluid_log, 0), 0u);

  // A fresh run into the directory starts its logs and history again.
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, "--set coupling.time.end=0.01"), 0) << run_logs(dir);
  EXPECT_EQ(read_text(dir / "coupler.log").find("===== cosim restart"), std::string::npos);
  EXPECT_EQ(json_of(dir / "run_history.json")["attempts"].size(), 1u);
  EXPECT_EQ(json_of(dir / "run_summary.json")["attempt"], 1);
}
