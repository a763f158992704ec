#include "evaluation/compose.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "evaluation/metrics.h"
#include "image/draw.h"

namespace tripath {

namespace {

constexpr int kGap = 8, kLabelHeight = 44;
constexpr Font kTitle{15, true}, kDetail{13};

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

Sheet sideBySide(const std::vector<Panel>& panels, const Region& r, const SheetStyle& style, int minWidth) {
    checkPanels(panels, r);
    const Theme& t = style.theme;
    const int w = panels.front().image.width, h = panels.front().image.height;
    const int scale = std::max(1, (minWidth + w - 1) / w);
    const int panelW = w * scale, panelH = h * scale;
    const int zoom = std::max(1, std::min(panelW / r.w, panelH / r.h));
    const int insetH = r.h * zoom;
    const int top = style.labels ? kLabelHeight : kGap;
    const int sheetW = kGap + static_cast<int>(panels.size()) * (panelW + kGap);
    Sheet sheet(sheetW, top + panelH + kGap + insetH + kGap, t.background);
    for (size_t i = 0; i < panels.size(); ++i) {
        const Panel& p = panels[i];
        const int x = kGap + static_cast<int>(i) * (panelW + kGap);
        if (style.labels) {
            sheet.label(x, 19, p.title, kTitle, t.title);
            sheet.label(x, 37, p.detail, kDetail, t.detail);
        }
        sheet.picture(p.image, x, top, scale);
        sheet.frame({x + r.x * scale - 1, top + r.y * scale - 1, r.w * scale + 2, r.h * scale + 2}, t.outline);
        const int insetY = top + panelH + kGap;
        sheet.picture(crop(p.image, r.x, r.y, r.w, r.h), x, insetY, zoom);
        sheet.frame({x - 1, insetY - 1, r.w * zoom + 2, insetH + 2}, t.outline);
    }
    return sheet;
}

Image magnifiedCrop(const Image& image, const Region& r, int size) {
    return magnified(crop(image, r.x, r.y, r.w, r.h), std::max(1, size / std::max(r.w, r.h)));
}

}  // namespace tripath
