#include "scene/load_error.h"

namespace ddish::scene {

namespace {

std::string one_line(const std::string& text) {
  std::string out;
  bool pending_break = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pending_break = !out.empty();
      continue;
    }
    if (pending_break) {
      out += "; ";
      pending_break = false;
    }
    out += c;
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';' || out.back() == '.'))
    out.pop_back();
  return out.empty() ? std::string("unknown problem") : out;
}

}  // namespace

LoadError::LoadError(const std::string& file, const std::string& problem)
    : std::runtime_error(file + ": " + one_line(problem)), file_(file) {}

}  // namespace ddish::scene
