// The one buffer a GLB holds, filled view by view: shared by the GLB writers of this stage
// (glb_file.cpp, collision_glb.cpp). The model must already have buffers[0].
#pragma once

#include <cstddef>

namespace tinygltf {
class Model;
}

namespace rockbake {

// Appends `size` bytes at `bytes` to buffers[0], aligned to 4 bytes as glTF requires of
// accessors, as a new buffer view with `target` (TINYGLTF_TARGET_*); returns the view's index.
int addBufferView(tinygltf::Model& model, const void* bytes, std::size_t size, int target);

}  // namespace rockbake
