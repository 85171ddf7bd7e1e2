#include "launcher/launch.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include "common/app/errors.h"
#include "common/app/scene_kind.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/config/config.h"
#include "common/coupling/endpoints.h"
#include "common/util/progress.h"
#include "launcher/energy_account.h"
#include "launcher/output_activity.h"
#include "launcher/process.h"
#include "launcher/python_paths.h"
#include "launcher/rank_launcher.h"
#include "launcher/restart_check.h"
#include "launcher/run_summary.h"
#include "launcher/run_view.h"
#include "launcher/scene_check.h"
#include "launcher/scene_plan.h"
#include "launcher/watcher.h"

namespace fs = std::filesystem;

namespace cosim::launcher {

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Progress from the coupler's progress.txt ("cycle t t_end dt"): cycle, t / t_end, dt, wall per cycle, ETA.
std::string progress_text(const fs::path& file, double elapsed) {
  std::ifstream in(file);
  long cycle = 0;
  double t = 0, t_end = 0, dt = 0;
  if (!(in >> cycle >> t >> t_end) || t_end <= 0) return fmt::format("starting ... {:.0f} s", elapsed);
  in >> dt;
  const double eta = t > 0 ? elapsed * (t_end - t) / t : -1.0;
  return fmt::format("cycle {}  t = {:.6g} / {:.6g} s ({:.0f}%)  dt {:.3g} s  {:.3g} ms/cycle  wall {}  ETA {}", cycle,
                     t, t_end, 100.0 * t / t_end, dt, cycle > 0 ? 1e3 * elapsed / cycle : 0.0,
                     util::format_duration(elapsed), util::format_duration(eta));
}
// The output folders of processes that were stopped before they wrote anything (DIR/fluid, ...): a failed run
// keeps its logs and run_summary.json, not empty folders.
void remove_empty_outputs(const fs::path& out, const std::vector<Child>& children) {
  for (const Child& c : children) {
    std::error_code ec;
    const fs::path dir = out / c.name;
    if (fs::is_directory(dir, ec) && fs::is_empty(dir, ec) && !ec) fs::remove(dir, ec);
  }
}
}  // namespace

std::string make_token() {
  std::random_device rd;
  return fmt::format("{:08x}{:08x}{:08x}{:08x}", rd(), rd(), rd(), rd());
}

std::string ipc_endpoint(const fs::path& dir) {
  const fs::path p = fs::absolute(dir) / "coupler.sock";
  if (p.string().size() < 100) return "ipc://" + p.string();
  // sun_path holds 108 bytes: a private directory of its own (0700, named at random, never from the token)
  char tmpl[] = "/tmp/cosim-XXXXXX";
  if (!::mkdtemp(tmpl))
    throw std::runtime_error(fmt::format("cannot make a directory for the socket: {}", std::strerror(errno)));
  return "ipc://" + std::string(tmpl) + "/coupler.sock";
}

std::string tcp_endpoint(const std::string& host) {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  if (s < 0) throw std::runtime_error(fmt::format("cannot open a socket: {}", std::strerror(errno)));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = 0;
  if (::inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) {
    ::close(s);
    throw std::runtime_error(fmt::format("--tcp {}: not an IPv4 address", host));
  }
  socklen_t len = sizeof a;
  if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    const std::string err = std::strerror(errno);
    ::close(s);
    throw std::runtime_error(fmt::format("no free tcp port on {}: {}", host, err));
  }
  const int port = ntohs(a.sin_port);
  ::close(s);
  return fmt::format("tcp://{}:{}", host, port);
}

