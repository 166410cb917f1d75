// Lucerna CLI: checks of the output paths (apps/output_paths.h).
#include "apps/output_paths.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace lu::app {

namespace fs = std::filesystem;

namespace {

std::string Lower(std::string s) {
    for (char &c : s) c = char(std::tolower((unsigned char)c));
    return s;
}

std::string Mode(unsigned mode) {
    char b[16];
    std::snprintf(b, sizeof b, "%04o", mode & 07777);
    return b;
}

bool InGroup(gid_t gid) {
    if (getegid() == gid) return true;
    gid_t groups[256];
    int n = getgroups(256, groups);
    for (int i = 0; i < n; ++i)
        if (groups[i] == gid) return true;
    return false;
}

// "" when `dir` (an existing path) can hold a new file; else why not.
std::string CheckFolder(const fs::path &dir) {
    struct stat st;
    if (::stat(dir.c_str(), &st) != 0) return dir.string() + ": " + std::strerror(errno);
    if (!S_ISDIR(st.st_mode)) return dir.string() + " is not a folder";
    if (::access(dir.c_str(), W_OK | X_OK) != 0) return "the folder " + dir.string() + " is not writable";
    return "";
}

std::string CheckOne(const NamedPath &o) {
    const std::string where = o.role + " " + (o.path.empty() ? "\"\"" : o.path);
    if (o.path.empty()) return where + ": empty path";
    fs::path p(o.path);
    struct stat st;
    bool exists = ::stat(o.path.c_str(), &st) == 0;
    if (!exists && errno != ENOENT && errno != ENOTDIR) return where + ": " + std::strerror(errno);
    if (exists && S_ISDIR(st.st_mode)) return where + " is a folder";
    if (o.image) {
        std::string ext = Lower(p.extension().string());
        if (ext != ".exr" && ext != ".png")
            return where + ": unknown image format '" + ext + "' (use .exr, or .png for an sRGB preview)";
    }
    if (exists) {
        if (!S_ISREG(st.st_mode)) return where + " is not a regular file";
        if (!ModeAllowsWrite(st.st_mode, st.st_uid, st.st_gid))
            return where + " is read-only (mode " + Mode(st.st_mode) + "); make it writable or choose another path";
        std::string why = CheckFolder(p.has_parent_path() ? p.parent_path() : fs::path("."));
        return why.empty() ? "" : where + ": " + why;
    }
    if (!o.path.empty() && o.path.back() == '/') return where + " names a folder";
    // A new file: the nearest existing ancestor must be a writable folder.
    fs::path dir = fs::absolute(p).parent_path();
    while (!dir.empty()) {
        std::error_code ec;
        if (fs::exists(dir, ec) || dir == dir.root_path()) break;
        dir = dir.parent_path();
    }
    std::string why = CheckFolder(dir);
    return why.empty() ? "" : where + ": " + why;
}

}  // namespace

bool ModeAllowsWrite(unsigned mode, unsigned owner, unsigned group) {
    if (geteuid() == owner) return (mode & S_IWUSR) != 0;
    if (InGroup(gid_t(group))) return (mode & S_IWGRP) != 0;
    return (mode & S_IWOTH) != 0;
}

bool SameFile(const std::string &a, const std::string &b) {
    std::error_code ea, eb;
    if (fs::exists(a, ea) && fs::exists(b, eb)) {
        std::error_code ec;
        bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    fs::path ca = fs::weakly_canonical(fs::absolute(a), ea), cb = fs::weakly_canonical(fs::absolute(b), eb);
    if (ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
    return ca == cb;
}

std::string CheckOutputs(const std::vector<NamedPath> &outputs) {
    for (const NamedPath &o : outputs)
        if (std::string why = CheckOne(o); !why.empty()) return why;
    return "";
}

std::string CheckDistinct(const std::vector<NamedPath> &outputs, const std::vector<NamedPath> &inputs,
                          const std::vector<std::pair<std::string, std::string>> &allowed) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        for (size_t j = 0; j < i; ++j)
            if (SameFile(outputs[i].path, outputs[j].path))
                return outputs[i].role + " " + outputs[i].path + " is the same file as " + outputs[j].role + " " +
                       outputs[j].path + "; give each output its own path";
        for (const NamedPath &in : inputs) {
            bool ok = false;
            for (const auto &[o, r] : allowed) ok |= o == outputs[i].role && r == in.role;
            if (!ok && SameFile(outputs[i].path, in.path))
                return outputs[i].role + " " + outputs[i].path + " would overwrite " + in.role + " " + in.path +
                       ", which the render reads; choose another path";
        }
    }
    return "";
}

std::string CreateOutputFolders(const std::vector<NamedPath> &outputs) {
    for (const NamedPath &o : outputs) {
        fs::path dir = fs::path(o.path).parent_path();
        if (dir.empty()) continue;
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) return o.role + " " + o.path + ": cannot make the folder " + dir.string() + ": " + ec.message();
    }
    return "";
}

}  // namespace lu::app
