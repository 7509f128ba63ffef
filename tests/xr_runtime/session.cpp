// The session: its state machine (IDLE -> READY -> [begin] -> SYNCHRONIZED -> VISIBLE ->
// FOCUSED -> ... -> STOPPING -> [end] -> IDLE -> EXITING, or LOSS_PENDING), reference spaces,
// the frame calls and xrLocateViews along the script's head path.
//
// Frame timing: frame k's display period p is the script's at k; xrWaitFrame blocks until one
// period before the frame's display time, which is the previous one's plus p, or now plus p when
// the app was late (missed displays are skipped, not queued).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "functions.h"

namespace ddish::xr_runtime {

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

Session* session_of(XrSession h) {
  return runtime().get<Session>(reinterpret_cast<std::uintptr_t>(h), Kind::session);
}

bool visible(XrSessionState s) {
  return s == XR_SESSION_STATE_VISIBLE || s == XR_SESSION_STATE_FOCUSED;
}

// FOCUSED/VISIBLE/SYNCHRONIZED -> STOPPING, one state at a time as the specification orders.
void stop(Session& s) {
  if (s.state == XR_SESSION_STATE_FOCUSED) change_state(s, XR_SESSION_STATE_VISIBLE);
  if (s.state == XR_SESSION_STATE_VISIBLE) change_state(s, XR_SESSION_STATE_SYNCHRONIZED);
  if (s.state == XR_SESSION_STATE_SYNCHRONIZED) change_state(s, XR_SESSION_STATE_STOPPING);
}

// Multiplies two poses: b expressed in a's frame, to a's parent.
XrPosef compose(const XrPosef& a, const XrPosef& b) {
  const XrQuaternionf& p = a.orientation;
  const XrQuaternionf& q = b.orientation;
  const XrQuaternionf r{p.w * q.x + p.x * q.w + p.y * q.z - p.z * q.y,
                        p.w * q.y - p.x * q.z + p.y * q.w + p.z * q.x,
                        p.w * q.z + p.x * q.y - p.y * q.x + p.z * q.w,
                        p.w * q.w - p.x * q.x - p.y * q.y - p.z * q.z};
  const XrVector3f v = b.position;
  const XrVector3f u{p.x, p.y, p.z};
  const XrVector3f c{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  const XrVector3f cc{u.y * c.z - u.z * c.y, u.z * c.x - u.x * c.z, u.x * c.y - u.y * c.x};
  const XrVector3f rv{v.x + 2.0f * (p.w * c.x + cc.x), v.y + 2.0f * (p.w * c.y + cc.y),
                      v.z + 2.0f * (p.w * c.z + cc.z)};
  return {r, {a.position.x + rv.x, a.position.y + rv.y, a.position.z + rv.z}};
}

XrPosef inverse(const XrPosef& a) {
  const XrQuaternionf qi{-a.orientation.x, -a.orientation.y, -a.orientation.z, a.orientation.w};
  const XrPosef r{qi, {0.0f, 0.0f, 0.0f}};
  const XrPosef t = compose(r, {{0.0f, 0.0f, 0.0f, 1.0f}, a.position});
  return {qi, {-t.position.x, -t.position.y, -t.position.z}};
}

}  // namespace

void change_state(Session& s, XrSessionState state) {
  s.state = state;
  s.states.push_back(state_name(state));
  XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
  auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e->next = nullptr;
  e->session = reinterpret_cast<XrSession>(&s);
  e->state = state;
  e->time = now_ns();
  s.instance->events.push_back(buffer);
}

XrResult XRAPI_CALL create_session(XrInstance handle, const XrSessionCreateInfo* info, XrSession* out) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_SESSION_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (inst->session != nullptr) return XR_ERROR_LIMIT_REACHED;
  const XrGraphicsBindingVulkan2KHR* binding = nullptr;
  for (auto* b = static_cast<const XrBaseInStructure*>(info->next); b; b = b->next)
    if (b->type == XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR) binding = reinterpret_cast<const XrGraphicsBindingVulkan2KHR*>(b);
  if (binding == nullptr) return XR_ERROR_GRAPHICS_DEVICE_INVALID;  // a headless session is not offered
  if (!inst->requirements_queried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
  if (binding->instance == VK_NULL_HANDLE || binding->device == VK_NULL_HANDLE ||
      binding->physicalDevice != inst->named_device)
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  auto s = std::make_unique<Session>();
  s->instance = inst;
  s->binding = *binding;
  s->binding.next = nullptr;
  vkGetDeviceQueue(binding->device, binding->queueFamilyIndex, binding->queueIndex, &s->queue);
  const VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                     VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, binding->queueFamilyIndex};
  if (vkCreateCommandPool(binding->device, &pool, nullptr, &s->pool) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
  Session* raw = s.release();
  runtime().live[raw] = Kind::session;
  inst->session = raw;
  change_state(*raw, XR_SESSION_STATE_IDLE);
  change_state(*raw, XR_SESSION_STATE_READY);
  *out = reinterpret_cast<XrSession>(raw);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_session(XrSession handle) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  write_record(*s);
  for (Swapchain* c : std::vector<Swapchain*>(s->swapchains)) destroy_swapchain_locked(c);
  for (Space* sp : s->spaces) {
    runtime().live.erase(sp);
    delete sp;
  }
  vkDestroyCommandPool(s->binding.device, s->pool, nullptr);
  // Events of a destroyed session are not delivered.
  auto& ev = s->instance->events;
  ev.erase(std::remove_if(ev.begin(), ev.end(), [&](const XrEventDataBuffer& b) {
             return b.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED &&
                    reinterpret_cast<const XrEventDataSessionStateChanged&>(b).session == handle;
           }), ev.end());
  s->instance->session = nullptr;
  runtime().live.erase(s);
  delete s;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL begin_session(XrSession handle, const XrSessionBeginInfo* info) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_SESSION_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (s->running) return XR_ERROR_SESSION_RUNNING;
  if (s->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
    return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  s->running = true;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL end_session(XrSession handle) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (s->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
  s->running = false;
  s->waited.reset();
  s->begun.reset();
  change_state(*s, XR_SESSION_STATE_IDLE);
  // Both the app's request and the script's stop end this runtime's sessions for good.
  change_state(*s, XR_SESSION_STATE_EXITING);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL request_exit_session(XrSession handle) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  s->exit_requested = true;
  stop(*s);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_reference_spaces(XrSession handle, uint32_t capacity, uint32_t* count,
                                               XrReferenceSpaceType* spaces) {
  std::lock_guard lock(runtime().mutex);
  if (session_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  return two_call(std::vector<XrReferenceSpaceType>{XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                                    XR_REFERENCE_SPACE_TYPE_STAGE},
                  capacity, count, spaces);
}

XrResult XRAPI_CALL create_reference_space(XrSession handle, const XrReferenceSpaceCreateInfo* info, XrSpace* out) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_REFERENCE_SPACE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->referenceSpaceType != XR_REFERENCE_SPACE_TYPE_VIEW && info->referenceSpaceType != XR_REFERENCE_SPACE_TYPE_LOCAL &&
      info->referenceSpaceType != XR_REFERENCE_SPACE_TYPE_STAGE)
    return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
  const XrQuaternionf& q = info->poseInReferenceSpace.orientation;
  if (std::fabs(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w - 1.0f) > 1e-3f) return XR_ERROR_POSE_INVALID;
  auto* sp = new Space{s, info->referenceSpaceType, info->poseInReferenceSpace};
  runtime().live[sp] = Kind::space;
  s->spaces.push_back(sp);
  *out = reinterpret_cast<XrSpace>(sp);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_space(XrSpace handle) {
  std::lock_guard lock(runtime().mutex);
  Space* sp = runtime().get<Space>(reinterpret_cast<std::uintptr_t>(handle), Kind::space);
  if (sp == nullptr) return XR_ERROR_HANDLE_INVALID;
  auto& v = sp->session->spaces;
  v.erase(std::remove(v.begin(), v.end(), sp), v.end());
  runtime().live.erase(sp);
  delete sp;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL wait_frame(XrSession handle, const XrFrameWaitInfo* info, XrFrameState* state) {
  std::unique_lock lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if ((info != nullptr && info->type != XR_TYPE_FRAME_WAIT_INFO) || state == nullptr ||
      state->type != XR_TYPE_FRAME_STATE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  const int k = s->frames_waited++;
  const Script& script = s->instance->script;
  if (k == 0) change_state(*s, XR_SESSION_STATE_SYNCHRONIZED);
  if (k == script.synchronized_frames && s->state == XR_SESSION_STATE_SYNCHRONIZED && !s->exit_requested) {
    change_state(*s, XR_SESSION_STATE_VISIBLE);
    change_state(*s, XR_SESSION_STATE_FOCUSED);
  }
  const XrDuration period = script.period_ns(k);
  const XrTime now = now_ns();
  const XrTime display = s->last_display == 0 ? now + period : std::max(s->last_display + period, now + period);
  s->last_display = display;
  FrameRecord rec;
  rec.index = k;
  rec.predicted_display_time = display;
  rec.predicted_display_period = period;
  rec.should_render = visible(s->state);
  s->waited = k;
  s->frames.push_back(rec);
  // Block (unlocked) until one period before the display.
  lock.unlock();
  const XrTime wake = display - period;
  if (wake > now) std::this_thread::sleep_for(std::chrono::nanoseconds(wake - now));
  lock.lock();
  if (session_of(handle) != s) return XR_ERROR_HANDLE_INVALID;
  s->frames[static_cast<std::size_t>(k)].wait_return = now_ns();
  state->predictedDisplayTime = display;
  state->predictedDisplayPeriod = period;
  state->shouldRender = rec.should_render ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL begin_frame(XrSession handle, const XrFrameBeginInfo* info) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info != nullptr && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->waited) return XR_ERROR_CALL_ORDER_INVALID;  // no xrWaitFrame for this frame
  XrResult result = XR_SUCCESS;
  if (s->begun) {  // the frame in progress is discarded
    s->frames[static_cast<std::size_t>(*s->begun)].discarded = true;
    result = XR_FRAME_DISCARDED;
  }
  s->begun = s->waited;
  s->waited.reset();
  s->frames[static_cast<std::size_t>(*s->begun)].begin = now_ns();
  return result;
}

XrResult XRAPI_CALL end_frame(XrSession handle, const XrFrameEndInfo* info) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_FRAME_END_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->begun) return XR_ERROR_CALL_ORDER_INVALID;  // no xrBeginFrame
  FrameRecord& rec = s->frames[static_cast<std::size_t>(*s->begun)];
  if (info->displayTime != rec.predicted_display_time) return XR_ERROR_TIME_INVALID;
  if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
  if (info->layerCount > 0 && info->layers == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (info->layerCount > 16) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
  const XrCompositionLayerProjection* projection = nullptr;
  for (uint32_t i = 0; i < info->layerCount; ++i) {
    const XrCompositionLayerBaseHeader* l = info->layers[i];
    if (l == nullptr || l->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) return XR_ERROR_LAYER_INVALID;
    const auto* p = reinterpret_cast<const XrCompositionLayerProjection*>(l);
    if (!runtime().get<Space>(reinterpret_cast<std::uintptr_t>(p->space), Kind::space)) return XR_ERROR_HANDLE_INVALID;
    if (p->viewCount != 2 || p->views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    for (uint32_t v = 0; v < 2; ++v) {
      const XrSwapchainSubImage& sub = p->views[v].subImage;
      Swapchain* c = runtime().get<Swapchain>(reinterpret_cast<std::uintptr_t>(sub.swapchain), Kind::swapchain);
      if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
      if (!c->released) return XR_ERROR_LAYER_INVALID;  // nothing released to show
      if (sub.imageRect.offset.x < 0 || sub.imageRect.offset.y < 0 || sub.imageRect.extent.width < 1 ||
          sub.imageRect.extent.height < 1 ||
          std::uint32_t(sub.imageRect.offset.x + sub.imageRect.extent.width) > c->width ||
          std::uint32_t(sub.imageRect.offset.y + sub.imageRect.extent.height) > c->height)
        return XR_ERROR_SWAPCHAIN_RECT_INVALID;
      if (sub.imageArrayIndex != 0) return XR_ERROR_VALIDATION_FAILURE;
    }
    projection = p;
  }
  rec.end = now_ns();
  rec.ended = true;
  if (projection != nullptr) {
    const Space* space = runtime().get<Space>(reinterpret_cast<std::uintptr_t>(projection->space), Kind::space);
    for (uint32_t v = 0; v < 2; ++v) {
      const XrCompositionLayerProjectionView& pv = projection->views[v];
      // Submitted poses are in the layer's space; the record holds them in LOCAL.
      rec.submitted.push_back({compose(space->pose, pv.pose), pv.fov});
      if (!s->instance->out.empty() && s->instance->script.record_images) {
        Swapchain* c = runtime().get<Swapchain>(reinterpret_cast<std::uintptr_t>(pv.subImage.swapchain), Kind::swapchain);
        const std::string name = "frame_" + std::to_string(1000000 + rec.index).substr(1) +
                                 (v == 0 ? "_left.exr" : "_right.exr");
        rec.images.push_back(record_image(*s, *c, *c->released, pv.subImage.imageRect, s->instance->out / name));
      }
    }
  }
  s->begun.reset();
  const int done = rec.index + 1;
  const Script& script = s->instance->script;
  if (script.loss_after && done >= *script.loss_after && !s->loss_pending) {
    s->loss_pending = true;
    change_state(*s, XR_SESSION_STATE_LOSS_PENDING);
  } else if (script.stop_after && done >= *script.stop_after && s->state != XR_SESSION_STATE_STOPPING) {
    stop(*s);
  }
  return XR_SUCCESS;
}

XrResult XRAPI_CALL locate_views(XrSession handle, const XrViewLocateInfo* info, XrViewState* state,
                                 uint32_t capacity, uint32_t* count, XrView* views) {
  std::lock_guard lock(runtime().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || state == nullptr || count == nullptr || info->type != XR_TYPE_VIEW_LOCATE_INFO ||
      state->type != XR_TYPE_VIEW_STATE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
    return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  const Space* space = runtime().get<Space>(reinterpret_cast<std::uintptr_t>(info->space), Kind::space);
  if (space == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  *count = 2;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
  if (views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  // The frame whose display time is nearest: where the head is then.
  FrameRecord* frame = nullptr;
  for (FrameRecord& f : s->frames)
    if (!frame || std::llabs(f.predicted_display_time - info->displayTime) <
                      std::llabs(frame->predicted_display_time - info->displayTime))
      frame = &f;
  const Script& script = s->instance->script;
  const XrPosef head = script.head(frame ? frame->index : 0);
  // A space's pose is given in LOCAL (STAGE is LOCAL here); VIEW follows the head.
  const XrPosef base = space->type == XR_REFERENCE_SPACE_TYPE_VIEW ? compose(head, space->pose) : space->pose;
  const XrPosef to_space = inverse(base);
  state->viewStateFlags = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT |
                          XR_VIEW_STATE_ORIENTATION_TRACKED_BIT | XR_VIEW_STATE_POSITION_TRACKED_BIT;
  if (frame) frame->located.clear();
  for (int e = 0; e < 2; ++e) {
    if (views[e].type != XR_TYPE_VIEW) return XR_ERROR_VALIDATION_FAILURE;
    const XrPosef eye = eye_pose(head, script.ipd, e);
    views[e].pose = compose(to_space, eye);
    views[e].fov = script.fov[e];
    if (frame) frame->located.push_back({eye, script.fov[e]});
  }
  if (frame) frame->located_at = now_ns();
  return XR_SUCCESS;
}

}  // namespace ddish::xr_runtime
