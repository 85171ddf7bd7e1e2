// The coupling client as an outside solver gets it: `cmake --install` into a temporary prefix, the C and Fortran
// rigid pistons of examples/clients/ built out of tree against it (CMake find_package; the Fortran one also with
// pkg-config), each run as the solid of configs/piston_2d.yaml, and the piston's travel compared with the run of
// the stock solid_solver and with the Python piston they port. Both checkpoint their state through the library
// (cosim_write_part) and resume from it (cosim_read_part): a restarted run ends bit for bit as the uninterrupted
// one, and a corrupt part is refused by the launcher and by the piston itself, naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "common/checkpoint/checkpoint_sets.h"
#include "tests/coupled/coupled_test_util.h"
#include "tests/coupled/run_compare.h"

using namespace cosim::test;

namespace {

// The scene's first 30 ms (half the piston's first stroke, 0.35 m): a few seconds per run.
const std::string kShort = " --set coupling.time.end=0.03 --set coupling.output.interval=0.01";

int sh(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

bool have_gfortran() { return sh("command -v gfortran > /dev/null 2>&1") == 0; }

// The build installed once into a scratch prefix (shared by the tests of this file).
const fs::path& prefix() {
  static const fs::path p = [] {
    const fs::path dir = scratch_path("client_prefix");
    const int rc = sh("cmake --install " + std::string(COSIM_BINARY_DIR) + " --prefix " + dir.string() + " > " +
                      dir.string() + ".log 2>&1");
    EXPECT_EQ(rc, 0) << read_text(dir.string() + ".log");
    return dir;
  }();
  return p;
}

// Configures and builds examples/clients/NAME against the prefix; returns the program ("" on failure).
fs::path build_example(const std::string& name) {
  const fs::path src = fs::path(COSIM_SOURCE_DIR) / "examples" / "clients" / name;
  const fs::path build = scratch_path("client_build_" + name);
  const std::string log = build.string() + ".log";
  const int rc = sh("cmake -S " + src.string() + " -B " + build.string() + " -G Ninja -DCMAKE_BUILD_TYPE=Release " +
                    "-DCMAKE_PREFIX_PATH=" + prefix().string() + " > " + log + " 2>&1 && cmake --build " +
                    build.string() + " >> " + log + " 2>&1");
  EXPECT_EQ(rc, 0) << read_text(log);
  return rc == 0 ? build / "rigid_piston" : fs::path();
}

const History& solid_solver_run() {
  static const History h = [] {
    const fs::path dir = run_dir("client_reference");
    EXPECT_EQ(cosim_run(scene_file("piston_2d"), dir, kShort), 0) << run_logs(dir);
    return read_history(dir);
  }();
  return h;
}

const History& python_run() {
  static const History h = [] {
    const fs::path dir = run_dir("client_python");
    const std::string exe = "/usr/bin/python3 " + (fs::path(COSIM_BINARY_DIR) / "python" / "rigid_piston.py").string();
    EXPECT_EQ(cosim_run(scene_file("piston_2d"), dir, kShort + " --solid-exe '" + exe + "'"), 0) << run_logs(dir);
    return read_history(dir);
  }();
  return h;
}

// Runs `exe` as the solid and compares its piston with solid_solver's and the Python piston's.
void run_as_solid(const fs::path& exe, const std::string& label) {
  const fs::path dir = run_dir("client_" + label);
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, kShort + " --solid-exe '" + exe.string() + "'"), 0)
      << run_logs(dir);
  const History h = read_history(dir);
  ASSERT_GT(h.size(), 100u);
  EXPECT_NEAR(h.t.back(), 0.03, 1e-12);
  const TrajectoryDifference ref = trajectory_difference(solid_solver_run(), h);
  const TrajectoryDifference py = trajectory_difference(python_run(), h);
  std::printf(
      "[ measured ] %s piston: travel %.6f m; max |dx| %.3e m (%.2e of the travel) from solid_solver, %.3e m from "
      "the Python piston, %zu cycles\n",
      label.c_str(), ref.travel, ref.worst, ref.worst / ref.travel, py.worst, h.size());
  EXPECT_GT(ref.travel, 0.05);
  EXPECT_LT(ref.worst, 1e-4 * ref.travel);
  EXPECT_LT(py.worst, 1e-9 * py.travel);  // the same physics, step for step
  const std::string csv = read_text(dir / "solid" / "piston.csv");
  EXPECT_EQ(csv.rfind("time,x,v,force\n", 0), 0u) << csv;
  EXPECT_GE(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;  // outputs at 0, 10, 20, 30 ms
}

// Runs `exe` as the solid with checkpoints, resumes a copy of the run from its first set and compares the two bit
// for bit (snapshots, interface history, piston.csv); then flips one bit of the piston's part in the newest set:
// `cosim run --restart` refuses that set naming the file, and so does the piston started on it by hand.
void checkpoint_and_resume(const fs::path& exe, const std::string& label) {
  const std::string args = kShort + " --set coupling.checkpoint.interval=0.012 --solid-exe '" + exe.string() + "'";
  const fs::path full = run_dir("client_" + label + "_full"), resumed = run_dir("client_" + label + "_resumed");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), full, args), 0) << run_logs(full);
  const auto sets = cosim::checkpoint::complete_sets(full / "checkpoints");
  ASSERT_EQ(sets.size(), 2u) << "sets after 12 and 24 ms";
  for (const auto& s : sets) {
    ASSERT_TRUE(fs::exists(s.dir / "solid.bin.sha256")) << s.dir;
    EXPECT_NO_THROW(cosim::checkpoint::verify_set(s)) << s.dir;
    EXPECT_EQ(s.manifest["checksums"]["solid.bin"]["bytes"].get<long>(), (9 + 2 * 4) * 8) << s.dir;  // 4 faces
  }
  fs::copy(full, resumed, fs::copy_options::recursive);
  const std::string restart = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                              resumed.string() + " --quiet " + args;
  ASSERT_EQ(sh(restart + " --from " + std::to_string(sets.front().cycle) + " > " + resumed.string() + ".log 2>&1"), 0)
      << read_text(resumed.string() + ".log") << run_logs(resumed);
  std::printf("[ measured ] %s piston restarted from cycle %ld (t = %.6g s)\n", label.c_str(), sets.front().cycle,
              sets.front().time);
  EXPECT_NE(read_text(full / "solid" / "piston.csv"), "");
  expect_same_runs(full, resumed, 3);

  // One bit of the piston's x in the newest set flipped.
  const fs::path part = sets.back().dir.string().replace(0, full.string().size(), resumed.string()) + "/solid.bin";
  {
    std::fstream f(part, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(3 * 8 + 5);
    char c = 0;
    f.read(&c, 1);
    c ^= 0x04;
    f.seekp(3 * 8 + 5);
    f.write(&c, 1);
  }
  const std::string log = resumed.string() + ".corrupt.log";
  EXPECT_EQ(sh(restart + " --from " + std::to_string(sets.back().cycle) + " > " + log + " 2>&1"), 2) << read_text(log);
  EXPECT_NE(read_text(log).find(part.string() + ": SHA-256"), std::string::npos) << read_text(log);
  const std::string by_hand = exe.string() + " " + scene_file("piston_2d").string() + " --out " +
                              (resumed / "by_hand").string() + " --coupler ipc://" + (resumed / "none.sock").string() +
                              " --restart " + part.parent_path().string() + " > " + log + " 2>&1";
  EXPECT_EQ(sh(by_hand), 2) << read_text(log);
  EXPECT_NE(read_text(log).find(part.string() + ": SHA-256"), std::string::npos) << read_text(log);
  EXPECT_NE(read_text(log).find("the part is corrupt"), std::string::npos) << read_text(log);
  EXPECT_FALSE(fs::exists(resumed / "by_hand" / "piston.csv")) << "nothing written from a corrupt part";
}

}  // namespace

