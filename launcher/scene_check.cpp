#include "launcher/scene_check.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "common/app/plan_facts.h"

namespace cosim::launcher {

int run_captured(const std::vector<std::string>& argv, std::string& output, double timeout) {
  output.clear();
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return -1;
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return -1;
  }
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    const int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) ::dup2(devnull, STDIN_FILENO);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  const auto t0 = std::chrono::steady_clock::now();
  char buf[4096];
  for (;;) {
    const double left = timeout - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (left <= 0) {
      ::kill(pid, SIGKILL);
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left * 1000) + 1) <= 0) continue;
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    if (output.size() < (1u << 20)) output.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::optional<SceneRefusal> check_scene(const SceneCheck& c, std::vector<std::string>* plan, nlohmann::json* facts) {
  std::vector<std::string> programs;
  if (c.coupled && c.check_coupler) programs.push_back("coupler");
  if (c.check_fluid) programs.push_back("fluid_solver");
  if ((c.coupled || c.solid_only) && c.check_solid) programs.push_back("solid_solver");
  for (const std::string& p : programs) {
    std::vector<std::string> argv{(c.bin_dir / p).string(), c.scene, "--check", "--quiet", "--plan-facts"};
    if (p == "fluid_solver" && c.fluid_ranks > 1) argv.insert(argv.end(), {"--ranks", std::to_string(c.fluid_ranks)});
    if (p == "solid_solver" && c.solid_ranks > 1) argv.insert(argv.end(), {"--ranks", std::to_string(c.solid_ranks)});
    for (const auto& o : c.overrides) argv.insert(argv.end(), {"--set", o});
    std::string out;
    const int rc = run_captured(argv, out, 120.0);
    if (rc != 0) {
      while (!out.empty() && out.back() == '\n') out.pop_back();
      return SceneRefusal{p, rc, rc == 127 && out.empty() ? "cannot execute " + argv[0] : out};
    }
    std::string lines;  // the plan without its facts line
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind(app::kPlanFactsTag, 0) == 0) {
        if (facts)
          (*facts)[p] = nlohmann::json::parse(line.substr(std::string(app::kPlanFactsTag).size()), nullptr,
                                              /*allow_exceptions=*/false);
      } else {
        lines += (lines.empty() ? "" : "\n") + line;
      }
    }
    if (plan && !lines.empty()) plan->push_back(lines);
  }
  return std::nullopt;
}

std::string coupled_estimate(const nlohmann::json& facts) {
  const auto number = [&](const char* program, const char* key) {
    const auto p = facts.find(program);
    if (p == facts.end() || !p->is_object()) return 0.0;
    const auto v = p->find(key);
    return v != p->end() && v->is_number() ? v->get<double>() : 0.0;
  };
  const double fluid = number("fluid_solver", "first_step"), solid = number("solid_solver", "first_step"),
               subcycles = std::max(1.0, number("solid_solver", "max_subcycles")), dt_max = number("coupler", "dt_max"),
               end = number("coupler", "end_time");
  double dt = 0.0;
  std::string by;
  const auto take = [&](double v, std::string what) {
    if (v > 0 && (dt == 0 || v < dt)) dt = v, by = std::move(what);
  };
  take(fluid, "the fluid's step");
  take(solid * subcycles, subcycles > 1 ? fmt::format("the solid's stable step x {:g} substeps", subcycles)
                                        : std::string("the solid's stable step"));
  take(dt_max, "coupling.time.dt_max");
  if (dt <= 0) return "";
  std::string line = fmt::format("coupled: first cycle's step {:.3g} s ({})", dt, by);
  if (end > 0)
    line += fmt::format(", about {:.0f} cycles to {:g} s at that step (the step follows the flow)",
                        std::ceil(end / dt * (1 - 1e-12)), end);
  return line;
}

}  // namespace cosim::launcher
