// Frames written beside the frame loop. The loop hands each frame's read-back views (moved, not
// copied) to a writer thread and goes on with the next frame; the writer thread encodes them
// (frame_outputs.h), so encoding a quilt overlaps the next frame's probe update and
// rasterization. A full queue blocks the loop: no frame is dropped, and at most `waiting` frames
// wait in memory besides the one being written (0 by default: a frame is handed over when the
// writer is free, so two frames' images are the most a run holds). The first failed write is
// rethrown by the next push() or by finish(); frames after it are not written.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "raster/renderer.h"

namespace ddish::app {

class FrameWriter;

class OutputQueue {
 public:
  // `writer` is borrowed and must outlive the queue.
  explicit OutputQueue(const FrameWriter& writer, std::size_t waiting = 0);
  // Writes what is still queued and joins the writer thread (errors are then dropped: call
  // finish() to see them).
  ~OutputQueue();
  OutputQueue(const OutputQueue&) = delete;
  OutputQueue& operator=(const OutputQueue&) = delete;

  // Queues one frame (`single` and `tag` as for FrameWriter::write); blocks while the queue is
  // full. Returns the milliseconds it waited for room.
  double push(std::vector<raster::ViewImage>&& views, std::string single, std::string tag);

  // Waits until every queued frame is written and returns the files written, in frame order.
  // Rethrows the first write failure.
  std::vector<std::filesystem::path> finish();

 private:
  struct Job {
    std::vector<raster::ViewImage> views;
    std::string single, tag;
  };
  void work();
  void rethrow_failure();  // with mutex_ held

  const FrameWriter& writer_;
  const std::size_t waiting_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool busy_ = false;     // the writer thread holds a job
  bool closing_ = false;  // no more jobs: the thread ends when the queue is empty
  std::exception_ptr failure_;
  std::vector<std::filesystem::path> written_;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace ddish::app