// What find_package and pkg-config users get: the shared library with its SONAME, the headers (no ZeroMQ or
// protobuf in them), the CMake package and the .pc file; the library exports its C interface only.
TEST(ClientExamples, InstallHasTheLibraryAndItsPackageFiles) {
  const fs::path p = prefix();
  for (const char* f : {"lib/libcosim_client.so", "lib/libcosim_client.so.1", "include/cosim/client.h",
                        "include/cosim/client.hpp", "include/cosim/cosim_client.f90",
                        "lib/cmake/cosim/cosimConfig.cmake", "lib/cmake/cosim/cosimConfigVersion.cmake",
                        "lib/cmake/cosim/cosimTargets.cmake", "lib/pkgconfig/cosim-client.pc"})
    EXPECT_TRUE(fs::exists(p / f)) << f;
  for (const char* h : {"client.h", "client.hpp"}) {
    const std::string text = read_text(p / "include" / "cosim" / h);
    EXPECT_EQ(text.find("zmq.h"), std::string::npos) << h;
    EXPECT_EQ(text.find("google/protobuf"), std::string::npos) << h;
    EXPECT_EQ(text.find("common/"), std::string::npos) << h;  // nothing of the source tree either
  }
  const fs::path out = scratch_path("client_symbols.txt");
  ASSERT_EQ(sh("nm -D --defined-only " + (p / "lib" / "libcosim_client.so").string() +
               " | awk '{print $3}' | grep -v '^cosim_' | grep -v '^COSIM_CLIENT_1$' > " + out.string() +
               "; test ! -s " + out.string()),
            0)
      << "exported beyond the C interface:\n"
      << read_text(out);
  ASSERT_EQ(
      sh("PKG_CONFIG_PATH=" + (p / "lib" / "pkgconfig").string() + " pkg-config --libs cosim-client > " + out.string()),
      0);
  // "-LDIR -lcosim_client" with DIR the prefix's lib (the .pc finds its prefix from where it lies).
  const std::string libs = read_text(out);
  EXPECT_NE(libs.find("-lcosim_client"), std::string::npos) << libs;
  const std::size_t l = libs.find("-L");
  ASSERT_NE(l, std::string::npos) << libs;
  std::error_code ec;
  EXPECT_TRUE(fs::equivalent(libs.substr(l + 2, libs.find(' ', l) - l - 2), p / "lib", ec)) << libs;
}

