// Tests of the pbrt-v4 tokenizer: token kinds, FileLoc (line, column), comments, escapes,
// brackets, and the errors for malformed or binary input.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lucerna/scene/tokenizer.h"

namespace lu {

struct Tok {
    Token::Kind kind;
    std::string text;
    int line, col;
};

static std::vector<Tok> Lex(const std::string &s) {
    Tokenizer tz(s, "test.pbrt");
    std::vector<Tok> out;
    Token t;
    while (tz.Next(&t)) out.push_back({t.kind, t.Text(), t.line, t.col});
    return out;
}

static SceneError LexError(const std::string &s) {
    try {
        Lex(s);
    } catch (SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no error for input of " << s.size() << " bytes";
    return SceneError(FileLoc{}, "");
}

TEST(Tokenizer, KindsAndLocations) {
    auto t = Lex("Shape \"sphere\"\n  \"float radius\" [ 2.5 ]\n");
    ASSERT_EQ(t.size(), 6u);
    EXPECT_EQ(t[0].kind, Token::Word);
    EXPECT_EQ(t[0].text, "Shape");
    EXPECT_EQ(t[0].line, 1);
    EXPECT_EQ(t[0].col, 1);
    EXPECT_EQ(t[1].kind, Token::String);
    EXPECT_EQ(t[1].text, "sphere");
    EXPECT_EQ(t[1].col, 7);
    EXPECT_EQ(t[2].text, "float radius");
    EXPECT_EQ(t[2].line, 2);
    EXPECT_EQ(t[2].col, 3);
    EXPECT_EQ(t[3].kind, Token::OpenBracket);
    EXPECT_EQ(t[3].col, 18);
    EXPECT_EQ(t[4].text, "2.5");
    EXPECT_EQ(t[4].col, 20);
    EXPECT_EQ(t[5].kind, Token::CloseBracket);
}

TEST(Tokenizer, BracketsAndQuotesDelimitWords) {
    auto t = Lex("[1 2]\"a\"b[c]");
    ASSERT_EQ(t.size(), 9u);
    EXPECT_EQ(t[0].kind, Token::OpenBracket);
    EXPECT_EQ(t[1].text, "1");
    EXPECT_EQ(t[2].text, "2");
    EXPECT_EQ(t[3].kind, Token::CloseBracket);
    EXPECT_EQ(t[4].text, "a");
    EXPECT_EQ(t[5].text, "b");
    EXPECT_EQ(t[5].kind, Token::Word);
    EXPECT_EQ(t[6].kind, Token::OpenBracket);
    EXPECT_EQ(t[7].text, "c");
    EXPECT_EQ(t[8].kind, Token::CloseBracket);
}

TEST(Tokenizer, CommentsAreSkipped) {
    auto t = Lex("# header\nA # trailing \"not a string\n# \xc3\xa9t\xc3\xa9 utf-8\nB");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].text, "A");
    EXPECT_EQ(t[1].text, "B");
    EXPECT_EQ(t[1].line, 4);
}

TEST(Tokenizer, EscapesInStrings) {
    auto t = Lex(R"("a\"b\\c\n\t" "it's")");
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].text, "a\"b\\c\n\t");
    EXPECT_EQ(t[1].text, "it's");
}

TEST(Tokenizer, CrLfAndTabsAndUtf8) {
    auto t = Lex("\xef\xbb\xbfWorldBegin\r\n\tShape \"caf\xc3\xa9\"\r\n");
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].text, "WorldBegin");
    EXPECT_EQ(t[1].line, 2);
    EXPECT_EQ(t[1].col, 2);
    EXPECT_EQ(t[2].text, "caf\xc3\xa9");
}

TEST(Tokenizer, EmptyInput) {
    EXPECT_TRUE(Lex("").empty());
    EXPECT_TRUE(Lex("  \n\t\r\n # only a comment").empty());
}

TEST(Tokenizer, UnterminatedString) {
    SceneError e = LexError("A\n  \"abc\nB");
    EXPECT_EQ(e.Message(), "unterminated string: missing closing '\"'");
    EXPECT_EQ(e.Loc().line, 2);
    EXPECT_EQ(e.Loc().col, 3);
    EXPECT_EQ(*e.Loc().file, "test.pbrt");
    // The diagnostic shows the line and a caret under the opening quote.
    EXPECT_EQ(e.Format(), "test.pbrt:2:3: error: unterminated string: missing closing '\"'\n  \"abc\n  ^");
    SceneError eof = LexError("\"abc");
    EXPECT_EQ(eof.Message(), "unterminated string: missing closing '\"'");
}

TEST(Tokenizer, BadEscape) {
    SceneError e = LexError("\"a\\qb\"");
    EXPECT_EQ(e.Message(), "unknown escape sequence '\\q' in string");
    EXPECT_EQ(e.Loc().col, 3);
}

TEST(Tokenizer, BinaryBytes) {
    SceneError e = LexError(std::string("Shape\n\x7f" "ELF\x02\x01"));
    EXPECT_EQ(e.Message(), "unexpected byte 0x7f outside a string or comment (is this a binary file?)");
    EXPECT_EQ(e.Loc().line, 2);
    SceneError nul = LexError(std::string("A\0B", 3));
    EXPECT_EQ(nul.Message(), "unexpected byte 0x00 outside a string or comment (is this a binary file?)");
    EXPECT_EQ(nul.Loc().col, 2);
    SceneError inString = LexError(std::string("\"a\x01\"", 4));
    EXPECT_EQ(inString.Message(), "unexpected control byte 0x01 in string (is this a binary file?)");
    SceneError utf16 = LexError(std::string("\xff\xfeW\0o\0", 6));
    EXPECT_EQ(utf16.Message(), "the file is UTF-16 encoded; scene files must be ASCII or UTF-8");
    SceneError gz = LexError(std::string("\x1f\x8b\x08\0", 4));
    EXPECT_EQ(gz.Message(), "the file is gzip-compressed, which is not supported; decompress it first (gunzip)");
}

TEST(Tokenizer, HugeTokensAreBounded) {
    SceneError w = LexError("A " + std::string(5000, '7'));
    EXPECT_EQ(w.Message(), "token too long (more than 1024 characters)");
    EXPECT_EQ(w.Loc().col, 3);
    SceneError s = LexError("\"" + std::string(100000, 'x') + "\"");
    EXPECT_EQ(s.Message(), "string too long (more than 65536 characters)");
    // Just under the bounds is fine.
    EXPECT_EQ(Lex(std::string(1024, '1')).size(), 1u);
    EXPECT_EQ(Lex("\"" + std::string(65536, 'x') + "\"")[0].text.size(), 65536u);
}

TEST(Tokenizer, FormatShowsLongLinesAroundTheColumn) {
    std::string line = std::string(300, 'a') + " \"oops";
    SceneError e = LexError(line);
    std::string f = e.Format();
    EXPECT_NE(f.find("error: unterminated string"), std::string::npos);
    // The caret line ends with '^' under the quote within a window of the line.
    size_t nl1 = f.find('\n'), nl2 = f.find('\n', nl1 + 1);
    std::string src = f.substr(nl1 + 1, nl2 - nl1 - 1), caret = f.substr(nl2 + 1);
    ASSERT_FALSE(caret.empty());
    EXPECT_EQ(caret.back(), '^');
    EXPECT_EQ(src[caret.size() - 1], '"');
    EXPECT_LT(src.size(), 200u);
}

}  // namespace lu
