// Work that may not end in reasonable time, run in a forked child with a deadline.
//
// Some third-party decoders read counts from the bytes they decode and loop over them unbounded
// (libdraco 1.5.5 decodes up to 2^31 texture-coordinate orientations from a 1 KB file, for
// seconds). ddish cannot see inside such a stream before the library reads it, and a thread
// cannot be stopped from outside, so the work runs in a child process that is killed at the
// deadline: a hostile file costs at most the deadline, and then gives one error line.
//
// The child is a fork of this process: the work sees the caller's memory as it was (copy on
// write), runs on the calling thread's copy only (no other thread of the parent exists there),
// and hands back one byte string through a pipe. The child ignores SIGINT / SIGTERM (the parent
// decides what a Ctrl-C means) and is killed if the parent dies first.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace ddish::io {

struct ChildOutcome {
  enum class Status {
    kOk,        // `bytes` is what the work returned
    kFailed,    // the work threw: `bytes` is the exception's message
    kTimedOut,  // killed at the deadline: `bytes` is empty
    kCrashed,   // ended by a signal or exited without an answer: `bytes` says how
  };
  Status status = Status::kCrashed;
  std::string bytes;
};

// Runs `work` in a child process and waits at most `limit` (wall clock) for its answer. Throws
// std::runtime_error only when no child can be started (fork or pipe failed); everything that
// goes wrong inside the child is an outcome.
ChildOutcome run_in_child(const std::function<std::string()>& work, std::chrono::milliseconds limit);

}  // namespace ddish::io
