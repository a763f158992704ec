// `tripath scenes`: the built-in scenes and what each is for.
#include <fmt/format.h>

#include "commands.h"
#include "scenes/builtin_scenes.h"

namespace tripath::app {

void addScenesCommand(CLI::App& app) {
    auto* cmd = app.add_subcommand("scenes", "List the built-in scenes (usable as --scene NAME)");
    cmd->callback([] {
        for (const BuiltinInfo& s : builtinScenes()) fmt::print("{:<16} {}\n", s.name, s.description);
    });
}

}  // namespace tripath::app
