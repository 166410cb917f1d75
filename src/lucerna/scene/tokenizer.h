// Lucerna scene reader: the pbrt-v4 tokenizer (host only). Follows pbrt-v4's Tokenizer (words,
// quoted strings with escapes, '[' and ']', '#' comments) with bounded tokens and errors for
// binary input instead of undefined behavior.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "lucerna/scene/error.h"

namespace lu {

// Limits that keep hostile input from allocating without bound.
constexpr size_t MaxSceneFileBytes = size_t(1) << 31;  // one scene text file
constexpr size_t MaxWordLength = 1024;                  // unquoted token (number, directive)
constexpr size_t MaxStringLength = 65536;               // quoted string, quotes excluded

struct Token {
    enum Kind { Word, String, OpenBracket, CloseBracket };
    Kind kind = Word;
    std::string_view raw;  // as in the file: a String includes its quotes; valid while the tokenizer lives
    int line = 0, col = 0;
    bool hasEscapes = false;
    const std::shared_ptr<const std::string> *file = nullptr;  // the tokenizer's file name
    const std::shared_ptr<const FileLoc> *includedFrom = nullptr;  // the tokenizer's

    FileLoc Loc() const {
        return FileLoc{file ? *file : nullptr, line, col, includedFrom ? *includedFrom : nullptr};
    }
    bool Is(std::string_view w) const { return kind == Word && raw == w; }
    bool IsString() const { return kind == String; }
    // The text of a String with its escapes decoded (they were validated by the tokenizer);
    // the raw text for other kinds.
    std::string Text() const;
};

// Reads a whole regular file (at most maxBytes) into *contents. Returns "" on success, else the
// reason ("No such file or directory", "not a regular file", "file too large", ...).
std::string ReadFileBytes(const std::string &path, std::string *contents, size_t maxBytes);

class Tokenizer {
  public:
    // The text is kept by the tokenizer; filename is what FileLocs report; includedFrom is the
    // Include/Import that opened the file (none for the main file), reported with every FileLoc.
    Tokenizer(std::string text, std::string filename, const FileLoc &includedFrom = FileLoc{});

    // Next token, skipping whitespace and comments; false at end of input. Throws SceneError on
    // an unterminated string, a bad escape, a control byte (binary input), an overlong token.
    bool Next(Token *tok);

    const std::shared_ptr<const std::string> &File() const { return file_; }
    // Line `line` (1-based) of the text, without its newline ("" if out of range).
    std::string SourceLine(int line) const;
    // Throws a SceneError at loc in this file with the source line attached.
    [[noreturn]] void Fail(int line, int col, const std::string &message) const;

  private:
    std::string text_;
    std::shared_ptr<const std::string> file_;
    std::shared_ptr<const FileLoc> includedFrom_;
    size_t pos_ = 0;
    int line_ = 1;
    size_t lineStart_ = 0;  // offset of the first byte of the current line
};

}  // namespace lu
