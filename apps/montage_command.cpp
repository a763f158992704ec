// `tripath montage`: a labelled grid of EXR renders in one PNG (the contact sheet of
// docs/failures.md). Each row is scaled by one factor, so the methods in a row stay comparable
// while rows of very different brightness (a caustic, a dim room) are each readable.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "core/error.h"
#include "image/draw.h"
#include "image/image.h"
#include "image/text.h"
#include "render_options.h"

namespace tripath::app {

namespace {

struct MontageCommand {
    std::vector<std::string> inputs;
    std::string out;
    int columns = 4;
    int scale = 1;
    int shrink = 1;
    std::string columnLabels, rowLabels;
    float percentile = 0.98f;
};

// Averages each shrink × shrink block into one pixel (a box filter), for a sheet small enough to
// keep in the repository.
Image shrinkImage(const Image& img, int shrink) {
    if (shrink == 1) return img;
    Image out(img.width / shrink, img.height / shrink);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int j = 0; j < shrink; ++j)
                    for (int i = 0; i < shrink; ++i) sum += img.at(x * shrink + i, y * shrink + j)[c];
                out.at(x, y)[c] = static_cast<float>(sum / (shrink * shrink));
            }
    return out;
}

// The factor that maps the given luminance percentile of `img` to 1 (white after sRGB); 1 for a
// black image.
float rowScale(const Image& img, float percentile) {
    std::vector<float> lum;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        const float* p = img.rgb.data() + 3 * i;
        const float l = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        if (std::isfinite(l)) lum.push_back(l);
    }
    if (lum.empty()) return 1.0f;
    const size_t k = std::min(lum.size() - 1, static_cast<size_t>(percentile * lum.size()));
    std::nth_element(lum.begin(), lum.begin() + static_cast<long>(k), lum.end());
    return lum[k] > 0 ? 1.0f / lum[k] : 1.0f;
}

void run(const MontageCommand& c) {
    if (std::filesystem::path(c.out).extension() != ".png") throw InputError("--out must name a .png file: " + c.out);
    if (c.columns < 1 || c.columns > 64) throw InputError(fmt::format("--columns must be between 1 and 64 (got {})", c.columns));
    if (c.scale < 1 || c.scale > 16) throw InputError(fmt::format("--scale must be between 1 and 16 (got {})", c.scale));
    if (c.shrink < 1 || c.shrink > 16) throw InputError(fmt::format("--shrink must be between 1 and 16 (got {})", c.shrink));
    if (!(c.percentile > 0 && c.percentile <= 1)) throw InputError("--percentile must be in (0, 1]");
    const auto columnLabels = splitCommas(c.columnLabels), rowLabels = splitCommas(c.rowLabels);
    const bool labels = !columnLabels.empty() || !rowLabels.empty();
    if (labels) requireFont();
    checkWritable(c.out);

    std::vector<Image> images;
    for (const std::string& path : c.inputs) images.push_back(readExr(path));
    if (images.front().width < c.shrink || images.front().height < c.shrink)
        throw InputError(fmt::format("--shrink {} leaves nothing of a {}x{} image", c.shrink, images.front().width,
                                     images.front().height));
    for (size_t i = 0; i < images.size(); ++i)
        if (images[i].width != images.front().width || images[i].height != images.front().height)
            throw InputError(fmt::format("{}: {}x{}, but the first image is {}x{}", c.inputs[i], images[i].width,
                                         images[i].height, images.front().width, images.front().height));
    for (Image& img : images) img = shrinkImage(img, c.shrink);
    const int w = images.front().width, h = images.front().height;

    const int rows = (static_cast<int>(images.size()) + c.columns - 1) / c.columns;
    const TextStyle style{13, {1, 1, 1}, false, Align::Left};
    int labelW = 0;
    for (const std::string& l : rowLabels) labelW = std::max(labelW, textWidth(l, style) + 8);
    const int gap = 2, top = columnLabels.empty() ? 0 : 20;
    const int cellW = w * c.scale, cellH = h * c.scale;
    Image sheet(labelW + c.columns * (cellW + gap), top + rows * (cellH + gap));
    fillRect(sheet, {0, 0, sheet.width, sheet.height}, fromSrgb(32, 32, 32));
    for (size_t j = 0; j < columnLabels.size() && j < static_cast<size_t>(c.columns); ++j)
        drawText(sheet, labelW + static_cast<int>(j) * (cellW + gap) + cellW / 2, 15, columnLabels[j],
                 {13, {1, 1, 1}, true, Align::Center});
    for (int r = 0; r < rows; ++r) {
        const int y = top + r * (cellH + gap);
        if (r < static_cast<int>(rowLabels.size())) drawText(sheet, 4, y + cellH / 2 + 5, rowLabels[r], style);
        const float k = rowScale(images[static_cast<size_t>(r * c.columns)], c.percentile);
        for (int col = 0; col < c.columns; ++col) {
            const size_t i = static_cast<size_t>(r * c.columns + col);
            if (i >= images.size()) break;
            Image scaled = images[i];
            for (float& v : scaled.rgb) v = std::isfinite(v) ? v * k : 0.0f;
            paste(sheet, scaled, labelW + col * (cellW + gap), y, c.scale);
        }
    }
    writePng(c.out, sheet, 0.0f);
    std::cerr << "wrote " << c.out << "\n";
}

}  // namespace

void addMontageCommand(CLI::App& app) {
    auto c = std::make_shared<MontageCommand>();
    auto* cmd = app.add_subcommand("montage", "Lay EXR images out in a labelled grid, written as one PNG");
    cmd->add_option("images", c->inputs, "EXR files, row by row")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", c->out, "Output PNG")->required();
    cmd->add_option("--columns", c->columns, "Images per row")->capture_default_str();
    cmd->add_option("--scale", c->scale, "Magnify each image by this whole factor (nearest neighbour)")
        ->capture_default_str();
    cmd->add_option("--shrink", c->shrink, "Shrink each image by this whole factor first (box filter)")
        ->capture_default_str();
    cmd->add_option("--column-labels", c->columnLabels, "Comma-separated labels above the columns");
    cmd->add_option("--row-labels", c->rowLabels, "Comma-separated labels left of the rows");
    cmd->add_option("--percentile", c->percentile,
                    "Each row is scaled so that this luminance percentile of its first image is white")
        ->capture_default_str();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
