#include "render/font_text.h"

#include <stdexcept>

#include <ft2build.h>
#include FT_FREETYPE_H

namespace rockbake {

struct TextRasterizer::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Impl() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
  // Loads and renders the glyph of one character into face->glyph.
  void load(unsigned char c) {
    if (FT_Load_Char(face, FT_ULong(c), FT_LOAD_RENDER) != 0) FT_Load_Char(face, FT_ULong('?'), FT_LOAD_RENDER);
  }
};

std::filesystem::path defaultFontFile() {
  return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

TextRasterizer::TextRasterizer(const std::filesystem::path& font_file, int pixel_height)
    : impl_(std::make_unique<Impl>()) {
  if (FT_Init_FreeType(&impl_->library) != 0) throw std::runtime_error("FreeType could not be initialised");
  if (FT_New_Face(impl_->library, font_file.c_str(), 0, &impl_->face) != 0) {
    std::string hint = font_file == defaultFontFile() ? " (install it with: apt-get install fonts-dejavu-core)" : "";
    throw std::runtime_error("cannot load the font " + font_file.string() + hint);
  }
  if (FT_Set_Pixel_Sizes(impl_->face, 0, FT_UInt(pixel_height)) != 0)
    throw std::runtime_error("the font " + font_file.string() + " has no size " + std::to_string(pixel_height));
}

TextRasterizer::~TextRasterizer() = default;

int TextRasterizer::width(const std::string& text) {
  long advance = 0;
  for (unsigned char c : text) {
    impl_->load(c);
    advance += impl_->face->glyph->advance.x;
  }
  return int(advance >> 6);
}

int TextRasterizer::ascender() const {
  return int(impl_->face->size->metrics.ascender >> 6);
}

void TextRasterizer::draw(RgbImage& image, int x, int baseline_y, const std::string& text,
                          std::array<std::uint8_t, 3> color) {
  long pen = long(x) << 6;
  for (unsigned char c : text) {
    impl_->load(c);
    const FT_GlyphSlot glyph = impl_->face->glyph;
    const FT_Bitmap& bitmap = glyph->bitmap;
    const int left = int(pen >> 6) + glyph->bitmap_left;
    const int top = baseline_y - glyph->bitmap_top;
    for (unsigned row = 0; row < bitmap.rows; ++row)
      for (unsigned column = 0; column < bitmap.width; ++column) {
        const int px = left + int(column), py = top + int(row);
        if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
        const unsigned coverage = bitmap.buffer[std::ptrdiff_t(row) * bitmap.pitch + column];
        if (coverage == 0) continue;
        std::uint8_t* p = &image.pixels[(std::size_t(py) * std::size_t(image.width) + std::size_t(px)) * 3];
        for (int k = 0; k < 3; ++k) p[k] = std::uint8_t((color[k] * coverage + p[k] * (255 - coverage) + 127) / 255);
      }
    pen += glyph->advance.x;
  }
}

std::string TextRasterizer::fit(const std::string& text, int max_width) {
  if (width(text) <= max_width) return text;
  std::string shortened = text;
  while (!shortened.empty() && width(shortened + "...") > max_width) shortened.pop_back();
  return shortened + "...";
}

}  // namespace rockbake
