// Coupled scenes other than the piston's accuracy: paper 9.2 advection with a solid_solver block, the
// protocol transcript of the real piston scene, and a solver killed in the middle of a real run.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "common/io/hdf5_file.h"
#include "coupled_test_util.h"

using namespace cosim;
using namespace cosim::test;

// Paper 9.2: a rigid block moving diagonally with the flow, 13 x 13, 200 cycles: the flow stays uniform to
// 1e-10 relative, the block keeps its velocity, the interface pressure is the fluid's.
TEST(CoupledScenes, AdvectedBlockCreatesNoFlow) {
  const fs::path dir = run_dir("advection");
  ASSERT_EQ(cosim_run(scene_file("coupled_advection"), dir), 0) << run_logs(dir);
  const History h = read_history(dir);
  ASSERT_EQ(h.size(), 201u);  // cycles 0..200
  for (std::size_t i = 0; i < h.size(); ++i) {
    ASSERT_NEAR(h.vx[i], 0.1, 1e-11) << i;
    ASSERT_NEAR(h.vy[i], 0.1, 1e-11) << i;
    ASSERT_NEAR(h.pressure[i], 1.0, 1e-10) << i;
    ASSERT_NEAR(h.force_x[i], 0.0, 1e-10) << i;
  }
  EXPECT_GT(h.cx.back() - h.cx.front(), 0.2);      // it did move (more than 2.5 cells)
  EXPECT_FALSE(fs::exists(dir / "coupler.sock"));  // the launcher removes the coupler's socket file
  io::Hdf5File last(dir / "fluid" / "fluid_000001.h5", io::Hdf5File::Mode::ReadOnly);
  const auto cat = last.read_doubles("/cell/embedded_category");
  const auto p = last.read_doubles("/cell/gas_pressure");
  const auto u = last.read_doubles("/cell/gas_velocity");
  const auto rho = last.read_doubles("/cell/gas_density");
  ASSERT_EQ(cat.size(), 169u);
  int flow = 0, body = 0;
  double worst = 0;
  for (std::size_t c = 0; c < cat.size(); ++c) {
    if (cat[c] > 1) {
      ++body;
      continue;
    }
    ++flow;
    worst = std::max({worst, std::abs(p[c] - 1.0), std::abs(rho[c] - 1.0), std::abs(u[3 * c] - 0.1) / 0.1,
                      std::abs(u[3 * c + 1] - 0.1) / 0.1, std::abs(u[3 * c + 2]) / 0.1});
  }
  std::printf("[ measured ] coupled advection: %d flow cells, %d body cells, max relative deviation %.2e\n", flow, body,
              worst);
  EXPECT_GT(body, 4);
  EXPECT_LT(worst, 1e-10);
  EXPECT_NEAR(last.read_double_attribute("/", "time").at(0), h.t.back(), 1e-9);  // history: 12 digits
  // The coupler's interface snapshot of the same time: 14 segments, all wetted, at the fluid's pressure.
  io::Hdf5File iface(dir / "coupler" / "interface_000001.h5", io::Hdf5File::Mode::ReadOnly);
  const auto ip = iface.read_doubles("/cell/pressure"), wet = iface.read_doubles("/cell/wetted");
  ASSERT_EQ(ip.size(), 14u);
  for (std::size_t i = 0; i < ip.size(); ++i) {
    EXPECT_NEAR(ip[i], 1.0, 1e-12);
    EXPECT_EQ(wet[i], 1.0);
  }
  EXPECT_TRUE(fs::exists(dir / "coupler" / "interface.xmf"));
}

