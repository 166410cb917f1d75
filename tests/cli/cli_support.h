// Lucerna CLI tests: running the lucerna binary (waiting, or in the background with its output
// captured for signals), a small test scene, file comparisons.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lucerna/image/image.h"
#include "support/test_support.h"

namespace lu::test {

inline const std::string &Bin() {
    static const std::string bin = LucernaBinary();
    return bin;
}

// Runs the binary with arguments; returns its exit status (or 128 + signal). With wait = false it
// returns 0 at once and *pidOut is the child to signal and reap.
inline int RunLucerna(const std::vector<std::string> &args, bool quietStderr = true, pid_t *pidOut = nullptr,
                      bool wait = true) {
    pid_t pid = fork();
    if (pid == 0) {
        std::vector<char *> argv;
        argv.push_back(const_cast<char *>(Bin().c_str()));
        for (auto &a : args) argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        if (quietStderr) {
            if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
        }
        execv(Bin().c_str(), argv.data());
        _exit(127);
    }
    if (pidOut) *pidOut = pid;
    if (!wait) return 0;
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// `lucerna ARGS` in the background, stdout and stderr into one pipe (not a terminal).
struct Background {
    pid_t pid = -1;
    int fd = -1;
    std::string output_;

    explicit Background(const std::vector<std::string> &args) {
        int fds[2];
        if (pipe(fds) != 0) return;
        pid = fork();
        if (pid == 0) {
            dup2(fds[1], STDOUT_FILENO);
            dup2(fds[1], STDERR_FILENO);
            close(fds[0]);
            close(fds[1]);
            std::vector<char *> argv;
            argv.push_back(const_cast<char *>(Bin().c_str()));
            for (auto &a : args) argv.push_back(const_cast<char *>(a.c_str()));
            argv.push_back(nullptr);
            execv(Bin().c_str(), argv.data());
            _exit(127);
        }
        close(fds[1]);
        fd = fds[0];
    }
    // Reads output until it contains `text` (true) or the child closes it (false). The text is
    // kept for Finish.
    bool WaitFor(const std::string &text) {
        char buf[4096];
        while (output_.find(text) == std::string::npos) {
            ssize_t n = read(fd, buf, sizeof buf);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return false;
            output_.append(buf, size_t(n));
        }
        return true;
    }
    Background(const Background &) = delete;
    Background &operator=(const Background &) = delete;
    // Reads the output to its end and reaps the child: its exit status (128 + signal if killed).
    ProcessResult Finish() {
        ProcessResult r;
        r.output = std::move(output_);
        char buf[4096];
        ssize_t n;
        while ((n = read(fd, buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
            if (n > 0) r.output.append(buf, size_t(n));
        close(fd);
        fd = -1;
        int status = 0;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
        pid = -1;
        r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return r;
    }
    ~Background() {
        if (pid > 0) {
            kill(pid, SIGKILL);
            Finish();
        }
    }
};

// A glass sphere on a diffuse floor under an area light and an environment.
inline std::string WriteScene(const std::string &dir, int res = 48, int spp = 8, const std::string &name = "scene.pbrt") {
    std::string path = dir + "/" + name;
    std::ofstream(path) << "LookAt 0 1 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
                           "Film \"rgb\" \"integer xresolution\" [ " << res << " ] \"integer yresolution\" [ " << res
                        << " ]\nSampler \"zsobol\" \"integer pixelsamples\" [ " << spp << " ]\n"
                           "Integrator \"path\" \"integer maxdepth\" [ 8 ]\n"
                           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.4 0.5 0.6 ]\n"
                           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 8 8 8 ]\n"
                           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -0.3 2 -0.3  0.3 2 -0.3  0.3 2 0.3  -0.3 2 0.3 ]\n"
                           "AttributeEnd\n"
                           "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nShape \"sphere\" \"float radius\" [ 0.6 ]\nAttributeEnd\n"
                           "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
                           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 -0.6 -3  3 -0.6 -3  3 -0.6 3  -3 -0.6 3 ]\n";
    return path;
}

inline bool SameImage(const Image &a, const Image &b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

inline std::string FileBytes(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// Files in dir whose name contains ".tmp" (left-over temporary files of an atomic write).
inline std::vector<std::string> TempFiles(const std::string &dir) {
    std::vector<std::string> out;
    for (auto &e : std::filesystem::recursive_directory_iterator(dir))
        if (e.path().filename().string().find(".tmp") != std::string::npos) out.push_back(e.path().string());
    return out;
}

}  // namespace lu::test
