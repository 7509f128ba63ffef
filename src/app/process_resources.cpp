#include "app/process_resources.h"

#include <dirent.h>
#include <malloc.h>
#include <unistd.h>

#include <cstdio>

#include "gpu/memory.h"

namespace ddish::app {

namespace {

std::int64_t resident_kb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long long size = 0, resident = 0;
  const bool ok = std::fscanf(f, "%lld %lld", &size, &resident) == 2;
  std::fclose(f);
  return ok ? resident * (sysconf(_SC_PAGESIZE) / 1024) : 0;
}

std::int32_t open_descriptors() {
  DIR* dir = opendir("/proc/self/fd");
  if (!dir) return -1;
  std::int32_t n = 0;
  while (const dirent* e = readdir(dir))
    if (e->d_name[0] != '.') ++n;
  closedir(dir);
  return n - 1;  // the directory's own descriptor, open while it is read
}

}  // namespace

void return_free_memory() { malloc_trim(0); }

ProcessResources sample_process_resources() {
  const gpu::MemoryTally gpu = gpu::live_device_memory();
  return {resident_kb(), open_descriptors(), gpu.allocations, gpu.bytes};
}

}  // namespace ddish::app
