// Timing records: how many milliseconds each named stage of a frame took ("probe_update",
// "shadows", "view 3", ...), frame after frame, written as JSON for the benchmarks and plots.
// DESIGN.md: stage timings are recorded for every frame and can be written as JSON.
//
// JSON form (stage order is the order stages were first recorded in a frame):
//   {"frames": [{"frame": 0, "stages_ms": {"probe_update": 12.5, "raster": 40.1}, "total_ms": 52.6},
//               ...],
//    "summary": {"probe_update": {"frames": 10, "mean_ms": ..., "min_ms": ..., "max_ms": ...}, ...}}
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace ddish::metrics {

struct StageTime {
  std::string name;
  double ms = 0.0;
};

struct FrameTimings {
  std::int64_t frame = 0;
  std::vector<StageTime> stages;  // in the order first recorded

  // Adds ms to the stage of that name (a stage run several times in a frame sums up), or
  // appends it. Throws std::invalid_argument for a negative or non-finite duration.
  void add(std::string_view stage, double ms);
  // The stage's milliseconds, 0 when the frame has no such stage.
  double stage_ms(std::string_view stage) const;
  double total_ms() const;
};

// Measures wall-clock time (steady clock) from construction to stop() or destruction and adds
// it to a frame's stage, so a scope is timed by declaring one.
class StageTimer {
 public:
  StageTimer(FrameTimings& frame, std::string stage);
  ~StageTimer();
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  // Records now (once; later calls and the destructor do nothing) and returns the milliseconds.
  double stop();

 private:
  FrameTimings& frame_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
};

// One frame as {"frame", "stages_ms", "total_ms"}, the element of the "frames" array.
nlohmann::ordered_json frame_json(const FrameTimings& frame);

// The "summary" of frames seen one at a time (a log written as it goes keeps no frames):
// per stage, in first-seen order, the frames it ran in and its mean, min and max.
class StageSummary {
 public:
  void add(const FrameTimings& frame);
  nlohmann::ordered_json to_json() const;

 private:
  struct Stage {
    std::string name;
    int frames = 0;
    double sum = 0.0, min = 0.0, max = 0.0;
  };
  std::vector<Stage> stages_;
};

class TimingLog {
 public:
  void add(FrameTimings frame) { frames_.push_back(std::move(frame)); }
  const std::vector<FrameTimings>& frames() const { return frames_; }
  // The newest frame, for a stage that ends after the frame loop (e.g. waiting for the output
  // writer). Throws std::logic_error when there is none.
  FrameTimings& last();

  nlohmann::ordered_json to_json() const;
  // Reads the "frames" of a to_json() document (the summary is derived, so it is not read).
  // Takes ordered_json so the stages keep their recorded order. Throws std::invalid_argument on
  // a malformed document.
  static TimingLog from_json(const nlohmann::ordered_json& doc);
  static TimingLog read(const std::filesystem::path& path);

  // Writes to_json() to a file (pretty-printed, whole or not at all: io/atomic_file.h); throws
  // std::runtime_error when it cannot.
  void write(const std::filesystem::path& path) const;

 private:
  std::vector<FrameTimings> frames_;
};

}  // namespace ddish::metrics