// Protocol regression of the real piston scene: the messages of its first cycles in protobuf text form (numbers
// to 6 digits). Any change to what crosses the wire fails here; accept on purpose with COSIM_UPDATE_TRANSCRIPT=1
// and review the diff.
TEST(CoupledScenes, PistonSceneTranscriptOfTheFirstCycles) {
  const fs::path dir = run_dir("transcript");
  const fs::path got = fs::path(dir.string() + "_transcript.txt");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir,
                      "--set coupling.time.max_cycles=2 --coupler-exe '" + bin("coupler").string() + " --transcript " +
                          got.string() + "'"),
            0)
      << run_logs(dir);
  const fs::path expected = fs::path(COSIM_SOURCE_DIR) / "tests/coupled/data/transcript_piston_2d.txt";
  if (std::getenv("COSIM_UPDATE_TRANSCRIPT")) fs::copy_file(got, expected, fs::copy_options::overwrite_existing);
  const std::string a = read_text(expected), b = read_text(got);
  ASSERT_FALSE(b.empty());
  EXPECT_NE(b.find("faces {"), std::string::npos);
  EXPECT_NE(b.find("samples {"), std::string::npos);
  EXPECT_EQ(a, b) << "the piston scene's protocol transcript changed: diff " << expected << " " << got
                  << " (COSIM_UPDATE_TRANSCRIPT=1 accepts it)";
}

// A solver killed in the middle of a real coupled run: the launcher and the others stop within 5 s, the
// launcher names the process, nothing is left running, the snapshots written so far stay readable.
// In a log (stderr not a terminal) the launcher writes a progress line every --progress-every seconds: cycle,
// t / t_end, dt, wall per cycle, ETA.
TEST(CoupledScenes, ProgressLinesInALog) {
  const fs::path dir = run_dir("progress");
  const std::string cmd = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --out " +
                          dir.string() + " --set coupling.time.end=0.05 --progress-every 0.2 2> " + dir.string() +
                          ".err > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(fs::path(dir.string() + ".err"));
  std::istringstream err(read_text(fs::path(dir.string() + ".err")));
  int lines = 0;
  for (std::string l; std::getline(err, l);)
    if (l.rfind("cosim: cycle ", 0) == 0 && l.find(" / 0.05 s (") != std::string::npos &&
        l.find(" ms/cycle") != std::string::npos && l.find("ETA ") != std::string::npos)
      ++lines;
  EXPECT_GE(lines, 2) << read_text(fs::path(dir.string() + ".err"));
}

// A mistake in the scene found by a solver under `cosim run` names the user's file and line, not the launcher's
// copy in the run directory.
TEST(CoupledScenes, SceneErrorsNameTheUsersFile) {
  const fs::path dir = run_dir("typo");
  fs::create_directories(dir);
  std::string text = read_text(scene_file("piston_2d"));
  const std::size_t at = text.find("      density: 100.0");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 20, "      densty: 100.0");
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  const fs::path user = dir / "my_piston.yaml";
  std::ofstream(user) << text;
  EXPECT_EQ(cosim_run(user, dir / "run"), 2);
  const std::string log = read_text(fs::path((dir / "run").string() + ".log"));
  EXPECT_NE(log.find(user.string() + ":" + std::to_string(line) +
                     ": solid.blocks.0.densty: unknown key (did you mean "
                     "'density'?)"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("run/scene.yaml:"), std::string::npos) << log;
}

// A scene the fluid cannot set up for a coupled run (its own embedded bodies) is named as the user gave it too.
TEST(CoupledScenes, SetUpErrorsNameTheUsersFile) {
  const fs::path dir = run_dir("setup_error");
  fs::create_directories(dir);
  const fs::path user = dir / "my_piston.yaml";
  fs::copy_file(scene_file("piston_2d"), user);
  EXPECT_EQ(cosim_run(user, dir / "run",
                      "--set 'fluid.embedded.bodies=[{shape: box, lower: [0.1, 0.1], upper: [0.2, 0.2]}]'"),
            2);
  const std::string log = read_text(dir / "run" / "fluid.log");
  EXPECT_NE(
      log.find(user.string() + ": fluid.embedded.bodies: a coupled run takes its embedded boundary from the solid"),
      std::string::npos)
      << log;
  EXPECT_EQ(log.find("run/scene.yaml"), std::string::npos) << log;
}