std::vector<std::string> split_command(const std::string& cmd) {
  std::vector<std::string> out;
  std::string word;
  bool in_word = false;
  char quote = 0;  // the open quote, 0 outside quotes
  for (std::size_t i = 0; i < cmd.size(); ++i) {
    const char c = cmd[i];
    if (quote == '\'') {  // everything up to the closing ' is literal
      if (c == '\'') quote = 0;
      else word += c;
    } else if (quote == '"') {  // \" and \\ are escapes inside "..."
      if (c == '"') quote = 0;
      else if (c == '\\' && i + 1 < cmd.size() && (cmd[i + 1] == '"' || cmd[i + 1] == '\\')) word += cmd[++i];
      else word += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == '\\' && i + 1 < cmd.size()) {
      word += cmd[++i];
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) out.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (quote) throw std::runtime_error(fmt::format("unclosed {} quote in the command: {}", quote, cmd));
  if (in_word) out.push_back(word);
  return out;
}

namespace {
// The process whose failure started the chain, once `first` has failed. Every process gets up to a second to end
// by itself (a solver's failure reaches the coupler at once, which stops the other solver; the coupler's death
// reaches both solvers at once), whatever the order in which they are reaped; then the cause is, in this order:
//  1. the solver the coupler names as the cause in coupler_summary.json ("peer": dead, refused, reported an
//     error), when it ended by itself with an error;
//  2. a process killed by a signal (kill -9, a crash): nothing of this run has signalled its processes yet;
//  3. a solver failing with its own code (a solver's 5 is the coupler stopping it or vanishing: a consequence);
//  4. the coupler, when it failed;
//  5. the first that failed.
Child failure_cause(std::vector<Child>& children, const Child& first, const fs::path& out) {
  const auto own_failure = [](const Child& c) {
    return !c.running && c.exit_code != 0 && (c.signal > 0 || (c.name != "coupler" && c.exit_code != 5));
  };
  const double until = now_s() + 1.0;
  for (;;) {
    bool all_ended = true, decided = false;
    for (auto& c : children) {
      poll(c);
      all_ended = all_ended && !c.running;
      decided = decided || own_failure(c);
    }
    if (all_ended || decided || now_s() > until) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::string peer;
  try {
    std::ifstream in(out / "coupler" / "coupler_summary.json");
    if (in) peer = nlohmann::json::parse(in).value("peer", "");
  } catch (const std::exception&) {}
  for (const auto& c : children)
    if (!peer.empty() && c.name == peer && !c.running && c.exit_code != 0) return c;
  for (const auto& c : children)
    if (!c.running && c.signal > 0) return c;
  for (const auto& c : children)
    if (own_failure(c)) return c;
  for (const auto& c : children)
    if (c.name == "coupler" && !c.running && c.exit_code != 0) return c;
  return first;
}

// The checkpoint set a restart resumes from, checked against the scene given now: every key that shapes the
// physics must be as it was when the set was written. Prints why and gives nothing when the run cannot resume.
std::optional<fs::path> restart_set_for(const LaunchOptions& opt, const fs::path& root) {
  checkpoint::SetInfo set;
  try {
    // Every part is checked against its manifest (size, SHA-256, cycle) before anything starts; without --from a
    // set that fails is passed over, by name, for the newest one that verifies.
    const checkpoint::SetChoice choice =
        checkpoint::choose_set(root, opt.restart_from >= 0 ? std::optional<long>(opt.restart_from) : std::nullopt);
    for (const std::string& why : choice.skipped)
      std::cerr << fmt::format("cosim: --restart: skipping a checkpoint set that cannot be used: {}\n", why);
    set = choice.set;
    const config::Node was =
        config::load_string(set.manifest.value("scene", std::string()), (set.dir / "manifest.json").string(),
                            set.manifest.value("overrides", std::vector<std::string>{}));
    const config::Node now = config::load_file(opt.scene, opt.overrides);
    const std::vector<SceneChange> changes = physics_changes(was, now);
    if (!changes.empty()) {
      std::string list;
      for (const auto& c : changes) list += fmt::format("\n  {}: was {}, now {}", c.key, c.was, c.now);
      std::cerr << fmt::format(
          "cosim: --restart: {} changes the scene the checkpoint of cycle {} was written with ({}):{}\nA restart "
          "may change only the end time, the checkpoint settings, timeouts and threads; start a new run for the "
          "rest.\n",
          opt.scene, set.cycle, set.dir.string(), list);
      return std::nullopt;
    }
  } catch (const std::exception& e) {
    std::cerr << "cosim: --restart: " << e.what() << "\n";
    return std::nullopt;
  }
  std::cerr << fmt::format("cosim: restarting from the checkpoint of cycle {} at t = {:.9g} s ({})\n", set.cycle,
                           set.time, set.dir.string());
  return set.dir;
}
}  // namespace

int run(const LaunchOptions& opt) {
  const auto plan = read_plan(opt);
  if (!plan) return 2;
  const bool coupled = plan->coupled();
  const std::string name = plan->name;
  const LaunchOptions eff = plan->eff;
  if (!opt.restart.empty() && !opt.out.empty() && fs::absolute(opt.out) != fs::absolute(opt.restart)) {
    std::cerr << fmt::format("cosim: --restart {} continues that run in its own directory; --out {} differs\n",
                             opt.restart.string(), opt.out.string());
    return 2;
  }
  const fs::path out = !opt.restart.empty() ? opt.restart : opt.out.empty() ? fs::path("runs") / name : opt.out;
  const fs::path checkpoints = fs::absolute(out) / "checkpoints";
  fs::path restart_set;
  if (!opt.restart.empty()) {
    const auto set = restart_set_for(opt, checkpoints);
    if (!set) return 2;
    restart_set = *set;
  }
  // The endpoint before the run directory: a run that cannot start leaves no directory behind.
  const std::string token = make_token();
  std::string endpoint;
  try {
    endpoint = opt.tcp ? tcp_endpoint(opt.tcp_host) : ipc_endpoint(out);
  } catch (const std::exception& e) {
    std::cerr << "cosim: " << e.what() << "\n";
    return 2;
  }
  // The coupler's ipc socket file is removed however the run ends (zmq leaves it behind), and with it the private
  // directory made for it when the run directory's path is too long for a socket name.
  // The same for the coupler's heartbeat socket beside it.
  struct SocketCleanup {
    fs::path file, heartbeat_file, dir;
    ~SocketCleanup() {
      std::error_code ignored;
      for (const fs::path& f : {file, heartbeat_file})
        if (!f.empty()) fs::remove(f, ignored);
      if (!dir.empty()) fs::remove_all(dir, ignored);
    }
  } socket_cleanup;
  if (endpoint.rfind("ipc://", 0) == 0) {
    socket_cleanup.file = endpoint.substr(6);
    socket_cleanup.heartbeat_file = coupling::heartbeat_bind_endpoint(endpoint).substr(6);
  }
  if (endpoint.rfind("ipc:///tmp/cosim-", 0) == 0) socket_cleanup.dir = socket_cleanup.file.parent_path();
  std::error_code ec;
  const bool fresh = !fs::exists(out, ec);
  fs::create_directories(out, ec);
  if (ec) {  // an output that cannot be created is an I/O failure, as in the solvers
    std::cerr << fmt::format("cosim: {}: cannot create the run directory: {}\n", out.string(), ec.message());
    return app::kExitIo;
  }
  // One run per directory: a lock held for the whole run (released by the kernel when cosim ends, however).
  const fs::path lock_path = out / ".cosim.lock";
  const int lock_fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd < 0 || ::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
    std::string holder;
    std::ifstream(lock_path) >> holder;
    std::cerr << fmt::format(
        "cosim: {}: the run directory is in use by another run{}; choose another --out or wait "
        "for it to end\n",
        out.string(), holder.empty() ? "" : " (cosim pid " + holder + ")");
    return 2;
  }
  const std::string pid_text = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_fd, 0) != 0 || ::write(lock_fd, pid_text.data(), pid_text.size()) < 0)
    std::cerr << "cosim: note: cannot record the pid in " << lock_path.string() << "\n";
  const fs::path scene = fs::absolute(out / "scene.yaml");
  if (fs::absolute(opt.scene) != scene) fs::copy_file(opt.scene, scene, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    std::cerr << fmt::format("cosim: cannot copy {} to {}: {}\n", opt.scene, scene.string(), ec.message());
    std::error_code ignored;
    if (fresh) fs::remove_all(out, ignored);  // this run made it (and holds its lock): nothing of it is kept
    return app::kExitIo;
  }
  // A summary still "running" is a launcher's that died without a watcher to say so (the machine stopped): this
  // run holds the lock, so none runs there now. Said so before anything else is written.
  if (const long dead = running_launcher(out); dead != 0)
    mark_launcher_died(out, 0,
                       fmt::format("the launcher (cosim, pid {}) ended without writing its summary (killed, or the "
                                   "machine stopped); found by cosim pid {} at {}",
                                   dead, ::getpid(), utc_now()));
  const Attempt attempt = next_attempt(out, !opt.restart.empty(), restart_set.string());
  // The coupler's summary of an earlier run would name a cause of that run.
  fs::remove(out / "coupler" / "coupler_summary.json", ec);

  const auto command = [&](const std::string& given, const char* exe) {
    std::vector<std::string> argv = split_command(given);
    if (argv.empty()) argv.push_back((opt.bin_dir / exe).string());
    return argv;
  };
  const auto with_common = [&](std::vector<std::string> argv, const char* sub, bool client) {
    argv.push_back(scene.string());
    argv.insert(argv.end(), {"--out", (fs::absolute(out) / sub).string()});
    // The time driver (the coupler, or the solver alone) writes the checkpoint sets; every process restarts.
    if (!client || !coupled) argv.insert(argv.end(), {"--checkpoints", checkpoints.string()});
    if (!restart_set.empty()) argv.insert(argv.end(), {"--restart", restart_set.string()});
    // The token goes by the environment ($COSIM_TOKEN, set below): a command line is world-readable.
    if (coupled) { argv.insert(argv.end(), {client ? "--coupler" : "--endpoint", endpoint}); }
    for (const auto& o : opt.overrides) argv.insert(argv.end(), {"--set", o});
    if (opt.quiet && !client) argv.push_back("--quiet");
    return argv;
  };
  std::vector<Child> children;
  if (coupled)
    children.push_back(
        {"coupler", with_common(command(eff.coupler_cmd, "coupler"), "coupler", false), out / "coupler.log"});
  if (plan->has_fluid()) {
    std::vector<std::string> fluid = rank_launcher(eff.fluid_ranks);  // mpirun / srun before the program
    const std::vector<std::string> program = with_common(command(eff.fluid_cmd, "fluid_solver"), "fluid", true);
    fluid.insert(fluid.end(), program.begin(), program.end());
    children.push_back({"fluid", fluid, out / "fluid.log"});
    children.back().ranks = eff.fluid_ranks;
  }
  if (plan->has_solid()) {
    std::vector<std::string> solid = rank_launcher(eff.solid_ranks);  // mpirun / srun before the program
    const std::vector<std::string> program = with_common(command(eff.solid_cmd, "solid_solver"), "solid", true);
    solid.insert(solid.end(), program.begin(), program.end());
    children.push_back({"solid", solid, out / "solid.log"});
    children.back().ranks = eff.solid_ranks;
  }
  // A restart adds to the logs of the earlier attempts, after a line that marks where it begins.
  if (attempt.restart)
    for (auto& c : children) {
      c.append_log = true;
      c.log_header = fmt::format("===== cosim restart at {} from checkpoint set {} (attempt {}) =====", attempt.started,
                                 attempt.restart_set, attempt.number);
    }

  nlohmann::json launch;
  launch["endpoint"] = coupled ? endpoint : "";
  launch["coupled"] = coupled;
  for (const auto& c : children) launch["commands"][c.name] = c.argv;
  std::ofstream(out / "launch.json") << launch.dump(2) << "\n";

  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  g_stop = false;
  // Three processes take turns on the cores: OpenMP threads that spin while their process waits for a
  // message steal the cores the other processes need (a 10x slower cycle on 2 cores). The user's own
  // setting wins.
  ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  // Relative file names in the scene (a Gmsh mesh) are the user's, relative to the scene they gave; the solvers
  // read the copy in the run directory (config::scene_base_dir).
  ::setenv("COSIM_SCENE_DIR", fs::absolute(opt.scene).parent_path().string().c_str(), 1);
  // ... and their messages name the user's file, not the copy (config::load_file).
  ::setenv("COSIM_SCENE_FILE", opt.scene.c_str(), 1);
  ::setenv("COSIM_SCENE_COPY", scene.string().c_str(), 1);
  // The run's token, for the processes it starts only: an environment is readable by its owner alone.
  ::setenv("COSIM_TOKEN", token.c_str(), 1);
  // A solver written in Python imports the cosim package (`python3 -m cosim.rigid_piston`) without a path set.
  {
    const char* old = std::getenv("PYTHONPATH");
    const std::string pkg = python_paths(opt.bin_dir).package.string();
    ::setenv("PYTHONPATH", (old && *old ? pkg + ":" + old : pkg).c_str(), 1);
  }

  const auto stop_children = [&] { stop_all(children, 3.0); };
  const double launch_time = now_s();
  bool viewed = false;  // RUN/view.py written at the end
  const auto summarise = [&](const std::string& status, const std::string& reason, const Child* failed) {
    if (status != "completed" && status != "running") remove_empty_outputs(out, children);
    // A failed or interrupted run's snapshots are worth a look too; a run without any gets no view.
    if (status != "running") {
      const std::string why = write_run_view(out);
      viewed = why.empty();
      if (!viewed && status == "completed") std::cerr << "cosim: no view.py (ParaView state): " << why << "\n";
    }
    write_run_summary(out, {status, reason, failed, now_s() - launch_time}, children, coupled, attempt);
  };
  Watcher watcher;  // says so in run_summary.json if this launcher dies
  start_watcher(watcher, out, {socket_cleanup.file, socket_cleanup.heartbeat_file});
  try {
    for (auto& c : children) {
      start(c);
      watcher.started(c.pid);
    }
  } catch (const std::exception& e) {
    stop_children();
    std::cerr << "cosim: " << e.what() << "\n";
    summarise("failed", e.what(), nullptr);
    return app::kExitIo;  // a log that cannot be written, a fork that fails
  }
  summarise("running", fmt::format("cosim (pid {}) is running it", ::getpid()), nullptr);
  if (!opt.quiet)
    std::cerr << fmt::format("cosim: {} run {} in {} ({})\n", kind_name(plan->kind), name, out.string(),
                             coupled ? endpoint : "no coupler");
  const bool tty = ::isatty(STDERR_FILENO);
  const double start_time = now_s();
  double last_progress = 0;
  int finished = 0;
  // After a clean exit the others have `grace` seconds to finish, counted afresh while one writes (its output
  // folder or the checkpoint sets change: a large final snapshot), so only a silent one is stopped.
  const double grace = end_grace_seconds();
  double first_exit = 0, last_written = 0, last_look = 0;
  std::vector<OutputActivity> written(children.size());
  while (finished < static_cast<int>(children.size())) {
    if (g_stop) {
      if (tty && !opt.quiet) std::cerr << "\n";
      std::cerr << "cosim: interrupted: stopping all processes\n";
      stop_children();
      summarise("interrupted", "cosim run was interrupted (SIGINT/SIGTERM): all processes stopped", nullptr);
      return 130;
    }
    for (auto& c : children) {
      if (!poll(c)) continue;
      ++finished;
      if (first_exit == 0) first_exit = now_s();
      if (c.exit_code != 0) {
        if (tty && !opt.quiet) std::cerr << "\n";
        const Child failed = failure_cause(children, c, out);  // as it ended, before the others are stopped
        stop_children();
        std::cerr << fmt::format("cosim: {} failed with exit code {}; last lines of {}:\n{}", failed.describe(),
                                 failed.exit_code, failed.log.string(), tail(failed.log, 15));
        summarise("failed",
                  fmt::format("{} failed ({}); the others were stopped", failed.name, exit_description(failed)),
                  &failed);
        return failed.exit_code;
      }
    }
    if (first_exit > 0 && finished < static_cast<int>(children.size()) && now_s() - last_look >= 0.5) {
      last_look = now_s();
      for (std::size_t i = 0; i < children.size(); ++i) {
        if (!children[i].running) continue;
        OutputActivity a = output_activity(fs::absolute(out) / children[i].name);
        const OutputActivity sets = output_activity(checkpoints);
        a.bytes += sets.bytes, a.files += sets.files, a.latest = std::max(a.latest, sets.latest);
        if (!(a == written[i])) last_written = now_s();
        written[i] = a;
      }
    }
    if (first_exit > 0 && finished < static_cast<int>(children.size()) &&
        now_s() - std::max(first_exit, last_written) > grace) {
      for (auto& c : children)
        if (c.running) {
          const std::string why =
              fmt::format("{} still running {:.0f} s after the others ended, writing nothing", c.name, grace);
          std::cerr << fmt::format("cosim: {}; stopping it ({})\n", why, c.describe());
          const Child hung = c;
          stop_children();
          std::cerr << tail(c.log, 15);
          summarise("failed", why, &hung);
          return 1;
        }
    }
    // On a terminal the line is rewritten twice a second; in a log (stderr not a terminal) a line every
    // --progress-every seconds (30).
    const double every = tty ? 0.5 : opt.progress_every;
    if (!opt.quiet && now_s() - last_progress > every && now_s() - start_time > (tty ? 0.0 : every)) {
      last_progress = now_s();
      const std::string line =
          coupled ? progress_text(out / "coupler" / "progress.txt", now_s() - start_time)
                  : fmt::format("{} running ... {:.0f} s", children.front().name, now_s() - start_time);
      if (tty) std::cerr << "\r" << line << "\033[K" << std::flush;
      else std::cerr << "cosim: " << line << "\n" << std::flush;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (tty && !opt.quiet) std::cerr << "\n";
  if (coupled) {
    const std::string why = write_energy_account(out);
    if (!why.empty()) std::cerr << "cosim: no energy_account.json: " << why << "\n";
  }
  summarise("completed", "all processes completed", nullptr);
  if (!opt.quiet)
    std::cerr << fmt::format("cosim: completed in {:.1f} s; logs and results in {}{}\n", now_s() - start_time,
                             out.string(), viewed ? fmt::format("; in ParaView: cosim view {}", out.string()) : "");
  return 0;
}

}  // namespace cosim::launcher
