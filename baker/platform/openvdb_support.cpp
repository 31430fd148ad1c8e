#include "platform/openvdb_support.h"

#include <mutex>

namespace rockbake {

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr voxelCenterTransform(const GridLayout& layout) {
  auto transform = openvdb::math::Transform::createLinearTransform(layout.h);
  const double half = 0.5 * layout.h;
  transform->postTranslate(openvdb::Vec3d(layout.origin[0] + half, layout.origin[1] + half, layout.origin[2] + half));
  return transform;
}

}  // namespace rockbake
