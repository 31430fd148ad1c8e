#include "export/gltf_buffer.h"

#include <tiny_gltf.h>

namespace rockbake {

int addBufferView(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  auto& data = model.buffers[0].data;
  while (data.size() % 4) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

}  // namespace rockbake
