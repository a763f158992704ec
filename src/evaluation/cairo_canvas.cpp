// Cairo surfaces for the three formats, each drawn on by the same routine, and text set in one
// font by Cairo's own (toy) text API, which fontconfig resolves to DejaVu Sans.
#include "evaluation/cairo_canvas.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <memory>
#include <stdexcept>

#include "core/srgb.h"

namespace tripath::canvas {

namespace {

constexpr const char* kFont = "DejaVu Sans";  // Debian's fonts-dejavu-core (requireFont checks for it)

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// Cairo records its first error on the context or surface and ignores the calls after it.
void check(cairo_status_t status) {
    if (status != CAIRO_STATUS_SUCCESS) throw std::runtime_error(std::string("drawing: ") + cairo_status_to_string(status));
}

void drawOnto(const Surface& surface, const Drawing& draw) {
    cairo_t* cr = cairo_create(surface.get());
    draw(cr);
    const cairo_status_t status = cairo_status(cr);
    cairo_destroy(cr);
    check(status);
    cairo_surface_flush(surface.get());
    check(cairo_surface_status(surface.get()));
}

cairo_status_t append(void* out, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(out)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

// A vector surface writing into `bytes`, drawn on and finished (which writes its closing parts).
std::string finished(Surface surface, const Drawing& draw, std::string& bytes) {
    drawOnto(surface, draw);
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()));
    return std::move(bytes);
}

}  // namespace

void setColor(cairo_t* cr, const Srgb8& c, double alpha) {
    cairo_set_source_rgba(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, alpha);
}

double advance(cairo_t* cr, const std::string& s, const Font& font) {
    cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font.size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

double textWidth(const std::string& s, const Font& font) {
    const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1), cairo_surface_destroy);
    double w = 0;
    drawOnto(surface, [&](cairo_t* cr) { w = advance(cr, s, font); });
    return w;
}

void text(cairo_t* cr, double x, double y, const std::string& s, const Font& font, Anchor anchor, double angle) {
    const double w = advance(cr, s, font);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, angle);
    cairo_move_to(cr, anchor == Anchor::Start ? 0 : anchor == Anchor::Middle ? -w / 2 : -w, 0);
    cairo_show_text(cr, s.c_str());
    cairo_restore(cr);
}

std::string svgOf(int width, int height, const Drawing& draw) {
    std::string svg;
    Surface surface(cairo_svg_surface_create_for_stream(append, &svg, width, height), cairo_surface_destroy);
    // Pixels, not Cairo's default points: <img width="800"> in a report shows it at its size.
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
    return finished(std::move(surface), draw, svg);
}

std::string pdfOf(int width, int height, const Drawing& draw) {
    std::string pdf;
    return finished(Surface(cairo_pdf_surface_create_for_stream(append, &pdf, width, height), cairo_surface_destroy),
                    draw, pdf);
}

// Cairo's 8-bit values are sRGB-encoded, as a browser shows the SVG; decoded here to the linear
// values that writePng encodes back into the same bytes. Every drawing paints an opaque
// background first, so every pixel has alpha 255 and Cairo's premultiplied colour is the colour.
Image imageOf(int width, int height, const Drawing& draw) {
    const Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height), cairo_surface_destroy);
    drawOnto(surface, draw);
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    Image img(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const uint32_t argb = reinterpret_cast<const uint32_t*>(data + size_t(y) * stride)[x];
            for (int ch = 0; ch < 3; ++ch) img.at(x, y)[ch] = srgbDecode(uint8_t(argb >> (16 - 8 * ch)) / 255.0f);
        }
    return img;
}

}  // namespace tripath::canvas
