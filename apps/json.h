// Lucerna CLI (host): writing JSON that is always valid: strings escaped (quotes, backslashes,
// control characters; invalid UTF-8 bytes become U+FFFD), non-finite numbers written as null.
// Header-only; tested in tests/cli/json_test.cpp.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace lu::app {

// The JSON string literal (with its quotes) of s.
inline std::string JsonQuote(std::string_view s) {
    std::string out;
    out.reserve(s.size() + 2);
    out += '"';
    const auto *p = reinterpret_cast<const unsigned char *>(s.data());
    size_t n = s.size();
    for (size_t i = 0; i < n;) {
        unsigned char c = p[i];
        if (c < 0x80) {
            switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20 || c == 0x7f) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += char(c);
                }
            }
            ++i;
            continue;
        }
        // A multi-byte UTF-8 sequence: copied when well formed (no overlong forms, no
        // surrogates, at most U+10FFFF), else the byte becomes U+FFFD.
        size_t len = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
        bool ok = len > 0 && c <= 0xf4 && i + len <= n;
        for (size_t k = 1; ok && k < len; ++k) ok = (p[i + k] & 0xc0) == 0x80;
        if (ok && len == 3) {
            unsigned char c1 = p[i + 1];
            ok = !(c == 0xe0 && c1 < 0xa0) && !(c == 0xed && c1 >= 0xa0);
        }
        if (ok && len == 4) {
            unsigned char c1 = p[i + 1];
            ok = !(c == 0xf0 && c1 < 0x90) && !(c == 0xf4 && c1 >= 0x90);
        }
        if (ok) {
            out.append(reinterpret_cast<const char *>(p + i), len);
            i += len;
        } else {
            out += "\\ufffd";
            ++i;
        }
    }
    out += '"';
    return out;
}

// A number: the shortest text that reads back as the same double; null if not finite.
inline std::string JsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

// An object written field by field, in order: {"a": 1, "b": "x"}; Pretty() puts one field per
// line. Values that are objects or arrays are added with AddRaw (their Str()).
class JsonObject {
  public:
    JsonObject &Add(std::string_view key, std::string_view value) { return AddRaw(key, JsonQuote(value)); }
    JsonObject &Add(std::string_view key, const char *value) {
        return value ? Add(key, std::string_view(value)) : AddRaw(key, "null");
    }
    JsonObject &Add(std::string_view key, const std::string &value) { return Add(key, std::string_view(value)); }
    JsonObject &Add(std::string_view key, bool value) { return AddRaw(key, value ? "true" : "false"); }
    JsonObject &Add(std::string_view key, std::nullptr_t) { return AddRaw(key, "null"); }
    template <typename T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, int> = 0>
    JsonObject &Add(std::string_view key, T value) {
        if constexpr (std::is_integral_v<T>) return AddRaw(key, std::to_string(value));
        else return AddRaw(key, JsonNumber(double(value)));
    }
    JsonObject &Add(std::string_view key, const std::vector<std::string> &values) {
        std::string a = "[";
        for (size_t i = 0; i < values.size(); ++i) a += (i ? ", " : "") + JsonQuote(values[i]);
        return AddRaw(key, a + "]");
    }
    // value must already be JSON (a nested JsonObject's Str(), an array).
    JsonObject &AddRaw(std::string_view key, std::string value) {
        fields_.emplace_back(JsonQuote(key), std::move(value));
        return *this;
    }
    std::string Str() const {
        std::string s = "{";
        for (size_t i = 0; i < fields_.size(); ++i) s += (i ? ", " : "") + fields_[i].first + ": " + fields_[i].second;
        return s + "}";
    }
    std::string Pretty() const {
        if (fields_.empty()) return "{}";
        std::string s = "{\n";
        for (size_t i = 0; i < fields_.size(); ++i)
            s += "  " + fields_[i].first + ": " + fields_[i].second + (i + 1 < fields_.size() ? ",\n" : "\n");
        return s + "}";
    }

  private:
    std::vector<std::pair<std::string, std::string>> fields_;
};

}  // namespace lu::app
