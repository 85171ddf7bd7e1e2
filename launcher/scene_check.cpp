#include "launcher/scene_check.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

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

std::optional<SceneRefusal> check_scene(const SceneCheck& c, std::vector<std::string>* plan) {
  std::vector<std::string> programs;
  if (c.coupled && c.check_coupler) programs.push_back("coupler");
  if (c.check_fluid) programs.push_back("fluid_solver");
  if (c.coupled && c.check_solid) programs.push_back("solid_solver");
  for (const std::string& p : programs) {
    std::vector<std::string> argv{(c.bin_dir / p).string(), c.scene, "--check", "--quiet"};
    for (const auto& o : c.overrides) argv.insert(argv.end(), {"--set", o});
    std::string out;
    const int rc = run_captured(argv, out, 120.0);
    if (rc != 0) {
      while (!out.empty() && out.back() == '\n') out.pop_back();
      return SceneRefusal{p, rc, rc == 127 && out.empty() ? "cannot execute " + argv[0] : out};
    }
    while (!out.empty() && out.back() == '\n') out.pop_back();
    if (plan && !out.empty()) plan->push_back(out);
  }
  return std::nullopt;
}

}  // namespace cosim::launcher
