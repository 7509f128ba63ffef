// The loader <-> runtime negotiation of the OpenXR loader specification ("Runtime Interface
// Negotiation"), declared here from the specification's text: Debian's libopenxr-dev ships
// openxr.h but not the SDK's loader_interfaces.h. Only the runtime half is declared (no API
// layer structs): the loader passes an XrNegotiateLoaderInfo and the runtime fills an
// XrNegotiateRuntimeRequest with its interface version, API version and xrGetInstanceProcAddr.
#pragma once

#include <cstddef>
#include <cstdint>

#include <openxr/openxr.h>

namespace ddish::xr_runtime {

// XrLoaderInterfaceStructs: the structType of the negotiation structs.
enum LoaderInterfaceStruct : std::int32_t {
  kStructUninitialized = 0,
  kStructLoaderInfo = 1,
  kStructApiLayerRequest = 2,
  kStructRuntimeRequest = 3,
  kStructApiLayerCreateInfo = 4,
  kStructApiLayerNextInfo = 5,
};

inline constexpr std::uint32_t kLoaderInfoStructVersion = 1;   // XR_LOADER_INFO_STRUCT_VERSION
inline constexpr std::uint32_t kRuntimeInfoStructVersion = 1;  // XR_RUNTIME_INFO_STRUCT_VERSION
inline constexpr std::uint32_t kLoaderRuntimeInterface = 1;    // XR_CURRENT_LOADER_RUNTIME_VERSION

struct NegotiateLoaderInfo {  // XrNegotiateLoaderInfo
  LoaderInterfaceStruct structType;
  std::uint32_t structVersion;
  std::size_t structSize;
  std::uint32_t minInterfaceVersion;
  std::uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};

struct NegotiateRuntimeRequest {  // XrNegotiateRuntimeRequest
  LoaderInterfaceStruct structType;
  std::uint32_t structVersion;
  std::size_t structSize;
  std::uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};

}  // namespace ddish::xr_runtime
