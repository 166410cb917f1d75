// Lucerna command-line entry point: one CLI11 app, one subcommand per apps/cmd_*.cpp file.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "apps/commands.h"

int main(int argc, char **argv) {
    CLI::App app{"Lucerna: spectral path tracing with selective path regularization"};
    app.require_subcommand(1);
    lu::app::CommandTable table;
    lu::app::RegisterCommands(app, table);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    try {
        return table.Run(app);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "lucerna: internal error: %s\n", e.what());
        return 1;
    }
}
