// Lucerna scene reader: the pbrt-v4 tokenizer (after pbrt-v4's Tokenizer::Next in parser.cpp),
// with line/column tracking, bounded tokens and errors for binary input.
#include "lucerna/scene/tokenizer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>

namespace lu {

static char DecodeEscape(char c) {
    switch (c) {
    case 'b': return '\b';
    case 'f': return '\f';
    case 'n': return '\n';
    case 'r': return '\r';
    case 't': return '\t';
    case '\\': return '\\';
    case '\'': return '\'';
    case '"': return '"';
    default: return 0;
    }
}

std::string Token::Text() const {
    if (kind != String) return std::string(raw);
    std::string_view s = raw.substr(1, raw.size() >= 2 ? raw.size() - 2 : 0);
    if (!hasEscapes) return std::string(s);
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size()) out.push_back(DecodeEscape(s[++i]));
        else out.push_back(s[i]);
    }
    return out;
}

std::string ReadFileBytes(const std::string &path, std::string *contents, size_t maxBytes) {
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
    if (S_ISDIR(st.st_mode)) return "is a directory";
    if (!S_ISREG(st.st_mode)) return "not a regular file";
    if (st.st_size < 0 || uint64_t(st.st_size) > maxBytes)
        return "file too large (" + std::to_string((long long)st.st_size) + " bytes; the limit is " +
               std::to_string(maxBytes) + ")";
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) return std::strerror(errno);
    // Read exactly the size stat reported (files under /proc report 0 and read as empty).
    contents->assign(size_t(st.st_size), '\0');
    size_t n = contents->empty() ? 0 : std::fread(contents->data(), 1, contents->size(), f);
    bool err = std::ferror(f);
    std::fclose(f);
    if (err) return "read error";
    contents->resize(n);
    return "";
}

Tokenizer::Tokenizer(std::string text, std::string filename, const FileLoc &includedFrom)
    : text_(std::move(text)), file_(std::make_shared<const std::string>(std::move(filename))),
      includedFrom_(includedFrom.file ? std::make_shared<const FileLoc>(includedFrom) : nullptr) {
    const unsigned char *c = (const unsigned char *)text_.data();
    if (text_.size() >= 2 && ((c[0] == 0xfe && c[1] == 0xff) || (c[0] == 0xff && c[1] == 0xfe)))
        Fail(1, 1, "the file is UTF-16 encoded; scene files must be ASCII or UTF-8");
    if (text_.size() >= 2 && c[0] == 0x1f && c[1] == 0x8b)
        Fail(1, 1, "the file is gzip-compressed, which is not supported; decompress it first (gunzip)");
    if (text_.size() >= 3 && c[0] == 0xef && c[1] == 0xbb && c[2] == 0xbf) pos_ = 3;  // UTF-8 BOM
}

std::string Tokenizer::SourceLine(int line) const {
    if (line < 1) return "";
    size_t start = 0;
    if (line == line_) start = lineStart_;
    else {
        int l = 1;
        while (l < line) {
            size_t nl = text_.find('\n', start);
            if (nl == std::string::npos) return "";
            start = nl + 1;
            ++l;
        }
    }
    size_t end = text_.find('\n', start);
    if (end == std::string::npos) end = text_.size();
    end = std::min(end, start + 4096);
    return text_.substr(start, end - start);
}

void Tokenizer::Fail(int line, int col, const std::string &message) const {
    SceneError e(FileLoc{file_, line, col, includedFrom_}, message);
    e.SetSourceLine(SourceLine(line));
    throw e;
}

static std::string ByteName(unsigned char c) {
    char buf[8];
    std::snprintf(buf, sizeof(buf), "0x%02x", c);
    return buf;
}

bool Tokenizer::Next(Token *tok) {
    const char *s = text_.data();
    const size_t n = text_.size();
    while (pos_ < n) {
        unsigned char c = (unsigned char)s[pos_];
        int col = int(pos_ - lineStart_) + 1;
        if (c == '\n') {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') { ++pos_; continue; }
        if (c == '#') {  // comment to the end of the line; any text but NUL is allowed
            while (pos_ < n && s[pos_] != '\n') {
                if (s[pos_] == '\0')
                    Fail(line_, int(pos_ - lineStart_) + 1, "unexpected NUL byte in a comment (is this a binary file?)");
                ++pos_;
            }
            continue;
        }
        tok->line = line_;
        tok->col = col;
        tok->file = &file_;
        tok->includedFrom = &includedFrom_;
        tok->hasEscapes = false;
        if (c == '[' || c == ']') {
            tok->kind = c == '[' ? Token::OpenBracket : Token::CloseBracket;
            tok->raw = std::string_view(s + pos_, 1);
            ++pos_;
            return true;
        }
        if (c == '"') {
            size_t start = pos_++;
            while (true) {
                if (pos_ >= n || s[pos_] == '\n' || (s[pos_] == '\r' && pos_ + 1 < n && s[pos_ + 1] == '\n'))
                    Fail(line_, col, "unterminated string: missing closing '\"'");
                unsigned char d = (unsigned char)s[pos_];
                if (d == '"') break;
                if (d == '\\') {
                    if (pos_ + 1 >= n || s[pos_ + 1] == '\n')
                        Fail(line_, col, "unterminated string: missing closing '\"'");
                    if (!DecodeEscape(s[pos_ + 1])) {
                        unsigned char e = (unsigned char)s[pos_ + 1];
                        std::string shown = (e >= 0x20 && e < 0x7f) ? std::string(1, char(e)) : ByteName(e);
                        Fail(line_, int(pos_ - lineStart_) + 1, "unknown escape sequence '\\" + shown + "' in string");
                    }
                    tok->hasEscapes = true;
                    pos_ += 2;
                } else {
                    if ((d < 0x20 && d != '\t' && d != '\r') || d == 0x7f)
                        Fail(line_, int(pos_ - lineStart_) + 1,
                             "unexpected control byte " + ByteName(d) + " in string (is this a binary file?)");
                    ++pos_;
                }
                if (pos_ - start - 1 > MaxStringLength)
                    Fail(line_, col, "string too long (more than " + std::to_string(MaxStringLength) + " characters)");
            }
            ++pos_;  // closing quote
            tok->kind = Token::String;
            tok->raw = std::string_view(s + start, pos_ - start);
            return true;
        }
        // A word: up to whitespace, a quote or a bracket (as pbrt-v4).
        size_t start = pos_;
        while (pos_ < n) {
            unsigned char d = (unsigned char)s[pos_];
            if (d == ' ' || d == '\n' || d == '\t' || d == '\r' || d == '"' || d == '[' || d == ']') break;
            if (d < 0x20 || d >= 0x7f)
                Fail(line_, int(pos_ - lineStart_) + 1,
                     "unexpected byte " + ByteName(d) + " outside a string or comment (is this a binary file?)");
            ++pos_;
            if (pos_ - start > MaxWordLength)
                Fail(line_, col, "token too long (more than " + std::to_string(MaxWordLength) + " characters)");
        }
        tok->kind = Token::Word;
        tok->raw = std::string_view(s + start, pos_ - start);
        return true;
    }
    return false;
}

}  // namespace lu
