// Loading a glTF 2.0 scene (.gltf with external or data-URI buffers, or .glb) into the scene
// model, together with its sidecar NAME.ddish.json. Every problem with the input is reported
// as a scene::LoadError whose message is one line naming the file.
#pragma once

#include <string>

#include "scene/load_error.h"
#include "scene/scene.h"

namespace ddish::scene {

struct LoadOptions {
  // false: record each texture's width and height only and leave Texture::rgba8 empty. Reading
  // image headers instead of decoding them makes `ddish info` on Sponza take well under a
  // second instead of decoding ~205 MB of pixels it never looks at.
  bool decode_textures = true;
  // false: ignore NAME.ddish.json and keep the sidecar defaults.
  bool read_sidecar = true;
  // Threads used to decode textures (0: one per hardware thread).
  unsigned decode_threads = 0;
};

// Loads the scene and poses it at t = 0.
Scene load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace ddish::scene
