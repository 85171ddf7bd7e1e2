// A scene's launcher: commands may name programs kept next to the scene ({scene_dir}): they are found from the
// directory of the scene the user gave, whatever the working directory and however the scene was named.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "coupling_test_util.h"

using namespace cosim::test;

namespace {

TEST(SceneDirPrograms, ALauncherCommandNextToTheSceneIsFound) {
  const fs::path dir = test_dir("scene_dir_programs");
  const fs::path where = dir / "study";
  fs::create_directories(where);
  std::ofstream(where / "scene.yaml") << "name: study\nfluid: {dummy: 1}\nsolid: {dummy: 1}\n"
                                      << "launcher: {fluid: '{scene_dir}/wait.sh', solid: '{scene_dir}/solid.sh'}\n"
                                      << "coupling:\n  time: {end: 1.0}\n";
  std::ofstream(where / "wait.sh") << "#!/bin/sh\nexec sleep 30\n";
  std::ofstream(where / "solid.sh") << "#!/bin/sh\necho \"solid from the scene's directory: $1\" >&2\nexit 3\n";
  for (const char* f : {"wait.sh", "solid.sh"}) fs::permissions(where / f, fs::perms::owner_all);
  // the scene named relative to a working directory that is not its own
  const fs::path run = dir / "run";
  const std::string cmd = "cd " + dir.string() + " && " + bin("cosim").string() + " run study/scene.yaml --out " +
                          run.string() + " --quiet > " + (dir / "cosim.log").string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 3) << read_file(dir / "cosim.log");
  EXPECT_NE(read_file(run / "solid.log").find("solid from the scene's directory: " + (run / "scene.yaml").string()),
            std::string::npos)
      << read_file(run / "solid.log");
  EXPECT_NE(read_file(run / "launch.json").find((where / "solid.sh").string()), std::string::npos)
      << read_file(run / "launch.json");
}

}  // namespace
