// The test runtime's script: a head-pose path and what the runtime does along it, read from the
// JSON file named by DDISH_XR_SCRIPT (tests/xr_runtime/README.md has the format). Frame k is
// the k-th xrWaitFrame of the session; everything is keyed on frame indices, not on time, so a
// slow CPU renderer sees the same poses as a fast one.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <openxr/openxr.h>

namespace ddish::xr_runtime {

struct PoseKey {
  int frame = 0;
  XrVector3f position{0.0f, 0.0f, 0.0f};
  XrQuaternionf orientation{0.0f, 0.0f, 0.0f, 1.0f};
  std::optional<double> display_hz;  // from this frame on
};

struct Script {
  int eye_width = 64;   // recommended per-eye image size
  int eye_height = 72;
  float ipd = 0.063f;   // metres, along the head's x axis
  XrFovf fov[2] = {{-0.8727f, 0.7505f, 0.8203f, -0.9250f}, {-0.7505f, 0.8727f, 0.8203f, -0.9250f}};
  double display_hz = 90.0;
  int synchronized_frames = 1;   // frames at the start that the session is only SYNCHRONIZED
  std::optional<int> stop_after;  // the runtime ends the session after this many frames
  std::optional<int> loss_after;  // LOSS_PENDING after this many frames
  bool record_images = true;      // write each submitted eye image as EXR
  std::vector<PoseKey> keys;      // increasing frames; empty: the head at the origin

  // Throws std::runtime_error naming the file and the problem.
  static Script load(const std::filesystem::path& path);

  // The head pose at frame k: linear in position, normalized-linear in orientation between the
  // keys around k, held before the first key and after the last.
  XrPosef head(int frame) const;
  // The display period at frame k, nanoseconds.
  XrDuration period_ns(int frame) const;
};

// Eye `eye` (0 left, 1 right) of the head pose: ipd / 2 along the head's x axis.
XrPosef eye_pose(const XrPosef& head, float ipd, int eye);

}  // namespace ddish::xr_runtime
