// --warmup-ms MS and --warmup-samples N, shared by `render`, `view` and `xr`: the probe warm-up
// before the first visible frame (app/probe_source.h, WarmupOptions), on by default so that the
// first frames show converged indirect light instead of blotches. --warmup-ms 0 turns it off.
#pragma once

#include "app/probe_source.h"

namespace CLI {
class App;
}

namespace ddish::app {

void add_warmup_options(CLI::App& cmd, WarmupOptions& options);
// Throws std::invalid_argument (one line) for a negative or non-finite bound.
void check_warmup_options(const WarmupOptions& options);
// The run log's line for a warm-up that ran.
std::string describe_warmup(const WarmupReport& report, const WarmupOptions& options);

}  // namespace ddish::app
