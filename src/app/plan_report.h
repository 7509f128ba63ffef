// What a scene's render plan leaves out and why (scene::RenderPlan::left_out), as the text lines
// both `ddish info` and `ddish render` print.
#pragma once

#include <string>
#include <vector>

#include "scene/features.h"

namespace ddish::app {

// One line per item, "WHAT: WHY", each prefixed by `indent`; a single "nothing: ..." line when
// the plan leaves nothing out.
std::vector<std::string> left_out_lines(const scene::RenderPlan& plan, const std::string& indent);

}  // namespace ddish::app
