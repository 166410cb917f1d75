// Lucerna test support: source-tree paths, temporary folders, processes (support/test_support.h).
#include "support/test_support.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

namespace lu::test {

std::string SharedPath(const std::string &rel) { return SourcePath("data/" + rel); }
std::string SourcePath(const std::string &rel) { return std::string(LUCERNA_SOURCE_DIR) + "/" + rel; }
std::string TempDir(const std::string &name) {
    // ctest runs each test in its own process, several at once: the pid keeps their folders apart.
    auto p = std::filesystem::temp_directory_path() / ("lucerna_test_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p.string();
}

std::string LucernaBinary() { return std::string(LUCERNA_BINARY_DIR) + "/lucerna"; }
std::string PythonExe() { return LUCERNA_PYTHON; }

ProcessResult RunProcess(const std::vector<std::string> &argv, const std::vector<std::pair<std::string, std::string>> &env) {
    ProcessResult r;
    if (argv.empty()) return r;
    int fds[2];
    if (pipe(fds) != 0) return r;
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return r;
    }
    if (pid == 0) {
        dup2(fds[1], STDOUT_FILENO);
        dup2(fds[1], STDERR_FILENO);
        close(fds[0]);
        close(fds[1]);
        for (const auto &[k, v] : env) setenv(k.c_str(), v.c_str(), 1);
        std::vector<char *> args;
        for (const std::string &a : argv) args.push_back(const_cast<char *>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        _exit(127);
    }
    close(fds[1]);
    char buf[4096];
    ssize_t n;
    while ((n = read(fds[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
        if (n > 0) r.output.append(buf, size_t(n));
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

}  // namespace lu::test
