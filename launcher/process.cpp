#include "launcher/process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <deque>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace cosim::launcher {

std::string Child::describe() const { return fmt::format("{} ({}, pid {})", name, argv.empty() ? "?" : argv[0], pid); }

void start(Child& c) {
  if (c.argv.empty()) throw std::runtime_error(c.name + ": no command");
  const int fd = ::open(c.log.c_str(), O_WRONLY | O_CREAT | (c.append_log ? O_APPEND : O_TRUNC) | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::runtime_error(fmt::format("{}: cannot write the log: {}", c.log.string(), std::strerror(errno)));
  if (!c.log_header.empty()) {
    const std::string line = c.log_header + "\n";
    if (::write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
      const std::string err = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error(fmt::format("{}: cannot write the log: {}", c.log.string(), err));
    }
  }
  std::vector<char*> args;
  for (auto& a : c.argv) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fd);
    throw std::runtime_error(fmt::format("{}: fork failed: {}", c.name, std::strerror(errno)));
  }
  if (pid == 0) {
    ::setpgid(0, 0);                     // own group: a terminal's Ctrl-C reaches only the launcher
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // no orphans if the launcher dies
    if (::getppid() != parent) ::_exit(127);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    const int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) ::dup2(devnull, STDIN_FILENO);
    ::execvp(args[0], args.data());
    const std::string msg = fmt::format("cosim: cannot execute {}: {}\n", args[0], std::strerror(errno));
    [[maybe_unused]] auto w = ::write(STDERR_FILENO, msg.data(), msg.size());
    ::_exit(127);
  }
  ::close(fd);
  ::setpgid(pid, pid);
  c.pid = pid;
  c.running = true;
}

bool poll(Child& c) {
  if (!c.running) return false;
  int status = 0;
  const pid_t r = ::waitpid(c.pid, &status, WNOHANG);
  if (r != c.pid) return false;
  c.running = false;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  c.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return true;
}

void stop(Child& c, double grace) {
  std::vector<Child> one{c};
  stop_all(one, grace);
  c = one[0];
}

void stop_all(std::vector<Child>& cs, double grace) {
  for (auto& c : cs)
    if (c.running) {
      ::kill(-c.pid, SIGTERM);
      ::kill(-c.pid, SIGCONT);
    }
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace);
  const auto all_done = [&] {
    bool done = true;
    for (auto& c : cs) {
      poll(c);
      done = done && !c.running;
    }
    return done;
  };
  while (!all_done() && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  for (auto& c : cs) {
    if (!c.running) continue;
    ::kill(-c.pid, SIGKILL);
    int status = 0;
    ::waitpid(c.pid, &status, 0);
    c.running = false;
    c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    c.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  }
}

std::string tail(const std::filesystem::path& file, int n) {
  std::ifstream in(file);
  std::deque<std::string> lines;
  for (std::string l; std::getline(in, l);) {
    lines.push_back(l);
    if (static_cast<int>(lines.size()) > n) lines.pop_front();
  }
  std::string out;
  for (const auto& l : lines) out += "    " + l + "\n";
  return out;
}

}  // namespace cosim::launcher
