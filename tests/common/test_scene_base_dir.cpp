// Relative file names of a scene (a Gmsh mesh) are resolved against the scene's directory; under `cosim run` the
// solvers read a copy of the scene in the run directory and resolve against the user's scene instead
// ($COSIM_SCENE_DIR for $COSIM_SCENE_COPY), and only for that copy: another scene keeps its own directory.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/config/config.h"
#include "tests/support/scratch_dir.h"

namespace cosim::config {
namespace {

namespace fs = std::filesystem;

TEST(SceneBaseDir, TheCopyResolvesAgainstTheUsersSceneAndOnlyTheCopy) {
  const fs::path root = cosim::test::scratch_path("scene_base_dir");
  fs::create_directories(root / "run");
  fs::create_directories(root / "other");
  const fs::path copy = root / "run" / "scene.yaml", other = root / "other" / "scene.yaml";
  std::ofstream(copy) << "a: 1\n";
  std::ofstream(other) << "a: 1\n";
  ::unsetenv("COSIM_SCENE_DIR");
  ::unsetenv("COSIM_SCENE_COPY");
  EXPECT_EQ(scene_base_dir(copy.string()), (root / "run").string());

  ::setenv("COSIM_SCENE_DIR", "/home/user/scenes", 1);
  ::setenv("COSIM_SCENE_COPY", copy.string().c_str(), 1);
  EXPECT_EQ(scene_base_dir(copy.string()), "/home/user/scenes");
  EXPECT_EQ(scene_base_dir((root / "run" / "." / "scene.yaml").string()), "/home/user/scenes");  // the same file
  EXPECT_EQ(scene_base_dir(other.string()), (root / "other").string());
  ::unsetenv("COSIM_SCENE_DIR");
  ::unsetenv("COSIM_SCENE_COPY");
}

}  // namespace
}  // namespace cosim::config
