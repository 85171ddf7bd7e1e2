#include "launcher/watcher.h"

#include <fcntl.h>
#include <signal.h>

#include <cerrno>
#include <sstream>

#include "launcher/run_summary.h"

namespace fs = std::filesystem;

namespace cosim::launcher {

void start_watcher(Watcher& w, const fs::path& out, const std::vector<fs::path>& leftovers) {
  int p[2];
  if (::pipe2(p, O_CLOEXEC) != 0) return;
  const pid_t launcher = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(p[0]);
    ::close(p[1]);
    return;
  }
  if (pid == 0) {
    ::close(p[1]);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::signal(sig, SIG_IGN);
    std::string text;
    char chunk[256];
    for (;;) {
      const ssize_t n = ::read(p[0], chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      text.append(chunk, static_cast<std::size_t>(n));
    }
    std::istringstream lines(text);
    std::vector<pid_t> groups;
    bool done = false;
    for (std::string l; std::getline(lines, l);) {
      if (l == "D") done = true;
      else if (l.size() > 1 && l[0] == 'P') groups.push_back(static_cast<pid_t>(std::atol(l.c_str() + 1)));
    }
    if (!done) {
      for (pid_t g : groups) ::kill(-g, SIGKILL);
      mark_launcher_died(out, launcher,
                         fmt::format("the launcher (cosim, pid {}) died (killed by a signal or crashed) at {}; its "
                                     "processes were killed with it",
                                     launcher, utc_now()));
      std::error_code ignored;
      for (const fs::path& f : leftovers)
        if (!f.empty()) fs::remove(f, ignored);
    }
    ::_exit(0);
  }
  ::close(p[0]);
  w.pid = pid;
  w.fd = p[1];
}

}  // namespace cosim::launcher