TEST(CoupledScenes, KilledFluidSolverStopsEverythingWithin5s) {
  const fs::path dir = run_dir("killed");
  const std::string cmd = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --out " +
                          dir.string() + " --quiet --set coupling.time.end=100 > " + dir.string() +
                          ".log 2>&1 & echo $!";
  FILE* f = ::popen(cmd.c_str(), "r");
  ASSERT_NE(f, nullptr);
  long launcher_pid = 0;
  ASSERT_EQ(std::fscanf(f, "%ld", &launcher_pid), 1);
  ::pclose(f);
  // Wait until the run is under way (a snapshot exists), then kill the fluid solver.
  for (int i = 0; i < 200 && !fs::exists(dir / "fluid" / "fluid_000001.h5"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(dir / "fluid" / "fluid_000001.h5")) << run_logs(dir);
  const std::string kill = "pkill -KILL -f '^" + bin("fluid_solver").string() + " " + dir.string() + "/scene.yaml'";
  ASSERT_EQ(std::system(kill.c_str()), 0);
  const auto t0 = std::chrono::steady_clock::now();
  bool gone = false;
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(10)) {
    if (::kill(static_cast<pid_t>(launcher_pid), 0) != 0) {
      gone = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ measured ] killed fluid_solver: the launcher ended %.2f s later\n", waited);
  ASSERT_TRUE(gone) << run_logs(dir);
  EXPECT_LT(waited, 5.0);
  const std::string log = read_text(fs::path(dir.string() + ".log"));
  EXPECT_NE(log.find("fluid"), std::string::npos) << log;
  // [s]: the shell running pgrep must not match its own pattern
  const std::string left = "pgrep -f '" + dir.string() + "/[s]cene.yaml' > /dev/null";
  EXPECT_NE(std::system(left.c_str()), 0) << "a process of the run is still alive";
  EXPECT_FALSE(fs::exists(dir / "coupler.sock"));  // also after a failed run
  io::Hdf5File snap(dir / "fluid" / "fluid_000001.h5", io::Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(snap.read_doubles("/cell/gas_pressure").size(), 160u * 8u);
}

// Ctrl-C on the launcher of a real run: exit code 130 within 5 s, no process of the run left, and every
// snapshot the XDMF index lists is complete and readable.
TEST(CoupledScenes, InterruptStopsAllThreeAndKeepsCompleteSnapshots) {
  const fs::path dir = run_dir("interrupt");
  const std::string cmd = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --out " +
                          dir.string() + " --quiet --set coupling.time.end=100 > " + dir.string() +
                          ".log 2>&1 & echo $!";
  FILE* f = ::popen(cmd.c_str(), "r");
  ASSERT_NE(f, nullptr);
  long pid = 0;
  ASSERT_EQ(std::fscanf(f, "%ld", &pid), 1);
  ::pclose(f);
  for (int i = 0; i < 200 && !fs::exists(dir / "fluid" / "fluid_000001.h5"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(dir / "fluid" / "fluid_000001.h5")) << run_logs(dir);
  ASSERT_EQ(::kill(static_cast<pid_t>(pid), SIGINT), 0);
  const auto t0 = std::chrono::steady_clock::now();
  while (::kill(static_cast<pid_t>(pid), 0) == 0 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ measured ] Ctrl-C: the launcher ended %.2f s later\n", waited);
  EXPECT_LT(waited, 5.0);
  EXPECT_NE(read_text(fs::path(dir.string() + ".log")).find("interrupted"), std::string::npos)
      << read_text(fs::path(dir.string() + ".log"));
  const std::string left = "pgrep -f '" + dir.string() + "/[s]cene.yaml' > /dev/null";
  EXPECT_NE(std::system(left.c_str()), 0) << "a process of the run is still alive";
  // Every snapshot named in the index opens and holds the full field.
  for (const char* solver : {"fluid", "solid"}) {
    const std::string xmf = read_text(dir / solver / (std::string(solver) + ".xmf"));
    const std::regex file(std::string(solver) + "_[0-9]{6}\\.h5");
    std::set<std::string> names;
    for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), file); it != std::sregex_iterator(); ++it)
      names.insert(it->str());
    const int listed = static_cast<int>(names.size());
    for (const std::string& name : names) {
      io::Hdf5File h(dir / solver / name, io::Hdf5File::Mode::ReadOnly);
      EXPECT_FALSE(
          h.read_doubles(std::string("/cell/") + (std::string(solver) == "fluid" ? "gas_pressure" : "pressure"))
              .empty())
          << name;
    }
    EXPECT_GE(listed, 2) << solver;
  }
}

