#include "render/exr_metadata.h"

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "platform/atomic_file.h"

namespace rockbake {
namespace {

struct HalfImage {
  Imf::Header header;
  Imf::RgbaChannels channels = Imf::WRITE_RGBA;
  int width = 0, height = 0;
  std::vector<Imf::Rgba> pixels;
};

HalfImage readHalf(const std::filesystem::path& file) {
  try {
    Imf::RgbaInputFile in(file.string().c_str());
    HalfImage img;
    img.header = in.header();
    img.channels = in.channels();
    const Imath::Box2i dw = in.dataWindow();
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    img.pixels.resize(std::size_t(img.width) * std::size_t(img.height));
    in.setFrameBuffer(img.pixels.data() - dw.min.x - std::ptrdiff_t(dw.min.y) * img.width, 1, std::size_t(img.width));
    in.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read EXR " + file.string() + ": " + e.what());
  }
}

void addMetadata(Imf::Header& h, const RenderMetadata& m) {
  std::ostringstream cam;
  cam.precision(9);
  cam << "location " << m.camera_location[0] << ' ' << m.camera_location[1] << ' ' << m.camera_location[2]
      << " look_at " << m.camera_look_at[0] << ' ' << m.camera_look_at[1] << ' ' << m.camera_look_at[2] << " angle "
      << m.camera_angle;
  h.insert("rockbake:preset", Imf::StringAttribute(m.preset));
  h.insert("rockbake:seed", Imf::StringAttribute(m.seed));
  h.insert("rockbake:preset_hash", Imf::StringAttribute(m.preset_hash));
  h.insert("rockbake:version", Imf::StringAttribute(m.version));
  h.insert("rockbake:frame", Imf::FloatAttribute(float(m.frame)));
  h.insert("rockbake:camera", Imf::StringAttribute(cam.str()));
  h.insert("rockbake:camera_angle", Imf::FloatAttribute(float(m.camera_angle)));
}

void writeHalf(const std::filesystem::path& target, const Imf::Header& header, Imf::RgbaChannels channels,
               const std::vector<Imf::Rgba>& pixels) {
  std::string bytes;
  try {
    Imf::StdOSStream os;
    {
      Imf::RgbaOutputFile out(os, header, channels, 1);
      const Imath::Box2i dw = header.dataWindow();
      const int width = dw.max.x - dw.min.x + 1;
      out.setFrameBuffer(pixels.data() - dw.min.x - std::ptrdiff_t(dw.min.y) * width, 1, std::size_t(width));
      out.writePixels(dw.max.y - dw.min.y + 1);
    }
    bytes = os.str();
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write EXR " + target.string() + ": " + e.what());
  }
  writeFileAtomically(target, bytes);
}

}  // namespace

void writeExrWithMetadata(const std::filesystem::path& source, const std::filesystem::path& target,
                          const RenderMetadata& metadata) {
  HalfImage img = readHalf(source);
  // POV-Ray stamps the time of the render; without it the EXR depends only on
  // the bake's inputs, so two bakes of one preset give the same bytes.
  img.header.erase("creation");
  addMetadata(img.header, metadata);
  writeHalf(target, img.header, img.channels, img.pixels);
}

void joinExrBands(const std::vector<ExrBand>& bands, const std::filesystem::path& target,
                  const RenderMetadata& metadata) {
  if (bands.empty()) throw std::runtime_error("cannot write EXR " + target.string() + ": no bands");
  HalfImage img = readHalf(bands.front().file);
  std::vector<bool> covered(std::size_t(img.height), false);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const ExrBand& band = bands[b];
    if (band.first_row < 0 || band.end_row > img.height || band.first_row >= band.end_row)
      throw std::runtime_error("cannot write EXR " + target.string() + ": band " + std::to_string(b) +
                               " has rows outside the image");
    const HalfImage part = b == 0 ? HalfImage{} : readHalf(band.file);
    if (b > 0 && (part.width != img.width || part.height != img.height))
      throw std::runtime_error("cannot write EXR " + target.string() + ": " + band.file.string() +
                               " is not the size of " + bands.front().file.string());
    for (int y = band.first_row; y < band.end_row; ++y) {
      if (covered[std::size_t(y)])
        throw std::runtime_error("cannot write EXR " + target.string() + ": row " + std::to_string(y) + " twice");
      covered[std::size_t(y)] = true;
      if (b == 0) continue;
      const std::size_t row = std::size_t(y) * std::size_t(img.width);
      std::copy_n(part.pixels.begin() + std::ptrdiff_t(row), img.width, img.pixels.begin() + std::ptrdiff_t(row));
    }
  }
  if (std::find(covered.begin(), covered.end(), false) != covered.end())
    throw std::runtime_error("cannot write EXR " + target.string() + ": the bands leave rows out");
  img.header.erase("creation");
  addMetadata(img.header, metadata);
  writeHalf(target, img.header, img.channels, img.pixels);
}

std::array<int, 2> writeContactSheet(const std::vector<std::filesystem::path>& frames,
                                     const std::filesystem::path& target, const RenderMetadata& metadata, int columns) {
  if (frames.empty()) throw std::runtime_error("cannot write contact sheet " + target.string() + ": no frames");
  const int n = int(frames.size());
  const int cols = columns > 0 ? columns : int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + cols - 1) / cols;
  int fw = 0, fh = 0, sw = 0, sh = 0;
  std::vector<Imf::Rgba> sheet;
  for (int i = 0; i < n; ++i) {
    const HalfImage img = readHalf(frames[std::size_t(i)]);
    if (i == 0) {
      fw = img.width, fh = img.height;
      sw = fw * cols, sh = fh * rows;
      sheet.assign(std::size_t(sw) * std::size_t(sh), Imf::Rgba(0.0f, 0.0f, 0.0f, 1.0f));
    } else if (img.width != fw || img.height != fh) {
      throw std::runtime_error("cannot write contact sheet " + target.string() + ": " +
                               frames[std::size_t(i)].string() + " is " + std::to_string(img.width) + "x" +
                               std::to_string(img.height) + ", not " + std::to_string(fw) + "x" + std::to_string(fh));
    }
    const int ox = (i % cols) * fw, oy = (i / cols) * fh;
    for (int y = 0; y < fh; ++y) {
      for (int x = 0; x < fw; ++x) {
        Imf::Rgba p = img.pixels[std::size_t(y) * std::size_t(fw) + std::size_t(x)];
        if (!(img.channels & Imf::WRITE_A)) p.a = 1.0f;
        sheet[std::size_t(oy + y) * std::size_t(sw) + std::size_t(ox + x)] = p;
      }
    }
  }
  Imf::Header header(sw, sh);
  header.compression() = Imf::ZIP_COMPRESSION;
  addMetadata(header, metadata);
  writeHalf(target, header, Imf::WRITE_RGBA, sheet);
  return {sw, sh};
}

}  // namespace rockbake
