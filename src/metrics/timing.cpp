#include "metrics/timing.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "io/atomic_file.h"

namespace ddish::metrics {

void FrameTimings::add(std::string_view stage, double ms) {
  if (!std::isfinite(ms) || ms < 0.0)
    throw std::invalid_argument("stage " + std::string(stage) + ": duration " +
                                std::to_string(ms) + " ms is not a time");
  for (StageTime& s : stages) {
    if (s.name == stage) {
      s.ms += ms;
      return;
    }
  }
  stages.push_back({std::string(stage), ms});
}

double FrameTimings::stage_ms(std::string_view stage) const {
  for (const StageTime& s : stages)
    if (s.name == stage) return s.ms;
  return 0.0;
}

double FrameTimings::total_ms() const {
  double t = 0.0;
  for (const StageTime& s : stages) t += s.ms;
  return t;
}

StageTimer::StageTimer(FrameTimings& frame, std::string stage)
    : frame_(frame), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}

StageTimer::~StageTimer() { stop(); }

double StageTimer::stop() {
  if (stopped_) return 0.0;
  stopped_ = true;
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
                  .count();
  frame_.add(stage_, ms);
  return ms;
}

FrameTimings& TimingLog::last() {
  if (frames_.empty()) throw std::logic_error("a timing log without frames has no last frame");
  return frames_.back();
}

nlohmann::ordered_json frame_json(const FrameTimings& f) {
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (const StageTime& s : f.stages) stages[s.name] = s.ms;
  return {{"frame", f.frame}, {"stages_ms", stages}, {"total_ms", f.total_ms()}};
}

void StageSummary::add(const FrameTimings& f) {
  for (const StageTime& s : f.stages) {
    auto it = std::find_if(stages_.begin(), stages_.end(), [&](const Stage& x) { return x.name == s.name; });
    if (it == stages_.end()) {
      stages_.push_back({s.name, 1, s.ms, s.ms, s.ms});
    } else {
      it->frames += 1;
      it->sum += s.ms;
      it->min = std::min(it->min, s.ms);
      it->max = std::max(it->max, s.ms);
    }
  }
}

nlohmann::ordered_json StageSummary::to_json() const {
  nlohmann::ordered_json sum = nlohmann::ordered_json::object();
  for (const Stage& s : stages_)
    sum[s.name] = {{"frames", s.frames}, {"mean_ms", s.sum / s.frames}, {"min_ms", s.min}, {"max_ms", s.max}};
  return sum;
}

nlohmann::ordered_json TimingLog::to_json() const {
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  StageSummary summary;
  for (const FrameTimings& f : frames_) {
    frames.push_back(frame_json(f));
    summary.add(f);
  }
  return {{"frames", frames}, {"summary", summary.to_json()}};
}

TimingLog TimingLog::from_json(const nlohmann::ordered_json& doc) {
  TimingLog log;
  try {
    for (const auto& jf : doc.at("frames")) {
      FrameTimings f;
      f.frame = jf.at("frame").get<std::int64_t>();
      for (const auto& [name, ms] : jf.at("stages_ms").items()) f.add(name, ms.get<double>());
      log.add(std::move(f));
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("malformed timing record: ") + e.what());
  }
  return log;
}

TimingLog TimingLog::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read timings from " + path.string());
  nlohmann::ordered_json doc = nlohmann::ordered_json::parse(in, nullptr, false);
  if (doc.is_discarded()) throw std::invalid_argument(path.string() + " is not JSON");
  return from_json(doc);
}

void TimingLog::write(const std::filesystem::path& path) const {
  io::write_file_atomically(path, to_json().dump(2) + '\n');
}

}  // namespace ddish::metrics
