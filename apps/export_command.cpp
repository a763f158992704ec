// `tripath export`: a scene (built-in or file) as a glTF 2.0 file (.glb, or .gltf with its buffer
// in a .bin beside it or, with --embed, inside it), which loads back to the same triangles,
// materials, lights and camera (see io/gltf_writer.h).
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
    bool embed = false;
    GltfOptions gltf;
};

void run(const ExportCommand& c) {
    checkGltfPath(c.out);
    const bool glb = std::filesystem::path(c.out).extension() == ".glb";
    if (c.embed && glb) throw InputError("--embed is for a .gltf (a .glb holds its buffer itself): " + c.out);
    checkWritable(c.out);
    const SceneDesc desc = loadSceneDesc(c.scene, c.gltf);
    const GltfBuffer buffer = c.embed ? GltfBuffer::Embedded : GltfBuffer::Beside;
    writeGltf(desc, c.out, printWarning, buffer);
    std::cerr << "wrote " << c.out << (glb || c.embed ? "" : " and " + binBeside(c.out)) << "\n";
}

}  // namespace

void addExportCommand(CLI::App& app) {
    auto c = std::make_shared<ExportCommand>();
    auto* cmd = app.add_subcommand("export", "Write a scene (built-in or file) as glTF 2.0 (.glb, or .gltf and .bin)");
    addSceneOptions(*cmd, c->scene, c->gltf);
    cmd->add_option("--out", c->out,
                    "Output file: .glb (binary glTF, one file) or .gltf (JSON, its buffer in a .bin of the same name "
                    "beside it)")
        ->required();
    cmd->add_flag("--embed", c->embed, "Keep a .gltf's buffer inside it as base64 (one self-contained file, a third "
                                       "larger), not in a .bin");
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
