// Lucerna CLI: the list of subcommands. Weak symbols let a subcommand file be absent while the
// others are developed; every shipped build links all of them.
#include "apps/commands.h"

namespace lu::app {

__attribute__((weak)) void RegisterInfo(CLI::App &, CommandTable &) {}
__attribute__((weak)) void RegisterRender(CLI::App &, CommandTable &) {}
__attribute__((weak)) void RegisterDiff(CLI::App &, CommandTable &) {}
__attribute__((weak)) void RegisterConverge(CLI::App &, CommandTable &) {}

void RegisterCommands(CLI::App &app, CommandTable &table) {
    RegisterInfo(app, table);
    RegisterRender(app, table);
    RegisterDiff(app, table);
    RegisterConverge(app, table);
}

}  // namespace lu::app
