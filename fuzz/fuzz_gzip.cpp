// libFuzzer target: gzip decompression (scene/gzip.cpp over zlib) must never crash, hang or exceed
// its output bound; bad input may only return a reason, with the output left empty.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "lucerna/scene/gzip.h"

using namespace lu;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    constexpr size_t maxBytes = size_t(1) << 22;
    std::string out = "stale";
    std::string why = Gunzip(std::string_view(reinterpret_cast<const char *>(data), size), &out, maxBytes);
    if (out.size() > maxBytes) std::abort();
    if (!why.empty() && !out.empty()) std::abort();
    return 0;
}
