// Rectangles, magnified and shrunk copies (draw.h): a few loops over the pixels, clipped to the image.
#include "image/draw.h"

#include <algorithm>

namespace tripath {

Rgb fromSrgb(uint8_t r, uint8_t g, uint8_t b) {
    return {srgbDecode(r / 255.0f), srgbDecode(g / 255.0f), srgbDecode(b / 255.0f)};
}

void fillRect(Image& img, Region r, Rgb c) {
    for (int y = std::max(0, r.y); y < std::min(img.height, r.y + r.h); ++y)
        for (int x = std::max(0, r.x); x < std::min(img.width, r.x + r.w); ++x) {
            float* p = img.at(x, y);
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
}

void strokeRect(Image& img, Region r, Rgb c, int t) {
    fillRect(img, {r.x, r.y, r.w, t}, c);
    fillRect(img, {r.x, r.y + r.h - t, r.w, t}, c);
    fillRect(img, {r.x, r.y + t, t, r.h - 2 * t}, c);
    fillRect(img, {r.x + r.w - t, r.y + t, t, r.h - 2 * t}, c);
}

void paste(Image& dst, const Image& src, int x, int y, int scale) {
    for (int sy = 0; sy < src.height * scale; ++sy)
        for (int sx = 0; sx < src.width * scale; ++sx) {
            const int dx = x + sx, dy = y + sy;
            if (dx < 0 || dy < 0 || dx >= dst.width || dy >= dst.height) continue;
            const float* s = src.at(sx / scale, sy / scale);
            std::copy(s, s + 3, dst.at(dx, dy));
        }
}

Image magnified(const Image& img, int scale) {
    Image out(img.width * scale, img.height * scale);
    paste(out, img, 0, 0, scale);
    return out;
}

Image shrink(const Image& img, int factor) {
    if (factor == 1) return img;
    Image out(img.width / factor, img.height / factor);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int j = 0; j < factor; ++j)
                    for (int i = 0; i < factor; ++i) sum += img.at(x * factor + i, y * factor + j)[c];
                out.at(x, y)[c] = static_cast<float>(sum / (factor * factor));
            }
    return out;
}

}  // namespace tripath
