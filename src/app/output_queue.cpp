#include "app/output_queue.h"

#include <chrono>
#include <utility>

#include "app/frame_outputs.h"

namespace ddish::app {

OutputQueue::OutputQueue(const FrameWriter& writer, std::size_t waiting)
    : writer_(writer), waiting_(waiting), thread_([this] { work(); }) {}

OutputQueue::~OutputQueue() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void OutputQueue::rethrow_failure() {
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

double OutputQueue::push(std::vector<raster::ViewImage>&& views, std::string single, std::string tag) {
  const auto start = std::chrono::steady_clock::now();
  std::unique_lock lock(mutex_);
  // Room: fewer than `waiting` frames queued, and with none allowed to wait, an idle writer.
  changed_.wait(lock, [&] {
    return (jobs_.size() + (busy_ ? 1u : 0u) < waiting_ + 1) || failure_;
  });
  rethrow_failure();
  jobs_.push_back({std::move(views), std::move(single), std::move(tag)});
  lock.unlock();
  changed_.notify_all();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::filesystem::path> OutputQueue::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return (jobs_.empty() && !busy_) || failure_; });
  rethrow_failure();
  return std::exchange(written_, {});
}

void OutputQueue::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !jobs_.empty() || closing_; });
    if (jobs_.empty()) return;  // closing, and everything is written
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    lock.unlock();
    changed_.notify_all();  // room for the next push
    std::vector<std::filesystem::path> files;
    std::exception_ptr failure;
    try {
      files = writer_.write(RasterFrameViews(job.views), job.single, job.tag);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
    busy_ = false;
    if (failure) {
      failure_ = failure;
      jobs_.clear();  // the frames after a failed one are not written
    }
    for (auto& f : files) written_.push_back(std::move(f));
    changed_.notify_all();
  }
}

}  // namespace ddish::app
