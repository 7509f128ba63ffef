#include "app/plan_report.h"

#include <fmt/format.h>

namespace ddish::app {

std::vector<std::string> left_out_lines(const scene::RenderPlan& plan, const std::string& indent) {
  std::vector<std::string> lines;
  if (plan.left_out.empty()) lines.push_back(indent + "nothing: the scene uses every pass");
  for (const scene::PlanItem& item : plan.left_out)
    lines.push_back(fmt::format("{}{}: {}", indent, item.what, item.why));
  return lines;
}

}  // namespace ddish::app
