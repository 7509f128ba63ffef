#include "xr/session.h"

#include <openxr/openxr_platform.h>

#include "gpu/device.h"
#include "gpu/instance.h"
#include "xr/error.h"
#include "xr/instance.h"

namespace ddish::xr {

namespace {

const char* state_name(XrSessionState s) {
  switch (s) {
    case XR_SESSION_STATE_IDLE: return "IDLE";
    case XR_SESSION_STATE_READY: return "READY";
    case XR_SESSION_STATE_SYNCHRONIZED: return "SYNCHRONIZED";
    case XR_SESSION_STATE_VISIBLE: return "VISIBLE";
    case XR_SESSION_STATE_FOCUSED: return "FOCUSED";
    case XR_SESSION_STATE_STOPPING: return "STOPPING";
    case XR_SESSION_STATE_LOSS_PENDING: return "LOSS_PENDING";
    case XR_SESSION_STATE_EXITING: return "EXITING";
    default: return "UNKNOWN";
  }
}

}  // namespace

Session::Session(const Instance& instance, const gpu::Device& device) : instance_(instance) {
  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  binding.instance = device.instance().handle();
  binding.physicalDevice = device.physical();
  binding.device = device.handle();
  binding.queueFamilyIndex = device.queue_family();
  binding.queueIndex = 0;
  XrSessionCreateInfo ci{XR_TYPE_SESSION_CREATE_INFO};
  ci.next = &binding;
  ci.systemId = instance.system();
  check(xrCreateSession(instance.handle(), &ci, &session_), "xrCreateSession");
  try {
    XrReferenceSpaceCreateInfo si{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
    si.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
    si.poseInReferenceSpace.orientation.w = 1.0f;
    check(xrCreateReferenceSpace(session_, &si, &local_), "xrCreateReferenceSpace(LOCAL)");
    for (int e = 0; e < 2; ++e) {
      const EyeSize size = instance.recommended()[static_cast<std::size_t>(e)];
      eyes_[static_cast<std::size_t>(e)] = std::make_unique<EyeSwapchain>(session_, size.width, size.height);
    }
  } catch (...) {
    for (auto& eye : eyes_) eye.reset();
    if (local_ != XR_NULL_HANDLE) xrDestroySpace(local_);
    xrDestroySession(session_);
    throw;
  }
}

Session::~Session() {
  for (auto& eye : eyes_) eye.reset();
  if (local_ != XR_NULL_HANDLE) xrDestroySpace(local_);
  if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
}

void Session::lose() {
  lost_ = true;
  over_ = true;
  running_ = false;
}

void Session::state_changed(XrSessionState state) {
  states_.emplace_back(state_name(state));
  switch (state) {
    case XR_SESSION_STATE_READY: {
      XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO};
      bi.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
      check(xrBeginSession(session_, &bi), "xrBeginSession");
      running_ = true;
      break;
    }
    case XR_SESSION_STATE_STOPPING:
      check(xrEndSession(session_), "xrEndSession");
      running_ = false;
      break;
    case XR_SESSION_STATE_EXITING:
      over_ = true;
      break;
    case XR_SESSION_STATE_LOSS_PENDING:
      lose();
      break;
    default:
      break;
  }
}

void Session::poll_events() {
  for (;;) {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult r = check(xrPollEvent(instance_.handle(), &event), "xrPollEvent");
    if (r == XR_EVENT_UNAVAILABLE) return;
    switch (event.type) {
      case XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED: {
        const auto& e = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        if (e.session == session_) state_changed(e.state);
        break;
      }
      case XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING:
        lose();
        break;
      default:  // events lost, interaction profiles, reference spaces: nothing to do
        break;
    }
    if (lost_) return;
  }
}

Frame Session::begin_frame() {
  Frame f;
  XrFrameWaitInfo wi{XR_TYPE_FRAME_WAIT_INFO};
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  const auto start = std::chrono::steady_clock::now();
  if (check(xrWaitFrame(session_, &wi, &fs), "xrWaitFrame") == XR_SESSION_LOSS_PENDING) {
    lose();
    return f;
  }
  f.waited = std::chrono::steady_clock::now();
  f.wait_ms = std::chrono::duration<double, std::milli>(f.waited - start).count();
  f.display_time = fs.predictedDisplayTime;
  f.display_period = fs.predictedDisplayPeriod;
  f.should_render = fs.shouldRender == XR_TRUE;
  XrFrameBeginInfo bi{XR_TYPE_FRAME_BEGIN_INFO};
  if (check(xrBeginFrame(session_, &bi), "xrBeginFrame") == XR_SESSION_LOSS_PENDING) {
    lose();
    return f;
  }
  if (!f.should_render) return f;
  XrViewLocateInfo li{XR_TYPE_VIEW_LOCATE_INFO};
  li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  li.displayTime = f.display_time;
  li.space = local_;
  XrViewState vs{XR_TYPE_VIEW_STATE};
  std::uint32_t n = 0;
  f.views = {XrView{XR_TYPE_VIEW}, XrView{XR_TYPE_VIEW}};
  if (check(xrLocateViews(session_, &li, &vs, 2, &n, f.views.data()), "xrLocateViews") == XR_SESSION_LOSS_PENDING) {
    lose();
    return f;
  }
  f.located = std::chrono::steady_clock::now();
  // Without a valid pose there is nothing to show this frame (tracking lost).
  const XrViewStateFlags both = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT;
  if ((vs.viewStateFlags & both) != both) f.should_render = false;
  return f;
}

void Session::end_frame(const Frame& frame, bool with_layer) {
  std::array<XrCompositionLayerProjectionView, 2> views{};
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.displayTime = frame.display_time;
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  if (with_layer) {
    for (int e = 0; e < 2; ++e) {
      XrCompositionLayerProjectionView& v = views[static_cast<std::size_t>(e)];
      v.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW;
      v.pose = frame.views[static_cast<std::size_t>(e)].pose;
      v.fov = frame.views[static_cast<std::size_t>(e)].fov;
      v.subImage.swapchain = eye(e).handle();
      v.subImage.imageRect = {{0, 0}, {static_cast<std::int32_t>(eye(e).width()), static_cast<std::int32_t>(eye(e).height())}};
      v.subImage.imageArrayIndex = 0;
    }
    layer.space = local_;
    layer.viewCount = 2;
    layer.views = views.data();
    ei.layerCount = 1;
    ei.layers = layers;
  }
  if (check(xrEndFrame(session_, &ei), "xrEndFrame") == XR_SESSION_LOSS_PENDING) lose();
}

void Session::request_exit() {
  exit_requested_ = true;
  if (running_ && check(xrRequestExitSession(session_), "xrRequestExitSession") == XR_SESSION_LOSS_PENDING) lose();
}

}  // namespace ddish::xr
