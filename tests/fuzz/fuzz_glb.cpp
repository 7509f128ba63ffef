// Binary glTF (.glb: JSON and BIN chunks) through the loader, the scene model and
// SceneFeatures (fuzz_scene.h).
#include "fuzz_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::load_scene_file(data, size, "input.glb");
  return 0;
}
