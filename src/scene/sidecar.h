// The sidecar NAME.ddish.json beside NAME.gltf: what glTF cannot say (environment radiance,
// probe grid, default camera). Format: ../shared/scenes/README.md.
#pragma once

#include <string>

#include "scene/scene.h"

namespace ddish::scene {

// dir/NAME.ddish.json for dir/NAME.gltf (or .glb).
std::string sidecar_path(const std::string& scene_path);

// Parses a sidecar's text. Unknown members are ignored (other modules may add their own);
// known members of the wrong shape throw a LoadError naming `file`.
Sidecar parse_sidecar(const std::string& text, const std::string& file);

// The sidecar beside a scene; defaults when there is none.
Sidecar load_sidecar(const std::string& scene_path);

}  // namespace ddish::scene
