#include "exr_image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <stdexcept>

namespace rockbake::test {

ExrImage readExr(const std::filesystem::path& file, const std::vector<std::string>& channels) {
  Imf::InputFile in(file.string().c_str());
  const Imath::Box2i window = in.header().dataWindow();
  ExrImage image;
  image.width = window.max.x - window.min.x + 1;
  image.height = window.max.y - window.min.y + 1;
  Imf::FrameBuffer frame;
  for (const std::string& name : channels) {
    const Imf::Channel* channel = in.header().channels().findChannel(name);
    if (!channel) throw std::runtime_error(file.string() + " has no channel " + name);
    image.types[name] = channel->type;
    std::vector<float>& plane = image.planes[name];
    plane.assign(std::size_t(image.width) * std::size_t(image.height), 0.0f);
    frame.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), window));
  }
  in.setFrameBuffer(frame);
  in.readPixels(window.min.y, window.max.y);
  return image;
}

}  // namespace rockbake::test
