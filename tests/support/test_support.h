// Lucerna test support: paths into the source tree (data/ holds the shared scenes and
// references), per-test temporary folders, and running the built binaries and scripts.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "support/chi2.h"

namespace lu::test {

// Runs `lucerna info FILE` with the built binary; returns its exit status (-1 when it did not
// exit normally) and appends its combined stdout and stderr to *out.
inline int RunLucernaInfo(const std::string &file, std::string *out) {
    std::string cmd = std::string(LUCERNA_BINARY_DIR) + "/lucerna info '" + file + "' 2>&1";
    FILE *p = popen(cmd.c_str(), "r");
    if (!p) return -1;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out->append(buf, n);
    int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Path of a file under data/ in the source tree: the shared scenes and references
// ("scenes/bitterli-cornell-box/scene-v4.pbrt", "refs/cornell-box.exr"; see data/README.md).
std::string SharedPath(const std::string &rel);
// Path of a file in the source tree.
std::string SourcePath(const std::string &rel);
// A fresh temporary directory for one test.
std::string TempDir(const std::string &name);

// The lucerna binary of this build.
std::string LucernaBinary();
// The Python interpreter with matplotlib and numpy that CMake found on PATH (LUCERNA_PYTHON).
std::string PythonExe();

struct ProcessResult {
    int exitCode = -1;   // the exit status, 128 + signal if killed, 127 if it could not be started
    std::string output;  // stdout and stderr together
};
// Runs argv[0] (looked up on PATH when it has no '/') with the arguments, no shell, the extra
// environment variables set; waits for it.
ProcessResult RunProcess(const std::vector<std::string> &argv,
                         const std::vector<std::pair<std::string, std::string>> &env = {});

}  // namespace lu::test
