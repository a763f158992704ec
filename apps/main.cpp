// tripath: light transport on one three-point path core. See `tripath --help`.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "input_words.h"
#include "processes.h"
#include "core/error.h"
#include "requests/interrupt.h"

namespace {

// The first argument must name a command (unless it is a flag: --help, --version, or one CLI11
// refuses): otherwise one line naming the commands, and the nearest one to a typo.
void requireCommand(const CLI::App& app, int argc, char** argv) {
    if (argc > 1 && argv[1][0] == '-') return;
    std::vector<std::string> names;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
        names.push_back(command->get_name());
    const std::string list = fmt::format("{}", fmt::join(names, ", "));
    if (argc < 2) throw tripath::InputError("a command is required: " + list + " (`tripath --help` says what each does)");
    if (std::find(names.begin(), names.end(), argv[1]) != names.end()) return;
    const auto nearest = tripath::app::nearestName(argv[1], names);
    throw tripath::InputError(fmt::format("unknown command '{}'{}; the commands are {}", tripath::clipped(argv[1]),
                                          nearest ? " (did you mean '" + *nearest + "'?)" : "", list));
}

// A command that SIGINT or SIGTERM cut short ends with 128 + the signal's number, as a shell reports
// a process the signal ended, even when it wrote what it had: a batch job killed at its time limit
// must not pass for finished.
int exitCode(int code) {
    const int signal = tripath::interruptSignal();
    return signal ? 128 + signal : code;
}

}  // namespace

int main(int argc, char** argv) {
    tripath::app::Processes processes(argc, argv);  // under mpirun: one of N ranks (processes.h)
    CLI::App app{"tripath " TRIPATH_VERSION " — path tracing, light tracing, bidirectional path tracing and vertex "
                 "merging (vcm, bpm, ppm) with MIS, and Metropolis light transport (mlt) over the same paths, on one "
                 "three-point (area-measure) path core.",
                 "tripath"};  // named, so that --help reads the same however the binary was called
    app.set_version_flag("--version", "tripath " TRIPATH_VERSION);
    app.require_subcommand(1);
    tripath::app::addRenderCommand(app);
    tripath::app::addScenesCommand(app);
    tripath::app::addReferenceCommand(app);
    tripath::app::addCompareCommand(app);
    tripath::app::addBenchmarkCommand(app);
    tripath::app::addExportCommand(app);
    tripath::app::addMontageCommand(app);
    try {
        requireCommand(app, argc, argv);
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::cerr << "error: " << tripath::oneLine(e.what()) << "\n";  // one line, like every other error
        return 1;
    } catch (const tripath::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return exitCode(1);
    } catch (const std::exception& e) {
        processes.fail(tripath::oneLine(e.what()), 2);  // a rank's own failure ends the job (others may wait for it)
        std::cerr << "error: " << tripath::oneLine(e.what()) << "\n";
        return 2;
    }
    return exitCode(0);
}
