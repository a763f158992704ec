// A figure laid out once, in pixels, and written as PNG, PDF or SVG: pictures (linear radiance,
// magnified by whole factors, nearest neighbour, so that noise stays noise), rectangles and
// one-line labels, drawn in the order they were added. Cairo draws all three formats from the
// same items, so they show the same thing; in PDF and SVG the labels stay text and the pictures
// stay pixels. The comparison sheets, the error scale and `tripath montage` are sheets.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "evaluation/cairo_canvas.h"
#include "image/draw.h"
#include "image/image.h"

namespace tripath {

using canvas::Anchor, canvas::Font, canvas::Srgb8;

// The colours of a sheet: dark for screens (the reports' default), light for a paper's page.
struct Theme {
    Srgb8 background, title, detail, outline;
};
inline constexpr Theme kDarkTheme{{32, 32, 32}, {255, 255, 255}, {210, 210, 210}, {255, 200, 0}};
inline constexpr Theme kLightTheme{{255, 255, 255}, {0, 0, 0}, {64, 64, 64}, {230, 110, 0}};
// "dark" or "light"; InputError naming the choices otherwise.
const Theme& themeNamed(const std::string& name);

class Sheet {
public:
    Sheet(int width, int height, const Srgb8& background);

    // `image` with its top-left corner at (x, y), each pixel scale × scale pixels; values are linear
    // radiance, shown as writePng writes them (previewBytes).
    void picture(const Image& image, int x, int y, int scale = 1);
    void fill(const Region& r, const Srgb8& colour);
    // A one-pixel frame on the pixels along the region's edge.
    void frame(const Region& r, const Srgb8& colour);
    // One line of text with its baseline at y, anchored at x.
    void label(double x, double y, const std::string& text, const Font& font, const Srgb8& colour,
               Anchor anchor = Anchor::Start);
    // Every item of `other` (its background as a filled rectangle) with its corner at (x, y).
    void place(const Sheet& other, int x, int y);

    int width() const { return width_; }
    int height() const { return height_; }

    struct Picture {
        Image image;
        int x, y, scale;
    };
    struct Rectangle {
        Region r;
        Srgb8 colour;
        bool filled;
    };
    struct Label {
        double x, y;
        std::string text;
        Font font;
        Srgb8 colour;
        Anchor anchor;
    };
    using Item = std::variant<Picture, Rectangle, Label>;
    const std::vector<Item>& items() const { return items_; }

private:
    int width_, height_;
    std::vector<Item> items_;
};

// Images one under the other, left-aligned, on the theme's background.
Sheet stackRows(const std::vector<Sheet>& rows, const Theme& theme);

// A scale that reads a false-colour picture: a title, a horizontal ramp `rampWidth` pixels long
// `margin` pixels from the left, and labelled ticks evenly spaced along it; beside it, optionally,
// a swatch of a colour outside the ramp (a bias map's "biased"). 56 pixels high, `width` across.
struct ColourBar {
    std::string title;
    std::function<Rgb(double t)> colour;  // the ramp's colour at t in [0, 1], left to right
    std::vector<std::string> ticks;       // tick i of n at t = i / (n − 1)
    int width, rampWidth, margin;
    std::optional<std::pair<Rgb, std::string>> swatch{};
};
Sheet colourBar(const ColourBar& bar, const Theme& theme);

// The sheet in the format its path's extension names (.png, .pdf or .svg; InputError otherwise),
// written atomically. PDF pages are sized one point per pixel, SVG in pixels.
void writeSheet(const std::string& path, const Sheet& sheet);
// What the PNG shows, as linear values (writePng encodes them back into its bytes).
Image sheetImage(const Sheet& sheet);

// The extensions writeSheet accepts, for a flag that lists them.
inline const std::vector<std::string> kSheetFormats{"png", "pdf", "svg"};

}  // namespace tripath
