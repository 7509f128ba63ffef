// Files written whole or not at all. Every file ddish writes (images, quilts, probe volumes,
// timings, CSVs, JSON) goes through write_atomically: the content is written to a temporary
// name in the same folder (".NAME.ddish-PID-N.part", hidden, same filesystem), flushed to disk
// and renamed over NAME, which POSIX makes atomic. So a reader, a second run or a run stopped
// half-way never finds a truncated file under the real name: only the old file, or the new one.
//
// A write that fails (a full disk, a file size limit, a folder that vanished) removes its
// temporary and throws std::runtime_error "cannot write NAME: REASON", one line.
//
// Writes in progress are registered (up to kTrackedWrites at once, from any thread) so that a
// signal handler can remove their temporaries before the process ends (remove_partial_files:
// a second Ctrl-C aborts at once and still leaves only whole files).
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>

namespace ddish::io {

inline constexpr std::size_t kTrackedWrites = 16;

// `write` creates and fills the file at the temporary path it is given; it reports a failure
// by throwing any std::exception whose message is the reason (the path is added here).
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

// `bytes` as the whole content of `path`.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// The same guarantee for a file written piece by piece over a long run (a frame loop's per-frame
// timings): the pieces go to the registered temporary as they come, so nothing grows in memory;
// commit() syncs and renames it over the real name. Destroyed without commit(), or after a
// failed write, the temporary is removed and the old file (if any) stays. Each call throws
// std::runtime_error "cannot write NAME: REASON".
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::filesystem::path& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view bytes);
  void commit();
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Open;
  std::filesystem::path path_;
  std::unique_ptr<Open> open_;  // null once committed or failed
};

// Fails early, before any long work: creates `dir` (and its parents) if needed and creates and
// removes a file in it. Throws std::runtime_error "cannot write to output folder DIR: REASON".
void check_writable_folder(const std::filesystem::path& dir);

// check_writable_folder for the folder a file `path` will be written in ("." for a bare name);
// also rejects a `path` that is an existing folder.
void check_writable_file(const std::filesystem::path& path);

// Removes the temporaries of the writes now in progress. Async-signal-safe (unlink only), for
// a signal handler that is about to end the process.
void remove_partial_files() noexcept;

}  // namespace ddish::io
