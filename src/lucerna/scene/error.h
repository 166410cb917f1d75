// Lucerna scene reader: source locations and compiler-style diagnostics (host only).
// Errors print "FILE:LINE:COL: error: MESSAGE" plus the source line and a caret; `lucerna`
// turns a SceneError into exit code 2.
#pragma once

#include <memory>
#include <stdexcept>
#include <cstdio>
#include <string>
#include <vector>

namespace lu {

// A number as printf's %g writes it, for messages.
inline std::string FormatNumber(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

// A position in a scene file; line and col are 1-based (0: unknown).
struct FileLoc {
    std::shared_ptr<const std::string> file;  // shared by all tokens of one file
    int line = 0, col = 0;
    // The Include/Import directive that opened `file` (itself with its own), null for the main file.
    std::shared_ptr<const FileLoc> includedFrom;
    std::string Filename() const { return file ? *file : std::string("<unknown>"); }
    std::string ToString() const;  // "file:line:col"
    // "In file included from a.pbrt:3:1,\n                 from main.pbrt:12:1:\n" as gcc prints
    // it, innermost first; "" for a location in the main file.
    std::string IncludeChain() const;
};

// Bad input: thrown by the reader and the scene builder, caught by the CLI (exit 2).
class SceneError : public std::runtime_error {
  public:
    SceneError(FileLoc loc, std::string message);
    const FileLoc &Loc() const { return loc_; }
    const std::string &Message() const { return message_; }
    // The full diagnostic: the include chain, "file:line:col: error: message\n<source line>\n<caret>".
    std::string Format() const;
    // The offending source line, when the reader has it in memory (in-memory scenes); when
    // empty, Format() reads the line from loc's file. (Additive; set by the parser.)
    void SetSourceLine(std::string line) { sourceLine_ = std::move(line); }
    const std::string &SourceLine() const { return sourceLine_; }
    // Further errors reported together with this one (the scene builder collects every
    // unsupported feature before it gives up); Format() prints them after this one, in order.
    void AddFollowing(const SceneError &e) { following_.push_back(e); }
    const std::vector<SceneError> &Following() const { return following_; }

  private:
    std::string FormatOne() const;
    FileLoc loc_;
    std::string message_;
    std::string sourceLine_;
    std::vector<SceneError> following_;
};

// Warnings go to stderr as "file:line:col: warning: message" (after the include chain, if any) and
// are also collected so that `lucerna info` and tests can list them.
struct Diagnostics {
    std::vector<std::string> warnings;     // formatted lines
    std::vector<std::string> unsupported;  // names of unsupported features seen (e.g. "Integrator \"sppm\"")
    bool quiet = false;                    // do not print (tests)
    void Warning(const FileLoc &loc, const std::string &message);
    void Unsupported(const FileLoc &loc, const std::string &feature, const std::string &what);
};

}  // namespace lu
