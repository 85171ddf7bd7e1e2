// What the machine can give a run: the memory the kernel reports as available, for refusing a scene whose state
// would not fit before any of it is allocated.
#pragma once

#include <cstddef>
#include <string>

namespace cosim::util {

// MemAvailable of /proc/meminfo in bytes; 0 where it cannot be read (the check is then skipped).
std::size_t available_memory_bytes();

// "12.3 GiB", "727 MiB", "12 KiB"
std::string format_bytes(double bytes);

}  // namespace cosim::util
