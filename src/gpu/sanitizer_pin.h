// Sanitizer builds only: keeps the Vulkan driver and layer libraries mapped until the process
// exits. The loader dlcloses them when the last instance goes, and LeakSanitizer, which reports
// at exit, then sees their frames as "<unknown module>" and no suppression can name them
// (.ci/sanitizers/lsan.supp). Does nothing in other builds.
#pragma once

namespace ddish::gpu {

void keep_vulkan_libraries_mapped();

}  // namespace ddish::gpu
