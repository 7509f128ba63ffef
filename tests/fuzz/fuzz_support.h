// Shared by the fuzz targets (fuzz_*.cpp): what counts as handling bad input correctly, and a
// scratch file for the loaders that read from a path.
//
// A target feeds its input to one reader and returns 0. The reader may reject the input by
// throwing a std::exception whose message is one non-empty line (that line is what `ddish`
// prints after "ddish: error: "). Anything else is a finding and aborts, so that libFuzzer and
// the standalone driver report it: a crash, a sanitizer report, an exception of another type, a
// message that is empty or spans lines, or an allocation failure (bad input must never ask for
// more memory than the machine has: a few KB of file asking for gigabytes is unbounded trust).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>

namespace fuzz {

[[noreturn]] inline void finding(const char* what, const char* detail) {
  std::fprintf(stderr, "fuzz finding: %s: %s\n", what, detail);
  std::abort();
}

// A property the target checks of what it decoded; false is a finding.
inline void require(bool condition, const char* what = "a decoded value broke its invariant") {
  if (!condition) finding("invariant", what);
}

// Runs `read`; returns true when it accepted the input, false when it rejected it properly.
template <typename Read>
bool accepts(Read&& read) {
  try {
    read();
    return true;
  } catch (const std::bad_alloc& e) {
    finding("allocation failure on bad input", e.what());
  } catch (const std::length_error& e) {
    finding("impossible size on bad input", e.what());
  } catch (const std::exception& e) {
    const char* m = e.what();
    if (m == nullptr || *m == '\0') finding("empty error message", typeid(e).name());
    if (std::strchr(m, '\n') != nullptr) finding("error message of more than one line", m);
    return false;
  } catch (...) {
    finding("exception not derived from std::exception", "");
  }
}

// The input as a file named `name` in a scratch folder of this process (removed at exit), for
// readers that take a path. Files the input refers to (glTF buffers, images) resolve against
// that folder, which holds nothing else.
inline std::string as_file(const std::uint8_t* data, std::size_t size, const char* name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                    ("ddish-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    static const std::string keep = d.string();  // for the exit handler
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(keep, ec);
    });
    return d;
  }();
  const std::string path = (dir / name).string();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) finding("cannot write the scratch file", path.c_str());
  if (size > 0 && std::fwrite(data, 1, size, f) != size) finding("short scratch write", path.c_str());
  std::fclose(f);
  return path;
}

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace fuzz
