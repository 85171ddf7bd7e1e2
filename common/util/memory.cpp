#include "common/util/memory.h"

#include <fmt/format.h>

#include <fstream>
#include <string>

namespace cosim::util {

std::size_t available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

std::string format_bytes(double bytes) {
  if (bytes >= 1024.0 * 1024.0 * 1024.0) return fmt::format("{:.1f} GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  if (bytes >= 1024.0 * 1024.0) return fmt::format("{:.0f} MiB", bytes / (1024.0 * 1024.0));
  return fmt::format("{:.0f} KiB", bytes / 1024.0);
}

}  // namespace cosim::util
