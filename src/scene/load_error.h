// The one error type of scene loading: a single line naming the file and what is wrong with it,
// so the command line can print it as is (`ddish: error: <message>`, exit code 2).
#pragma once

#include <stdexcept>
#include <string>

namespace ddish::scene {

class LoadError : public std::runtime_error {
 public:
  // "FILE: PROBLEM", with any line breaks in the problem (tinygltf reports several lines)
  // folded into "; " so the message stays on one line.
  LoadError(const std::string& file, const std::string& problem);

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace ddish::scene
