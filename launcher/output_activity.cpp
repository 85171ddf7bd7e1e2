#include "launcher/output_activity.h"

#include <cstdlib>
#include <string>
#include <system_error>

namespace cosim::launcher {

namespace fs = std::filesystem;

OutputActivity output_activity(const fs::path& dir) {
  OutputActivity a;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code e2;
    if (!it->is_regular_file(e2) || e2) continue;
    const auto size = it->file_size(e2);
    const auto when = it->last_write_time(e2);
    if (e2) continue;  // removed meanwhile (a file renamed into place)
    a.bytes += size;
    if (when > a.latest) a.latest = when;
    ++a.files;
  }
  return a;
}

double end_grace_seconds() {
  if (const char* s = std::getenv("COSIM_END_GRACE_S")) {
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end != s && *end == '\0' && v > 0) return v;
  }
  return 10.0;
}

}  // namespace cosim::launcher
