// The subcommands of the `tripath` command line, each in its own file.
#pragma once
#include <CLI/CLI.hpp>

namespace tripath::app {

void addRenderCommand(CLI::App& app);
void addScenesCommand(CLI::App& app);
void addReferenceCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addMontageCommand(CLI::App& app);
void addBenchmarkCommand(CLI::App& app);

}  // namespace tripath::app
