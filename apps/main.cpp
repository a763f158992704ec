// tripath: light transport on one three-point path core. See `tripath --help`.
#include <fmt/format.h>

#include <iostream>

#include "commands.h"
#include "processes.h"
#include "core/error.h"
#include "integrators/interrupt.h"

namespace {

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
                 "merging (vcm, bpm, ppm) with MIS on one three-point (area-measure) path core."};
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
