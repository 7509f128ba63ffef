// What a frame of the frame loop did, counted (not timed): the probe source's figures, the
// renderer's passes, the scheduler's log, and for a stream client what the stream brought.
#pragma once

#include <cstdint>
#include <optional>

#include "app/process_resources.h"
#include "probes/scheduler_record.h"

namespace ddish::app {

// A stream client's frame (remote probe source): what it held and received.
struct StreamFrameCounts {
  bool synced = false;            // holds the current server's probes
  std::uint64_t server_frame = 0;  // the server frame held
  double stale_ms = 0.0;           // since the last message from the server
  std::optional<double> probe_age_ms;  // server trace end -> this frame's upload, client clock
  std::uint64_t bytes_received = 0;    // this frame
  std::uint32_t frames_applied = 0;    // this frame
  std::uint64_t rejected = 0;          // malformed or refused messages so far
};

// What a frame did, counted (not timed): the figures that must not grow with the views.
struct FrameCounts {
  std::uint32_t views = 0;
  // Probe tracer runs this frame, read from the volume's update counter (ProbeVolume::frame()),
  // not from the loop's own control flow: one per frame whatever the number of views.
  std::uint64_t probe_updates = 0;
  std::uint64_t probe_rays = 0;  // rays the path tracer cast this frame (probe paths)
  std::uint32_t probes_traced = 0;
  std::uint32_t probes_changed = 0;   // traced or newly inactive: what the loop hands over
  std::uint32_t probes_uploaded = 0;  // what the renderer copied (it may copy the whole volume
                                      // when many changed: ProbeTextures::kFullUploadFraction)
  std::uint32_t probes_imported = 0;  // what the renderer converted on the GPU instead, from the
                                      // averages of a probe tracer on its device (no CPU copy)
  std::uint32_t probes_active = 0;     // after this frame's update
  std::uint32_t probes_inside_geometry = 0;  // of the inactive ones: found inside geometry
  std::uint32_t probes_inactive = 0;   // inside geometry (or otherwise inactive) after it
  std::uint32_t probes_never_updated = 0;  // active probes no update has reached yet
  std::uint32_t oldest_probe_age = 0;      // the largest age of an active probe after it
  std::uint32_t probes_unclassified = 0;   // not yet traced, so not yet known inside or out
  std::uint32_t shadow_passes = 0;     // raster::FrameStats::shadow_passes
  bool shadows_reused = false;
  std::uint32_t forward_passes = 0;
  std::uint32_t tonemap_passes = 0;
  bool read_back = false;       // the views' pixels came back to the CPU (a frame to write)
  bool rendered_again = false;  // the stop came while it rendered unread: drawn again, read back
  // The scheduler's log of this frame (budget, stages, probes traced and skipped, samples,
  // rays); with update_probes off only its stages and budget are filled.
  probes::SchedulerFrameRecord schedule;
  std::optional<StreamFrameCounts> stream;  // remote probe source only
  ProcessResources resources;                // sampled at the end of the frame
};

}  // namespace ddish::app
