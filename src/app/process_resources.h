// What the process holds at a moment: resident memory, open file descriptors and live Vulkan
// device-memory allocations. Sampled after every frame of the frame loop (a few microseconds) and
// written to --timings, so a long run shows whether anything grows (scripts/soak.sh).
#pragma once

#include <cstdint>

namespace ddish::app {

struct ProcessResources {
  std::int64_t rss_kb = 0;           // resident set size (/proc/self/statm), 0 where unknown
  std::int32_t open_fds = 0;         // entries of /proc/self/fd, -1 where unknown
  std::int64_t gpu_allocations = 0;  // live gpu::DeviceMemory allocations
  std::int64_t gpu_bytes = 0;        // and their bytes
};

ProcessResources sample_process_resources();

// Hands the allocator's free pages back to the system (glibc's malloc_trim over every arena);
// a few milliseconds at most, so the frame loop does it every kTrimInterval frames.
inline constexpr int kTrimInterval = 100;
void return_free_memory();

}  // namespace ddish::app
