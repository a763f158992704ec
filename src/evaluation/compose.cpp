#include "evaluation/compose.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "evaluation/metrics.h"
#include "image/text.h"

namespace tripath {

namespace {

constexpr int kGap = 8, kLabelHeight = 44;

Image magnify(const Image& img, int scale) {
    Image out(img.width * scale, img.height * scale);
    paste(out, img, 0, 0, scale);
    return out;
}

void checkPanels(const std::vector<Panel>& panels, const Region& r) {
    if (panels.empty()) throw InputError("side-by-side: no images to compose");
    const Image& first = panels.front().image;
    for (const Panel& p : panels)
        if (p.image.width != first.width || p.image.height != first.height)
            throw InputError(fmt::format("side-by-side: '{}' is {}x{}, the others {}x{}", p.title, p.image.width,
                                         p.image.height, first.width, first.height));
    crop(first, r.x, r.y, r.w, r.h);  // throws InputError for a region outside the image
}

}  // namespace

Image sideBySide(const std::vector<Panel>& panels, const Region& r, int minWidth) {
    checkPanels(panels, r);
    const int w = panels.front().image.width, h = panels.front().image.height;
    const int scale = std::max(1, (minWidth + w - 1) / w);
    const int panelW = w * scale, panelH = h * scale;
    // The inset fills the panel's width, or its height if the region is tall.
    const int zoom = std::max(1, std::min(panelW / r.w, panelH / r.h));
    const int insetH = r.h * zoom;
    const int sheetW = kGap + static_cast<int>(panels.size()) * (panelW + kGap);
    const int sheetH = kLabelHeight + panelH + kGap + insetH + kGap;
    Image sheet(sheetW, sheetH);
    fillRect(sheet, {0, 0, sheetW, sheetH}, fromSrgb(32, 32, 32));
    const Rgb outline = fromSrgb(255, 200, 0), textColor{1, 1, 1};
    for (size_t i = 0; i < panels.size(); ++i) {
        const Panel& p = panels[i];
        const int x = kGap + static_cast<int>(i) * (panelW + kGap);
        drawText(sheet, x, 19, p.title, {15, textColor, true});
        drawText(sheet, x, 37, p.detail, {13, fromSrgb(210, 210, 210)});
        paste(sheet, p.image, x, kLabelHeight, scale);
        strokeRect(sheet, {x + r.x * scale - 1, kLabelHeight + r.y * scale - 1, r.w * scale + 2, r.h * scale + 2},
                   outline);
        const int insetY = kLabelHeight + panelH + kGap;
        paste(sheet, magnify(crop(p.image, r.x, r.y, r.w, r.h), zoom), x, insetY);
        strokeRect(sheet, {x - 1, insetY - 1, r.w * zoom + 2, insetH + 2}, outline);
    }
    return sheet;
}

Image stackRows(const std::vector<Image>& rows) {
    int width = 0, height = 0;
    for (const Image& r : rows) width = std::max(width, r.width), height += r.height;
    Image sheet(width, height);
    fillRect(sheet, {0, 0, width, height}, fromSrgb(32, 32, 32));
    int y = 0;
    for (const Image& r : rows) {
        paste(sheet, r, 0, y);
        y += r.height;
    }
    return sheet;
}

}  // namespace tripath
