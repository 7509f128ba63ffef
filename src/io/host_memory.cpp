#include "io/host_memory.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace ddish::io {

std::uint64_t host_memory_available() {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return UINT64_MAX;
  char line[256];
  std::uint64_t kb = 0;
  bool found = false;
  while (!found && std::fgets(line, sizeof line, f))
    found = std::sscanf(line, "MemAvailable: %" SCNu64 " kB", &kb) == 1;
  std::fclose(f);
  return found ? kb * 1024 : UINT64_MAX;
}

std::string format_bytes(std::uint64_t bytes) {
  char text[48];
  const double mib = double(bytes) / (1024.0 * 1024.0);
  if (mib < 1024.0)  // rounded up: a need of 1.2 MiB reads "2 MiB", never "1 MiB"
    std::snprintf(text, sizeof text, "%.0f MiB", std::ceil(mib));
  else
    std::snprintf(text, sizeof text, "%.1f GiB", mib / 1024.0);
  return text;
}

}  // namespace ddish::io
