// Labels drawn by OpenImageIO's render_text straight into the Image's pixels (no copy): it finds
// the font by name, anchors the text and blends the glyphs' coverage over what is there.
#include "image/text.h"

#include <OpenImageIO/imagebufalgo.h>

#include "core/error.h"

namespace tripath {

namespace {

// Names, not paths: OIIO searches the system font directories (/usr/share/fonts/...) for them.
const char* fontName(bool bold) { return bold ? "DejaVuSans-Bold" : "DejaVuSans"; }

OIIO::ROI measure(const std::string& text, const TextStyle& style) {
    OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, style.size, fontName(style.bold));
    OIIO::geterror();  // drained: OIIO complains at exit about errors nobody read
    return r;
}

OIIO::ImageBufAlgo::TextAlignX alignOf(Align a) {
    using OIIO::ImageBufAlgo::TextAlignX;
    return a == Align::Left ? TextAlignX::Left : a == Align::Center ? TextAlignX::Center : TextAlignX::Right;
}

}  // namespace

void requireFont() {
    for (bool bold : {false, true})
        if (!measure("Ag", {14, {}, bold}).defined())
            throw InputError(std::string("font ") + fontName(bold) +
                             " not found: install the fonts-dejavu-core package (scripts/install-deps.sh does)");
}

void drawText(Image& img, int x, int y, const std::string& text, const TextStyle& style) {
    if (text.empty()) return;
    OIIO::ImageBuf pixels(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT), img.rgb.data());
    const float color[3] = {style.color.r, style.color.g, style.color.b};
    if (!OIIO::ImageBufAlgo::render_text(pixels, x, y, text, style.size, fontName(style.bold), color,
                                         alignOf(style.align))) {
        pixels.geterror();
        OIIO::geterror();
        throw InputError(std::string("cannot draw text: font ") + fontName(style.bold) +
                         " not found (install the fonts-dejavu-core package)");
    }
}

int textWidth(const std::string& text, const TextStyle& style) {
    if (text.empty()) return 0;
    const OIIO::ROI r = measure(text, style);
    return r.defined() ? r.width() : 0;
}

}  // namespace tripath
