// Lucerna CLI: each subcommand lives in apps/cmd_NAME.cpp and registers itself here.
// Exit codes: 0 success, 1 internal failure, 2 bad input, 3 interrupted (image so far written).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace lu::app {

constexpr int ExitOk = 0, ExitInternal = 1, ExitBadInput = 2, ExitInterrupted = 3;

struct CommandTable {
    std::vector<std::pair<CLI::App *, std::function<int()>>> commands;
    void Add(CLI::App *sub, std::function<int()> run) { commands.emplace_back(sub, std::move(run)); }
    int Run(CLI::App &) {
        for (auto &[sub, run] : commands)
            if (sub->parsed()) return run();
        return ExitBadInput;
    }
};

// Each cmd_*.cpp defines one of these; RegisterCommands (commands.cpp) calls every one.
void RegisterInfo(CLI::App &app, CommandTable &table);      // apps/cmd_info.cpp
void RegisterRender(CLI::App &app, CommandTable &table);    // apps/cmd_render.cpp
void RegisterDiff(CLI::App &app, CommandTable &table);      // apps/cmd_diff.cpp
void RegisterConverge(CLI::App &app, CommandTable &table);  // apps/cmd_converge.cpp
void RegisterCommands(CLI::App &app, CommandTable &table);

}  // namespace lu::app
