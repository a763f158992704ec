// `tripath montage`: a labelled grid of EXR renders in one figure, PNG, PDF or SVG (the contact
// sheet of docs/failures.md). Each row is scaled by one factor, so the methods in a row stay comparable
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
#include "evaluation/sheet.h"
#include "image/draw.h"
#include "image/exposure.h"
#include "image/font.h"
#include "image/image.h"
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
    std::string theme = "dark";
};

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
    const std::string ext = std::filesystem::path(c.out).extension().string();
    if (ext != ".png" && ext != ".pdf" && ext != ".svg") throw InputError("--out must name a .png, .pdf or .svg file: " + c.out);
    const Theme& theme = themeNamed(c.theme);
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
    for (Image& img : images) img = shrink(img, c.shrink);
    const int w = images.front().width, h = images.front().height;

    const int rows = (static_cast<int>(images.size()) + c.columns - 1) / c.columns;
    constexpr Font kRowLabel{13}, kColumnLabel{13, true};
    int labelW = 0;
    for (const std::string& l : rowLabels) labelW = std::max(labelW, int(std::ceil(canvas::textWidth(l, kRowLabel))) + 8);
    const int gap = 2, top = columnLabels.empty() ? 0 : 20;
    const int cellW = w * c.scale, cellH = h * c.scale;
    Sheet sheet(labelW + c.columns * (cellW + gap), top + rows * (cellH + gap), theme.background);
    for (size_t j = 0; j < columnLabels.size() && j < static_cast<size_t>(c.columns); ++j)
        sheet.label(labelW + static_cast<int>(j) * (cellW + gap) + cellW / 2, 15, columnLabels[j], kColumnLabel,
                    theme.title, Anchor::Middle);
    for (int r = 0; r < rows; ++r) {
        const int y = top + r * (cellH + gap);
        if (r < static_cast<int>(rowLabels.size())) sheet.label(4, y + cellH / 2 + 5, rowLabels[r], kRowLabel, theme.title);
        const size_t first = static_cast<size_t>(r * c.columns);
        const float k = rowScale(images, c.inputs, first, std::min(images.size(), first + size_t(c.columns)),
                                 c.percentile);
        for (int col = 0; col < c.columns; ++col) {
            const size_t i = static_cast<size_t>(r * c.columns + col);
            if (i >= images.size()) break;
            Image scaled = images[i];
            for (float& v : scaled.rgb) v = std::isfinite(v) ? v * k : 0.0f;
            sheet.picture(scaled, labelW + col * (cellW + gap), y, c.scale);
        }
    }
    writeSheet(c.out, sheet);
    std::cerr << "wrote " << c.out << "\n";
}

}  // namespace

void addMontageCommand(CLI::App& app) {
    auto c = std::make_shared<MontageCommand>();
    auto* cmd = app.add_subcommand("montage", "Lay EXR images out in a labelled grid, written as one PNG, PDF or SVG");
    cmd->add_option("images", c->inputs, "EXR files, row by row")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", c->out,
                    "The figure: .png, or .pdf or .svg (labels stay text, images stay pixels)")
        ->required();
    cmd->add_option("--columns", c->columns, "Images per row")->capture_default_str();
    cmd->add_option("--scale", c->scale, "Magnify each image by this whole factor (nearest neighbour)")
        ->capture_default_str();
    cmd->add_option("--shrink", c->shrink, "Shrink each image by this whole factor first (box filter)")
        ->capture_default_str();
    cmd->add_option("--column-labels", c->columnLabels, "Comma-separated labels above the columns");
    cmd->add_option("--row-labels", c->rowLabels, "Comma-separated labels left of the rows");
    cmd->add_option("--theme", c->theme, "Colours: dark (for screens) or light (for a paper's page)")->capture_default_str();
    cmd->add_option("--percentile", c->percentile,
                    "Each row is scaled by one factor: the smallest of those that map this luminance percentile "
                    "(of the pixels above 0) of each of its images to white, so that no image is blown out; black "
                    "images are warned about and do not count")
        ->capture_default_str();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