TEST(ClientExamples, CPistonReplacesSolidSolver) {
  const fs::path exe = build_example("c");
  ASSERT_FALSE(exe.empty());
  run_as_solid(exe, "c");
}

TEST(ClientExamples, FortranPistonReplacesSolidSolver) {
  if (!have_gfortran()) GTEST_SKIP() << "gfortran is not installed (scripts/install_deps.sh installs it)";
  const fs::path exe = build_example("fortran");
  ASSERT_FALSE(exe.empty());
  run_as_solid(exe, "fortran");
}

TEST(ClientExamples, CPistonResumesFromItsCheckpointBitForBitAndRefusesACorruptPart) {
  const fs::path exe = build_example("c");
  ASSERT_FALSE(exe.empty());
  checkpoint_and_resume(exe, "c");
}

TEST(ClientExamples, FortranPistonResumesFromItsCheckpointBitForBitAndRefusesACorruptPart) {
  if (!have_gfortran()) GTEST_SKIP() << "gfortran is not installed (scripts/install_deps.sh installs it)";
  const fs::path exe = build_example("fortran");
  ASSERT_FALSE(exe.empty());
  checkpoint_and_resume(exe, "fortran");
}

// The pkg-config route of examples/clients/fortran/CMakeLists.txt's comment: one gfortran line.
TEST(ClientExamples, FortranPistonBuildsWithPkgConfig) {
  if (!have_gfortran()) GTEST_SKIP() << "gfortran is not installed (scripts/install_deps.sh installs it)";
  const fs::path dir = scratch_path("client_pkg_config");
  fs::create_directories(dir);
  const std::string pc = "PKG_CONFIG_PATH=" + (prefix() / "lib" / "pkgconfig").string() + " pkg-config ";
  const std::string cmd = "cd " + dir.string() + " && gfortran $(" + pc + "--cflags cosim-client) $(" + pc +
                          "--variable=fortran_module cosim-client) " + COSIM_SOURCE_DIR +
                          "/examples/clients/fortran/rigid_piston.f90 -o rigid_piston $(" + pc +
                          "--libs cosim-client) -Wl,-rpath," + (prefix() / "lib").string() + " > build.log 2>&1";
  ASSERT_EQ(sh(cmd), 0) << read_text(dir / "build.log");
  EXPECT_TRUE(fs::exists(dir / "rigid_piston"));
}
