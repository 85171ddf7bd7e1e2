// Command lines a user gets wrong are answered with the word they typed and the closest valid one (exit 2): an
// option before cosim's command, a single-dash option, no command at all. Every program's --help ends with
// examples.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <stdexcept>
#include <utility>
#include <vector>

#include "coupling_test_util.h"
#include "launcher/launch.h"

using namespace cosim::test;

namespace {

TEST(CommandLine, CosimNamesAnOptionBeforeTheCommandAndAMissingCommand) {
  const fs::path dir = test_dir("cli_order");
  const std::string cosim = bin("cosim").string();
  auto [rc, log] = run_shell(dir, cosim);
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: a command is required: cosim run SCENE.yaml [options]"), std::string::npos) << log;
  std::tie(rc, log) = run_shell(dir, cosim + " --output x run s.yaml");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: unknown option '--output' (did you mean '--out'?); options follow the command"),
            std::string::npos)
      << log;
  std::tie(rc, log) = run_shell(dir, cosim + " run --version");  // the version is known after the command too
  EXPECT_EQ(rc, 0) << log;
  EXPECT_EQ(log.rfind("cosim 0.", 0), 0u) << log;
  std::tie(rc, log) = run_shell(dir, cosim + " --out x run s.yaml");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: '--out' is an option of 'run': cosim run SCENE.yaml --out ..."), std::string::npos) << log;
}

TEST(CommandLine, ASingleDashOptionIsNamedWithTheLongOneItAbbreviates) {
  const fs::path dir = test_dir("cli_dash");
  auto [rc, log] = run_shell(dir, bin("cosim").string() + " run s.yaml -o x");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: unknown option '-o' (did you mean '--out'?)"), std::string::npos) << log;
  std::tie(rc, log) = run_shell(dir, bin("cosim").string() + " run s.yaml -out x");
  EXPECT_NE(log.find("cosim: unknown option '-out' (did you mean '--out'?)"), std::string::npos) << log;
  std::tie(rc, log) = run_shell(dir, bin("fluid_solver").string() + " s.yaml -q -o x");  // -q is --quiet
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("fluid_solver: unknown option '-o' (did you mean '--out'?)"), std::string::npos) << log;
  // a negative number is a value, not an option
  std::tie(rc, log) = run_shell(dir, bin("cosim").string() + " run s.yaml --progress-every -5");
  EXPECT_EQ(log.find("unknown option"), std::string::npos) << log;
}

TEST(CommandLine, HelpEndsWithExamples) {
  const fs::path dir = test_dir("cli_help");
  for (const std::string cmd :
       {"cosim --help", "cosim run --help", "fluid_solver --help", "solid_solver --help", "coupler --help"}) {
    const auto [rc, log] = run_shell(dir, (fs::path(COSIM_BINARY_DIR) / "bin").string() + "/" + cmd);
    EXPECT_EQ(rc, 0) << cmd;
    const auto at = log.find("\nExamples:\n");
    ASSERT_NE(at, std::string::npos) << cmd << "\n" << log;
    const std::string program = cmd.substr(0, cmd.find(' '));
    EXPECT_NE(log.find("  " + program + " ", at), std::string::npos) << cmd << "\n" << log;
    EXPECT_NE(log.find(" configs/", at), std::string::npos) << cmd << "\n" << log;
  }
  // the examples name scenes that exist
  for (const char* scene : {"piston_2d", "sod", "shock_panel_2d", "solid_sedov_lulesh"})
    EXPECT_TRUE(fs::exists(fs::path(COSIM_SOURCE_DIR) / "configs" / (std::string(scene) + ".yaml"))) << scene;
}

}  // namespace

// Commands (--fluid-exe, a scene's launcher: keys) are split into words as a shell splits plain words: quotes keep
// blanks, a backslash escapes; an unclosed quote is refused.
TEST(CommandLine, CommandsAreSplitWithQuotesAsAShellDoes) {
  using cosim::launcher::split_command;
  EXPECT_EQ(split_command("  a  b\tc "), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(split_command("python3 '/my dir/solid.py' --name \"x y\" z\\ w"),
            (std::vector<std::string>{"python3", "/my dir/solid.py", "--name", "x y", "z w"}));
  EXPECT_EQ(split_command(R"(a "q\"uote" 'it''s' "")"), (std::vector<std::string>{"a", "q\"uote", "its", ""}));
  EXPECT_THROW(split_command("python3 'unclosed"), std::runtime_error);
}
