// A sheet keeps its items as they are added, and draws them in that order onto whichever Cairo
// surface the format asks for (cairo_canvas.h): one drawing for PNG, PDF and SVG.
#include "evaluation/sheet.h"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tripath {

const Theme& themeNamed(const std::string& name) {
    if (name == "dark") return kDarkTheme;
    if (name == "light") return kLightTheme;
    throw InputError(fmt::format("theme must be dark or light (got '{}')", name.substr(0, 40)));
}

Sheet::Sheet(int width, int height, const Srgb8& background) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) throw InputError(fmt::format("a figure of {}x{} pixels has nothing to show", width, height));
    fill({0, 0, width, height}, background);
}

void Sheet::picture(const Image& image, int x, int y, int scale) { items_.push_back(Picture{image, x, y, scale}); }
void Sheet::fill(const Region& r, const Srgb8& colour) { items_.push_back(Rectangle{r, colour, true}); }
void Sheet::frame(const Region& r, const Srgb8& colour) { items_.push_back(Rectangle{r, colour, false}); }
void Sheet::label(double x, double y, const std::string& text, const Font& font, const Srgb8& colour, Anchor anchor) {
    items_.push_back(Label{x, y, text, font, colour, anchor});
}

void Sheet::place(const Sheet& other, int x, int y) {
    for (Item item : other.items_) {
        std::visit(
            [&](auto& i) {
                if constexpr (std::is_same_v<std::decay_t<decltype(i)>, Rectangle>)
                    i.r.x += x, i.r.y += y;
                else
                    i.x += x, i.y += y;
            },
            item);
        items_.push_back(std::move(item));
    }
}

Sheet stackRows(const std::vector<Sheet>& rows, const Theme& theme) {
    int width = 0, height = 0;
    for (const Sheet& r : rows) width = std::max(width, r.width()), height += r.height();
    Sheet sheet(width, height, theme.background);
    int y = 0;
    for (const Sheet& r : rows) {
        sheet.place(r, 0, y);
        y += r.height();
    }
    return sheet;
}

Sheet colourBar(const ColourBar& b, const Theme& theme) {
    constexpr int kHeight = 56, kBarTop = 24, kBarHeight = 12, kSwatch = 40;
    constexpr Font kFont{12};
    const int ramp = std::max(2, b.rampWidth);
    Sheet sheet(b.width, kHeight, theme.background);
    sheet.label(b.margin, 16, b.title, kFont, theme.title);
    Image pixels(ramp, kBarHeight);
    for (int x = 0; x < ramp; ++x) fillRect(pixels, {x, 0, 1, kBarHeight}, b.colour(double(x) / (ramp - 1)));
    sheet.picture(pixels, b.margin, kBarTop);
    const size_t n = b.ticks.size();
    for (size_t i = 0; i < n; ++i) {
        const int x = b.margin + int(std::lround(n > 1 ? double(i) / double(n - 1) * (ramp - 1) : 0.0));
        sheet.fill({x, kBarTop + kBarHeight, 1, 4}, theme.title);
        sheet.label(x, kBarTop + kBarHeight + 16, b.ticks[i], kFont, theme.detail, Anchor::Middle);
    }
    if (b.swatch) {
        const int x = b.margin + ramp + 24;
        Image swatch(kSwatch, kBarHeight);
        fillRect(swatch, {0, 0, kSwatch, kBarHeight}, b.swatch->first);
        sheet.picture(swatch, x, kBarTop);
        sheet.label(x + kSwatch / 2, kBarTop + kBarHeight + 16, b.swatch->second, kFont, theme.detail, Anchor::Middle);
    }
    return sheet;
}

namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// The picture at its shown size in Cairo's pixel format (premultiplied ARGB, opaque): each pixel
// the bytes writePng would write for it.
Surface pixelsOf(const Sheet::Picture& p) {
    const Image shown = magnified(p.image, p.scale);
    const std::vector<unsigned char> bytes = previewBytes(shown);
    Surface s(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, shown.width, shown.height), cairo_surface_destroy);
    unsigned char* data = cairo_image_surface_get_data(s.get());
    const int stride = cairo_image_surface_get_stride(s.get());
    for (int y = 0; y < shown.height; ++y)
        for (int x = 0; x < shown.width; ++x) {
            const unsigned char* b = &bytes[3 * (size_t(y) * shown.width + x)];
            reinterpret_cast<uint32_t*>(data + size_t(y) * stride)[x] = 0xff000000u | b[0] << 16 | b[1] << 8 | b[2];
        }
    cairo_surface_mark_dirty(s.get());
    return s;
}

void draw(cairo_t* cr, const Sheet::Picture& p) {
    const Surface pixels = pixelsOf(p);
    cairo_set_source_surface(cr, pixels.get(), p.x, p.y);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, p.x, p.y, p.image.width * p.scale, p.image.height * p.scale);
    cairo_fill(cr);
}

void draw(cairo_t* cr, const Sheet::Rectangle& r) {
    canvas::setColor(cr, r.colour);
    cairo_set_line_width(cr, 1);
    if (r.filled) {
        cairo_rectangle(cr, r.r.x, r.r.y, r.r.w, r.r.h);
        cairo_fill(cr);
    } else {
        cairo_rectangle(cr, r.r.x + 0.5, r.r.y + 0.5, r.r.w - 1, r.r.h - 1);
        cairo_stroke(cr);
    }
}

void draw(cairo_t* cr, const Sheet::Label& l) {
    canvas::setColor(cr, l.colour);
    canvas::text(cr, l.x, l.y, l.text, l.font, l.anchor);
}

canvas::Drawing drawingOf(const Sheet& sheet) {
    return [&sheet](cairo_t* cr) {
        // Rectangles lie on whole pixels and stay crisp; text keeps its own (font) antialiasing.
        cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
        for (const Sheet::Item& item : sheet.items()) std::visit([cr](const auto& i) { draw(cr, i); }, item);
    };
}

}  // namespace

Image sheetImage(const Sheet& sheet) { return canvas::imageOf(sheet.width(), sheet.height(), drawingOf(sheet)); }

void writeSheet(const std::string& path, const Sheet& sheet) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".png") return writePng(path, sheetImage(sheet));
    if (ext != ".pdf" && ext != ".svg")
        throw InputError(fmt::format("cannot write '{}': a figure is a .png, .pdf or .svg file", path));
    const std::string bytes = ext == ".pdf" ? canvas::pdfOf(sheet.width(), sheet.height(), drawingOf(sheet))
                                            : canvas::svgOf(sheet.width(), sheet.height(), drawingOf(sheet));
    writeFileAtomically(path, [&](std::ostream& out) { out << bytes; });
}

}  // namespace tripath
