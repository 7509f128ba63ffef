// How the forward pass records the N views of a frame (DESIGN.md "Raster cost on lavapipe is
// vertex work"; measured by bench/raster_views, below):
//   per_view   one dynamic-rendering pass per view (layer i of the target), view index pushed;
//   multiview  passes of min(maxMultiviewViewCount, remaining) views with a view mask, each draw
//              replayed for every view of the pass by the device, gl_ViewIndex picks the matrix;
//   layered    one pass over all layers; every draw names its view as its instance and the
//              vertex shader writes gl_Layer (needs shaderOutputLayer).
// Culling is exact per view for per_view and layered, and the union of the pass's frusta for
// multiview (a cluster is drawn in every view of the pass when any of them sees it).
//
// Multiview is wrong on lavapipe of Mesa 22: a primitive its clipper cuts (near plane, beyond
// the guard band) loses its view index and is drawn into the pass's first view only, so big
// walls of view k show up in view 0 (tests/raster/multiview_test.cpp keeps a canary). Layered
// passes are exact: gl_Layer survives the clipper. Hence per_view is RendererOptions' default.
// On lavapipe of Mesa 25 multiview is exact, but the driver keeps the last pass's view mask
// for timestamp queries and wrote past the query pool (a crash in its queue thread): the forward
// pass records an empty one-view pass after its multiview passes there (gpu/driver_quirks.h,
// pinned by tests/gpu/test_driver_quirks.cpp).
//
// Measured (bench/raster_views, Breakfast room 262,687 triangles drawn, 420x560 tiles, a
// 48-view-style light-field rig, lavapipe on the shared 2-core box at load average 3.5-7, so
// +-20% noise; configurations interleaved frame by frame), ms per view:
//                   MSAA 4 (default)                          MSAA 1
//   N views         1          6          12         48*       6
//   per-view  off   539        578        1154       1033      289
//             on    572        704        1339       1288      286
//   multiview off   524        759        1112       1398      247
//             on    534        797        1100       1188      264
//   layered   off   579        835        1085       1230      293
//             on    519        829        1127       1409      290
// (* 48 views as four render() calls of 12, one frame: a single 48-view frame outlasted the
// 60 s fence wait at that load.) Culling drops 21% of the triangles for one view and 27% over
// the rig (per view; 5-23% for multiview's union of six frusta) at 0.1-1.7 ms of CPU recording
// for 1-48 views, but buys no measurable time here: at these tile sizes the room's shading, not
// its vertices, is what a view costs. No method wins beyond the noise at MSAA 4; at MSAA 1
// multiview is ~15% faster, which lavapipe 22's bug rules out.
#pragma once

#include <optional>
#include <string_view>

namespace ddish::raster {

enum class ViewMethod { per_view, multiview, layered };

std::string_view to_string(ViewMethod m);
std::optional<ViewMethod> parse_view_method(std::string_view name);

}  // namespace ddish::raster
