// `tripath montage`: a labelled grid of EXR renders in one PNG (the contact sheet of
// docs/failures.md). Each row is scaled by one factor, so the methods in a row stay comparable
// while rows of very different brightness (a caustic, a dim room) are each readable. The factor
// is the smallest of the row's images' own (each maps a luminance percentile of that image to
// white), so that no image is blown out by another's darkness: a method that renders a scene
// black (pt on sds-mirrors) neither sets its row's scale nor goes unnoticed (a warning names it).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "core/error.h"
#include "core/warnings.h"
#include "image/draw.h"
#include "image/exposure.h"
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
    float percentile = kAutoExposurePercentile;
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

// The factor of the row of images [first, end): the smallest of their own factors, each the one
// that maps the image's luminance percentile to 1 (white after sRGB). A black image has none and
// is warned about; a row of black images keeps factor 1.
float rowScale(const std::vector<Image>& images, const std::vector<std::string>& paths, size_t first, size_t end,
               float percentile) {
    float scale = 0;
    for (size_t i = first; i < end; ++i) {
        const float white = luminancePercentile(images[i], percentile);
        if (white > 0) {
            scale = scale > 0 ? std::min(scale, 1.0f / white) : 1.0f / white;
        } else {
            printWarning(paths[i] + ": the image is black (no pixel of finite luminance above 0); it does not set "
                         "its row's scale");
        }
    }
    return scale > 0 ? scale : 1.0f;
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
        const size_t first = static_cast<size_t>(r * c.columns);
        const float k = rowScale(images, c.inputs, first, std::min(images.size(), first + size_t(c.columns)),
                                 c.percentile);
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
                    "Each row is scaled by one factor: the smallest of those that map this luminance percentile "
                    "(of the pixels above 0) of each of its images to white, so that no image is blown out; black "
                    "images are warned about and do not count")
        ->capture_default_str();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
