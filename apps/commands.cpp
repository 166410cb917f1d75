// Lucerna CLI: the list of subcommands. Every apps/cmd_*.cpp is linked: a missing one is a link
// error, not a silently absent command (tests/cli checks that --help lists each of them).
#include "apps/commands.h"

namespace lu::app {

void RegisterCommands(CLI::App &app, CommandTable &table) {
    RegisterInfo(app, table);
    RegisterRender(app, table);
    RegisterDiff(app, table);
    RegisterConverge(app, table);
}

}  // namespace lu::app