// The energy account of a coupled run (DIR/energy_account.json, written by the launcher from the summaries): in
// a closed fluid domain its total change is the energy the interface created or lost. The advected rigid block
// (periodic, nothing happens) creates none; the light gas piston (walls, ratio 0.01) creates 1.1% of the total
// with the characteristic conditions (measured; the impedance conditions: 23%, printed, docs/deformable_structures.md).
TEST(CoupledScenes, EnergyAccountOfClosedDomains) {
  const auto account = [](const fs::path& dir) {
    return nlohmann::json::parse(read_text(dir / "energy_account.json"));
  };
  const fs::path adv = run_dir("account_advection");
  ASSERT_EQ(cosim_run(scene_file("coupled_advection"), adv), 0) << run_logs(adv);
  const auto a = account(adv);
  EXPECT_NEAR(a["fluid"]["change"].get<double>() + a["solid"]["change"].get<double>(), a["total_change"].get<double>(),
              1e-12);
  EXPECT_LT(std::abs(a["total_change_relative"].get<double>()), 1e-12);
  double light[2] = {0, 0};
  int k = 0;
  for (const char* mode : {"characteristic", "impedance"}) {
    const fs::path dir = run_dir(std::string("account_light_") + mode);
    ASSERT_EQ(cosim_run(scene_file("piston_light_2d"), dir, std::string("--set coupling.mode=") + mode), 0)
        << run_logs(dir);
    const auto j = account(dir);
    light[k++] = j["total_change_relative"].get<double>();
    // The solid's change is its boundary work (the interface pressures): its own balance is exact.
    EXPECT_NEAR(j["solid"]["change"].get<double>(), j["solid"]["boundary_work"].get<double>(),
                1e-9 * std::abs(j["solid"]["start"].get<double>()));
  }
  std::printf(
      "[ measured ] energy the interface created in a closed domain: advected block %.1e, light piston "
      "(ratio 0.01, 0.05 s) characteristic %.2f%%, impedance %.2f%% of the total\n",
      a["total_change_relative"].get<double>(), 100 * light[0], 100 * light[1]);
  EXPECT_LT(std::abs(light[0]), 0.02);
}

// A structure that overlaps the fluid domain's boundary is refused at the first cycle with a message naming the
// vertex, the coordinate and the domain (faces on the boundary itself, as in the piston and the Sod slab, are fine).
TEST(CoupledScenes, StructureOutsideTheFluidDomainIsRefused) {
  const fs::path dir = run_dir("outside_domain");
  EXPECT_NE(cosim_run(scene_file("modified_sod_square_2d"), dir, "--set solid.mesh.upper=[1.05,0.625]"), 0);
  const std::string log = run_logs(dir);
  EXPECT_NE(log.find("outside the fluid domain"), std::string::npos) << log;
  EXPECT_NE(log.find("x = 1.0"), std::string::npos) << log;
  EXPECT_NE(log.find("fluid.mesh"), std::string::npos) << log;
}
