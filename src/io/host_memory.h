// The host's free memory, as the kernel counts it: what a large allocation may still take
// before the out-of-memory killer steps in. Loading a scene and sizing GPU targets on a CPU
// device check against it first, so that an impossible size is one clear error.
#pragma once

#include <cstdint>
#include <string>

namespace ddish::io {

// The system's available memory (MemAvailable in /proc/meminfo), or UINT64_MAX where it cannot
// be read.
std::uint64_t host_memory_available();

// A byte count for messages: "512 MiB", "3.2 GiB".
std::string format_bytes(std::uint64_t bytes);

}  // namespace ddish::io
