// io/host_memory: the kernel's free-memory figure and the byte counts messages print.
#include <gtest/gtest.h>

#include "io/host_memory.h"

using ddish::io::format_bytes;

TEST(HostMemory, AvailableIsReadFromTheKernel) {
  // /proc/meminfo exists on every machine the suite runs on; a figure of 0 or "unknown" would
  // turn every memory check off or refuse every scene.
  const std::uint64_t free = ddish::io::host_memory_available();
  EXPECT_NE(free, UINT64_MAX);
  EXPECT_GT(free, std::uint64_t{64} << 20);
}

TEST(HostMemory, BytesPrintInMiBRoundedUpThenGiB) {
  EXPECT_EQ(format_bytes(0), "0 MiB");
  EXPECT_EQ(format_bytes(1), "1 MiB");  // a need is never printed smaller than it is
  EXPECT_EQ(format_bytes((std::uint64_t{3} << 20) + 1), "4 MiB");
  EXPECT_EQ(format_bytes(std::uint64_t{1023} << 20), "1023 MiB");
  EXPECT_EQ(format_bytes(std::uint64_t{3} << 29), "1.5 GiB");
  EXPECT_EQ(format_bytes(std::uint64_t{1001} << 30), "1001.0 GiB");
}
