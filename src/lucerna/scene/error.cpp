// Lucerna scene reader: FileLoc, SceneError and Diagnostics (compiler-style messages with the
// source line and a caret, as Tungsten and clang print them).
#include "lucerna/scene/error.h"

#include <algorithm>
#include <cstdio>

#include <zlib.h>

namespace lu {

std::string FileLoc::ToString() const {
    std::string s = Filename();
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (col > 0) s += ':' + std::to_string(col);
    }
    return s;
}

std::string FileLoc::IncludeChain() const {
    std::string s;
    for (const FileLoc *from = includedFrom.get(); from; from = from->includedFrom.get()) {
        s += s.empty() ? "In file included from " : "                 from ";
        s += from->ToString() + (from->includedFrom ? ",\n" : ":\n");
    }
    return s;
}

static std::string LocPrefix(const FileLoc &loc) {
    if (!loc.file && loc.line == 0) return "";
    return loc.ToString() + ": ";
}

SceneError::SceneError(FileLoc loc, std::string message)
    : std::runtime_error(LocPrefix(loc) + "error: " + message), loc_(std::move(loc)),
      message_(std::move(message)) {}

// Reads line `line` (1-based) of `path`, reading at most a bounded number of bytes; gzip files are
// decompressed (zlib's gzread passes other files through unchanged).
static bool ReadSourceLine(const std::string &path, int line, std::string *out) {
    gzFile in = gzopen(path.c_str(), "rb");
    if (!in) return false;
    constexpr size_t maxBytes = size_t(1) << 30;
    size_t read = 0;
    int current = 1;
    std::string s;
    char buf[1 << 14];
    bool found = false;
    while (!found && read < maxBytes) {
        int n = gzread(in, buf, sizeof(buf));
        if (n <= 0) break;
        read += size_t(n);
        for (int i = 0; i < n && !found; ++i) {
            char c = buf[i];
            if (c == '\n') {
                if (current == line) found = true;
                else ++current;
                continue;
            }
            if (current == line && s.size() < 4096) s.push_back(c);
        }
    }
    gzclose(in);
    if (found || current == line) {
        *out = s;
        return true;
    }
    return false;
}

// Printable version of a source line and the caret line under column col (1-based): control
// bytes become '?', tabs are kept so that the caret lines up, and very long lines are cut to a
// window around the column.
static void SourceAndCaret(std::string line, int col, std::string *src, std::string *caret) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    int c = std::max(col, 1) - 1;
    constexpr int window = 160;
    std::string prefix;
    if ((int)line.size() > window) {
        int start = std::max(0, std::min(c - window / 2, (int)line.size() - window));
        line = line.substr(start, window);
        c -= start;
        if (start > 0) { prefix = "..."; }
    }
    for (char &ch : line)
        if ((unsigned char)ch < 0x20 && ch != '\t') ch = '?';
        else if ((unsigned char)ch == 0x7f) ch = '?';
    *src = prefix + line;
    std::string car(prefix.size(), ' ');
    for (int i = 0; i < c && i < (int)line.size(); ++i) car.push_back(line[i] == '\t' ? '\t' : ' ');
    car.push_back('^');
    *caret = car;
}

std::string SceneError::Format() const {
    std::string s = loc_.IncludeChain() + LocPrefix(loc_) + "error: " + message_;
    if (loc_.line <= 0) return s;
    std::string line = sourceLine_;
    if (line.empty() && loc_.file && !ReadSourceLine(*loc_.file, loc_.line, &line)) return s;
    if (line.empty()) return s;
    std::string src, caret;
    SourceAndCaret(line, loc_.col, &src, &caret);
    return s + "\n" + src + "\n" + caret;
}

void Diagnostics::Warning(const FileLoc &loc, const std::string &message) {
    std::string s = loc.IncludeChain() + LocPrefix(loc) + "warning: " + message;
    if (!quiet) std::fprintf(stderr, "%s\n", s.c_str());
    warnings.push_back(std::move(s));
}

void Diagnostics::Unsupported(const FileLoc &loc, const std::string &feature, const std::string &what) {
    if (std::find(unsupported.begin(), unsupported.end(), feature) == unsupported.end())
        unsupported.push_back(feature);
    Warning(loc, feature + " is not supported" + (what.empty() ? std::string() : ": " + what));
}

}  // namespace lu
