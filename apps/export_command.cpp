// `tripath export`: a scene (built-in or file) as a glTF 2.0 file with an embedded buffer, which
// loads back to the same triangles, materials, lights and camera (see io/gltf_writer.h).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "commands.h"
#include "core/error.h"
#include "io/gltf_loader.h"
#include "io/gltf_writer.h"
#include "scenes/scene_source.h"
#include "image/image.h"
#include "render_options.h"

namespace tripath::app {

namespace {

struct ExportCommand {
    std::string scene, out;
    GltfOptions gltf;
};

void run(const ExportCommand& c) {
    if (std::filesystem::path(c.out).extension() != ".gltf") throw InputError("--out must name a .gltf file: " + c.out);
    checkWritable(c.out);
    const SceneDesc desc = loadSceneDesc(c.scene, c.gltf);
    writeGltf(desc, c.out, printWarning);
    std::cerr << "wrote " << c.out << "\n";
}

}  // namespace

void addExportCommand(CLI::App& app) {
    auto c = std::make_shared<ExportCommand>();
    auto* cmd = app.add_subcommand("export", "Write a scene (built-in or file) as glTF 2.0 with an embedded buffer");
    addSceneOptions(*cmd, c->scene, c->gltf);
    cmd->add_option("--out", c->out, "Output .gltf file (JSON, buffer embedded as base64)")->required();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
