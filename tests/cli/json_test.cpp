// Tests of apps/json.h: escaping (quotes, backslashes, control characters, invalid UTF-8),
// numbers (shortest round trip, non-finite as null), objects; and Python's json module reads
// the output back to the same strings and values.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "apps/json.h"
#include "support/test_support.h"

namespace lu::app {
namespace {

TEST(Json, QuoteEscapes) {
    EXPECT_EQ(JsonQuote("plain"), "\"plain\"");
    EXPECT_EQ(JsonQuote("a\"b"), "\"a\\\"b\"");
    EXPECT_EQ(JsonQuote("C:\\dir\\f"), "\"C:\\\\dir\\\\f\"");
    EXPECT_EQ(JsonQuote("l1\nl2\tt\r\b\f"), "\"l1\\nl2\\tt\\r\\b\\f\"");
    EXPECT_EQ(JsonQuote(std::string_view("nul\0x", 5)), "\"nul\\u0000x\"");
    EXPECT_EQ(JsonQuote("\x01\x1f"), "\"\\u0001\\u001f\"");
    EXPECT_EQ(JsonQuote(""), "\"\"");
}

TEST(Json, Utf8PassesInvalidBytesBecomeReplacement) {
    EXPECT_EQ(JsonQuote("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "\"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\"");
    EXPECT_EQ(JsonQuote("\xff"), "\"\\ufffd\"");
    EXPECT_EQ(JsonQuote("a\xc3"), "\"a\\ufffd\"");                // truncated sequence
    EXPECT_EQ(JsonQuote("\xc0\xaf"), "\"\\ufffd\\ufffd\"");       // overlong '/'
    EXPECT_EQ(JsonQuote("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // a UTF-16 surrogate
    EXPECT_EQ(JsonQuote("\xf4\x90\x80\x80"), "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // above U+10FFFF
}

TEST(Json, Numbers) {
    EXPECT_EQ(JsonNumber(0.1), "0.1");
    EXPECT_EQ(JsonNumber(-2), "-2");
    EXPECT_EQ(std::stod(JsonNumber(1.0 / 3)), 1.0 / 3);  // round trip
    EXPECT_EQ(JsonNumber(std::numeric_limits<double>::quiet_NaN()), "null");
    EXPECT_EQ(JsonNumber(std::numeric_limits<double>::infinity()), "null");
    EXPECT_EQ(JsonNumber(-std::numeric_limits<double>::infinity()), "null");
}

TEST(Json, ObjectKeepsOrderAndTypes) {
    JsonObject inner;
    inner.Add("x", 3).Add("y", -1);
    JsonObject o;
    o.Add("name", "a \"b\"").Add("n", uint64_t(18446744073709551615ull)).Add("f", 0.5f).Add("ok", true);
    o.Add("none", nullptr).Add("list", std::vector<std::string>{"p", "q\\"}).AddRaw("at", inner.Str());
    EXPECT_EQ(o.Str(), "{\"name\": \"a \\\"b\\\"\", \"n\": 18446744073709551615, \"f\": 0.5, \"ok\": true, "
                       "\"none\": null, \"list\": [\"p\", \"q\\\\\"], \"at\": {\"x\": 3, \"y\": -1}}");
    JsonObject two;
    two.Add("a", 1).Add("b", std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(two.Pretty(), "{\n  \"a\": 1,\n  \"b\": null\n}");
    EXPECT_EQ(JsonObject().Str(), "{}");
}

// An independent parser reads every byte value back: printable ASCII as itself, control
// characters through their escapes, invalid UTF-8 as U+FFFD.
TEST(Json, PythonReadsItBack) {
    std::string all;
    for (int c = 1; c < 256; ++c) all += char(c);
    JsonObject o;
    o.Add("all", all).Add("pi", 3.141592653589793).Add("nan", std::nan(""));
    std::string dir = lu::test::TempDir("json");
    std::ofstream(dir + "/t.json") << o.Pretty();
    std::string check =
        "import json, sys\n"
        "d = json.load(open(sys.argv[1], encoding='utf-8'))\n"
        "want = ''.join(chr(c) for c in range(1, 128)) + '\\ufffd' * 128\n"
        "assert d['all'] == want, repr(d['all'])\n"
        "assert d['pi'] == 3.141592653589793 and d['nan'] is None\n"
        "print('ok')\n";
    lu::test::ProcessResult r = lu::test::RunProcess({lu::test::PythonExe(), "-c", check, dir + "/t.json"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output, "ok\n");
}

}  // namespace
}  // namespace lu::app
