// The test runtime through the real loader, called directly: the error codes the OpenXR
// specification requires for a missing graphics-requirements call, a missing binding, wrong call
// order and wrong handles, and the session states it walks through. No validation layer here:
// it would catch the misuse before the runtime sees it.
#include <cstdlib>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "gpu/context.h"
#include "xr/instance.h"
#include "xr/session.h"
#include "xr/vulkan_binding.h"

namespace {

class RuntimeApi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ::setenv("XR_RUNTIME_JSON", DDISH_XR_RUNTIME_JSON, 1);
    ::unsetenv("DDISH_XR_SCRIPT");
    ::unsetenv("DDISH_XR_OUT");
  }
};

TEST_F(RuntimeApi, SessionNeedsTheGraphicsRequirementsAndABinding) {
  ddish::xr::Instance xr;
  EXPECT_EQ(xr.runtime_name(), "ddish headless test runtime");
  EXPECT_EQ(xr.recommended()[0].width, 64u);
  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  XrSessionCreateInfo ci{XR_TYPE_SESSION_CREATE_INFO};
  ci.next = &binding;
  ci.systemId = xr.system();
  XrSession session = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateSession(xr.handle(), &ci, &session), XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);
  auto requirements = xr.function<PFN_xrGetVulkanGraphicsRequirements2KHR>("xrGetVulkanGraphicsRequirements2KHR");
  XrGraphicsRequirementsVulkan2KHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
  ASSERT_EQ(requirements(xr.handle(), xr.system(), &req), XR_SUCCESS);
  EXPECT_LE(req.minApiVersionSupported, XR_MAKE_VERSION(1, 3, 0));
  ci.next = nullptr;  // no binding: a headless session is not offered
  EXPECT_EQ(xrCreateSession(xr.handle(), &ci, &session), XR_ERROR_GRAPHICS_DEVICE_INVALID);
  ci.next = &binding;  // a binding whose handles are not the runtime's device
  EXPECT_EQ(xrCreateSession(xr.handle(), &ci, &session), XR_ERROR_GRAPHICS_DEVICE_INVALID);
  XrSystemGetInfo si{XR_TYPE_SYSTEM_GET_INFO};
  si.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
  XrSystemId id = XR_NULL_SYSTEM_ID;
  EXPECT_EQ(xrGetSystem(xr.handle(), &si, &id), XR_ERROR_FORM_FACTOR_UNSUPPORTED);
  XrSystemProperties sp{XR_TYPE_SYSTEM_PROPERTIES};
  EXPECT_EQ(xrGetSystemProperties(xr.handle(), xr.system() + 7, &sp), XR_ERROR_SYSTEM_INVALID);
}

TEST_F(RuntimeApi, FrameCallsInTheWrongOrderAndWrongHandlesAreRefused) {
  ddish::xr::Instance xr;
  ddish::gpu::ContextOptions co;
  ddish::xr::bind_vulkan(xr, co);
  ddish::gpu::Context gpu(co);
  ddish::xr::Session session(xr, gpu.device());
  const XrSession s = session.handle();
  XrFrameWaitInfo wi{XR_TYPE_FRAME_WAIT_INFO};
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  XrFrameBeginInfo bi{XR_TYPE_FRAME_BEGIN_INFO};
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  // Not begun yet (READY is only queued).
  EXPECT_EQ(xrWaitFrame(s, &wi, &fs), XR_ERROR_SESSION_NOT_RUNNING);
  session.poll_events();  // IDLE, READY: xrBeginSession
  ASSERT_TRUE(session.running());
  XrSessionBeginInfo again{XR_TYPE_SESSION_BEGIN_INFO};
  again.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  EXPECT_EQ(xrBeginSession(s, &again), XR_ERROR_SESSION_RUNNING);
  EXPECT_EQ(xrBeginFrame(s, &bi), XR_ERROR_CALL_ORDER_INVALID);  // no xrWaitFrame
  EXPECT_EQ(xrEndFrame(s, &ei), XR_ERROR_CALL_ORDER_INVALID);    // no xrBeginFrame
  ASSERT_EQ(xrWaitFrame(s, &wi, &fs), XR_SUCCESS);
  EXPECT_GT(fs.predictedDisplayPeriod, 0);
  EXPECT_EQ(fs.shouldRender, XR_FALSE);  // frame 0 is SYNCHRONIZED only
  ASSERT_EQ(xrBeginFrame(s, &bi), XR_SUCCESS);
  ei.displayTime = fs.predictedDisplayTime + 1;
  EXPECT_EQ(xrEndFrame(s, &ei), XR_ERROR_TIME_INVALID);
  ei.displayTime = fs.predictedDisplayTime;
  // A projection layer of a swapchain that never released an image is not a layer.
  XrCompositionLayerProjectionView views[2] = {{XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW},
                                               {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW}};
  for (int e = 0; e < 2; ++e) {
    views[e].subImage.swapchain = session.eye(e).handle();
    views[e].subImage.imageRect = {{0, 0}, {64, 72}};
  }
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  layer.space = session.local_space();
  layer.viewCount = 2;
  layer.views = views;
  const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
  ei.layerCount = 1;
  ei.layers = layers;
  EXPECT_EQ(xrEndFrame(s, &ei), XR_ERROR_LAYER_INVALID);
  ei.layerCount = 0;
  EXPECT_EQ(xrEndFrame(s, &ei), XR_SUCCESS);
  // Swapchain images: wait or release before acquire, and all acquired at once.
  const XrSwapchain chain = session.eye(0).handle();
  XrSwapchainImageWaitInfo swi{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  swi.timeout = XR_INFINITE_DURATION;
  XrSwapchainImageReleaseInfo sri{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
  EXPECT_EQ(xrWaitSwapchainImage(chain, &swi), XR_ERROR_CALL_ORDER_INVALID);
  EXPECT_EQ(xrReleaseSwapchainImage(chain, &sri), XR_ERROR_CALL_ORDER_INVALID);
  XrSwapchainImageAcquireInfo sai{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
  std::uint32_t index = 0;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(xrAcquireSwapchainImage(chain, &sai, &index), XR_SUCCESS);
  EXPECT_EQ(xrAcquireSwapchainImage(chain, &sai, &index), XR_ERROR_CALL_ORDER_INVALID);
  // Ending a session that is not STOPPING.
  EXPECT_EQ(xrEndSession(s), XR_ERROR_SESSION_NOT_STOPPING);
  // Wrong handles: a swapchain handle where a session goes, and a made-up one.
  EXPECT_EQ(xrBeginFrame(reinterpret_cast<XrSession>(chain), &bi), XR_ERROR_HANDLE_INVALID);
  EXPECT_EQ(xrDestroySwapchain(reinterpret_cast<XrSwapchain>(std::uintptr_t{0x1234560})), XR_ERROR_HANDLE_INVALID);
  session.request_exit();
  session.poll_events();  // ... STOPPING: xrEndSession, IDLE, EXITING
  EXPECT_TRUE(session.over());
  EXPECT_FALSE(session.lost());
  EXPECT_EQ(session.states().back(), "EXITING");
}

}  // namespace
