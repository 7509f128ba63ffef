#include "gpu/sanitizer_pin.h"

#if defined(__SANITIZE_ADDRESS__)
#define DDISH_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DDISH_ASAN 1
#endif
#endif

#ifdef DDISH_ASAN
#include <dlfcn.h>
#include <link.h>

#include <cstring>
#endif

namespace ddish::gpu {

void keep_vulkan_libraries_mapped() {
#ifdef DDISH_ASAN
  // Every loaded driver (libvulkan_*.so: lavapipe is libvulkan_lvp.so) and layer
  // (libVkLayer_*.so) is marked RTLD_NODELETE; RTLD_NOLOAD opens nothing new.
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const char* name = info->dlpi_name;
        if (name != nullptr && (std::strstr(name, "/libvulkan_") || std::strstr(name, "/libVkLayer_")))
          dlopen(name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
#endif
}

}  // namespace ddish::gpu
