// tripath: light transport on one three-point path core. See `tripath --help`.
#include <fmt/format.h>

#include <iostream>

#include "commands.h"
#include "geometry/error.h"

int main(int argc, char** argv) {
    CLI::App app{"tripath " TRIPATH_VERSION " — path tracing, light tracing and bidirectional path tracing with MIS "
                 "on one three-point (area-measure) path core."};
    app.set_version_flag("--version", "tripath " TRIPATH_VERSION);
    app.require_subcommand(1);
    tripath::app::addRenderCommand(app);
    tripath::app::addScenesCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const tripath::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
