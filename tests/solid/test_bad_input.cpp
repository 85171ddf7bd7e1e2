// Bad input: clear messages (file:line, key, what was expected) and exit code 2; a run writes summary.json.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "solid_solver/core/scene.h"

using namespace cosim::solid;
namespace fs = std::filesystem;

namespace {
const char* kGood = R"(
name: tiny
description: a tiny elastic block
solid:
  mesh: {cells: [2, 2], lower: [0, 0], upper: [1, 1]}
  blocks:
    - {name: a, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {energy: 1.0}}
  boundaries:
    - {set: x_lower, type: fixed}
  time: {end: 0.01}
fluid: {anything: 1}
coupling: {whatever: true}
)";

std::string error_of(const std::string& yaml, const std::vector<std::string>& ov = {}) {
  try {
    parse_solid_scene(yaml, ov);
  } catch (const cosim::config::ConfigError& e) { return e.what(); }
  return "";
}

std::string replace(std::string s, const std::string& a, const std::string& b) {
  const auto p = s.find(a);
  EXPECT_NE(p, std::string::npos) << a;
  return s.replace(p, a.size(), b);
}

int run_solver(const std::string& args, std::string& log) {
  const fs::path exe = fs::path(COSIM_BINARY_DIR) / "bin" / "solid_solver";
  const fs::path out = fs::temp_directory_path() / "solid_bad_input_log.txt";
  const std::string cmd = exe.string() + " " + args + " > " + out.string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream in(out);
  log.assign(std::istreambuf_iterator<char>(in), {});
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
}  // namespace

TEST(SolidInput, GoodSceneParses) {
  EXPECT_EQ(error_of(kGood), "");
  SolidScene s = parse_solid_scene(kGood);
  EXPECT_EQ(s.dim, 2);
  EXPECT_EQ(s.name, "tiny");
}

TEST(SolidInput, TypoKeyGetsSuggestion) {
  const std::string e = error_of(replace(kGood, "density: 1.0", "densty: 1.0"));
  EXPECT_NE(e.find("densty"), std::string::npos) << e;
  EXPECT_NE(e.find("density"), std::string::npos) << e;
}

TEST(SolidInput, NegativeValueRejected) {
  const std::string e = error_of(replace(kGood, "density: 1.0", "density: -1.0"));
  EXPECT_NE(e.find("solid.blocks"), std::string::npos) << e;
  EXPECT_NE(e.find("> 0"), std::string::npos) << e;
  EXPECT_NE(error_of(kGood, {"solid.time.end=-1"}).find("--set solid.time.end"), std::string::npos);
}

TEST(SolidInput, UnknownSetAndBlockNamed) {
  const std::string e = error_of(replace(kGood, "set: x_lower", "set: x_lowr"));
  EXPECT_NE(e.find("did you mean 'x_lower'"), std::string::npos) << e;
  const std::string e3 = error_of(replace(kGood, "set: x_lower", "set: z_lower"));
  EXPECT_NE(e3.find("z_lower"), std::string::npos) << e3;
  const std::string e2 = error_of(replace(kGood, "eos: {type: ideal_gas, gamma: 1.4}", "material: unobtainium"));
  EXPECT_NE(e2.find("unobtainium"), std::string::npos) << e2;
  EXPECT_NE(e2.find("steel"), std::string::npos) << e2;
}

TEST(SolidInput, ExecutableExitCodes) {
  const fs::path exe = fs::path(COSIM_BINARY_DIR) / "bin" / "solid_solver";
  if (!fs::exists(exe)) GTEST_SKIP() << "solid_solver not built";
  const fs::path dir = fs::temp_directory_path() / "solid_input_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path good = dir / "good.yaml", bad = dir / "bad.yaml", broken = dir / "broken.yaml";
  std::ofstream(good) << kGood;
  std::ofstream(bad) << replace(kGood, "density: 1.0", "densty: 1.0");
  std::ofstream(broken) << "solid: {mesh: [unclosed\n";
  std::string log;
  EXPECT_EQ(run_solver(bad.string() + " --out " + (dir / "o1").string() + " --quiet", log), 2);
  EXPECT_NE(log.find("bad.yaml"), std::string::npos) << log;
  EXPECT_NE(log.find("density"), std::string::npos) << log;
  EXPECT_EQ(run_solver(broken.string() + " --out " + (dir / "o2").string() + " --quiet", log), 2);
  EXPECT_NE(log.find("broken.yaml"), std::string::npos) << log;
  EXPECT_EQ(run_solver((dir / "missing.yaml").string() + " --out " + (dir / "o3").string() + " --quiet", log), 2);
  EXPECT_EQ(run_solver(good.string() + " --out " + (dir / "o4").string() + " --quiet --set solid.time.end=-2", log), 2);
  EXPECT_NE(log.find("--set solid.time.end"), std::string::npos) << log;
  // A restart of a standalone solid from a folder that is not a checkpoint set.
  EXPECT_EQ(run_solver(good.string() + " --out " + (dir / "o8").string() + " --quiet --restart " + dir.string(), log),
            2);
  EXPECT_NE(log.find("--restart " + dir.string() + ": " + dir.string() + ": no manifest.json"), std::string::npos)
      << log;
  for (const char* o : {"o1", "o2", "o3", "o4", "o8"}) EXPECT_FALSE(fs::exists(dir / o)) << o;  // no empty folder
  // A scene that parses but cannot be set up (its Gmsh mesh does not exist): exit 2, no output folder either.
  EXPECT_EQ(run_solver(good.string() + " --out " + (dir / "o7").string() +
                           " --quiet --set 'solid.mesh={type: gmsh, file: nowhere.msh}'",
                       log),
            2)
      << log;
  EXPECT_NE(log.find("nowhere.msh"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "o7"));
  // A good run: summary.json with the energy budget.
  EXPECT_EQ(run_solver(good.string() + " --out " + (dir / "o5").string() + " --quiet", log), 0) << log;
  std::ifstream in(dir / "o5" / "summary.json");
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["status"], "completed");
  EXPECT_GT(j["steps"].get<long>(), 0);
  EXPECT_LT(std::abs(j["energy"]["relative_balance_error"].get<double>()), 1e-12);
  EXPECT_TRUE(fs::exists(dir / "o5" / "solid.xmf"));
  // A numerical failure: an element inverted by a huge prescribed velocity -> exit code 3, element named.
  EXPECT_EQ(run_solver(good.string() + " --out " + (dir / "o6").string() +
                           " --quiet --set 'solid.boundaries=[{set: x_lower, type: fixed}, {set: x_upper, type: "
                           "velocity, vx: -1000}]'"
                           " --set solid.numerics.q_quadratic=0 --set solid.numerics.q_linear=0",
                       log),
            3)
      << log;
  EXPECT_NE(log.find("element"), std::string::npos) << log;
  EXPECT_NE(log.find("inverted"), std::string::npos) << log;
  // A step below the floor (here a floor above any stable step): exit code 3, the limiting element named with its
  // block, place and state; the last snapshot is kept.
  EXPECT_EQ(
      run_solver(good.string() + " --out " + (dir / "o8").string() + " --quiet --set solid.numerics.dt_min=1", log), 3)
      << log;
  EXPECT_NE(log.find("below the floor 1 s (numerics.dt_min); element "), std::string::npos) << log;
  EXPECT_NE(log.find("of block 'a' at ("), std::string::npos) << log;
  EXPECT_NE(log.find("sound speed"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(dir / "o8" / "solid.xmf"));
}
