#include "image/text.h"

#include <OpenImageIO/imagebufalgo.h>

#include <vector>

#include "geometry/error.h"

namespace tripath {

namespace {

// Names, not paths: OIIO searches the system font directories (/usr/share/fonts/...) for them.
const char* fontName(bool bold) { return bold ? "DejaVuSans-Bold" : "DejaVuSans"; }

// Glyph coverage of one line of text, `baseline` rows below its top.
struct Mask {
    int width = 0, height = 0, baseline = 0, left = 0;
    std::vector<float> coverage;
    float at(int x, int y) const { return coverage[size_t(y) * width + x]; }
};

OIIO::ROI measure(const std::string& text, const TextStyle& style) {
    OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, style.size, fontName(style.bold));
    OIIO::geterror();  // drained: OIIO complains at exit about errors nobody read
    return r;
}

Mask rasterise(const std::string& text, const TextStyle& style) {
    const OIIO::ROI r = measure(text, style);
    if (!r.defined()) throw InputError(std::string("cannot draw text: font ") + fontName(style.bold) +
                                       " not found (install the fonts-dejavu-core package)");
    Mask m;
    m.width = r.width() + 2;  // a pixel of slack on each side for anti-aliased edges
    m.height = r.height() + 2;
    m.left = r.xbegin - 1;
    m.baseline = -r.ybegin + 1;
    OIIO::ImageBuf buf(OIIO::ImageSpec(m.width, m.height, 1, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::zero(buf);
    const float white = 1.0f;
    OIIO::ImageBufAlgo::render_text(buf, -m.left, m.baseline, text, style.size, fontName(style.bold),
                                    OIIO::cspan<float>(&white, 1));
    buf.geterror();
    m.coverage.resize(size_t(m.width) * m.height);
    buf.get_pixels(OIIO::ROI(0, m.width, 0, m.height, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT, m.coverage.data());
    return m;
}

int alignOffset(int width, Align align) {
    return align == Align::Left ? 0 : align == Align::Center ? -width / 2 : -width;
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
    const Mask m = rasterise(text, style);
    const int x0 = x + m.left + alignOffset(m.width - 2, style.align), y0 = y - m.baseline;
    for (int my = 0; my < m.height; ++my)
        for (int mx = 0; mx < m.width; ++mx) blendPixel(img, x0 + mx, y0 + my, style.color, m.at(mx, my));
}

int textWidth(const std::string& text, const TextStyle& style) {
    if (text.empty()) return 0;
    const OIIO::ROI r = measure(text, style);
    return r.defined() ? r.width() : 0;
}

}  // namespace tripath
