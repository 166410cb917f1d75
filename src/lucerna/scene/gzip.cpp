// Lucerna scene reader: gzip decompression with zlib's inflate (RFC 1952 members, checked CRC and
// length), bounded output, and located reasons for truncated or corrupt data.
#include "lucerna/scene/gzip.h"

#include <zlib.h>

#include <algorithm>
#include <climits>

#include "lucerna/scene/tokenizer.h"

namespace lu {

bool IsGzip(std::string_view data) {
    return data.size() >= 2 && (unsigned char)data[0] == 0x1f && (unsigned char)data[1] == 0x8b;
}

std::string Gunzip(std::string_view data, std::string *out, size_t maxBytes) {
    out->clear();
    z_stream zs{};
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK)  // 16: gzip wrapper only
        return "cannot initialize zlib";
    const unsigned char *in = (const unsigned char *)data.data();
    size_t inPos = 0;                  // bytes of data handed to zlib so far
    std::string why;
    char buf[1 << 16];
    while (true) {
        if (zs.avail_in == 0 && inPos < data.size()) {
            size_t n = std::min(data.size() - inPos, size_t(UINT_MAX));
            zs.next_in = const_cast<unsigned char *>(in + inPos);
            zs.avail_in = unsigned(n);
            inPos += n;
        }
        zs.next_out = (unsigned char *)buf;
        zs.avail_out = sizeof(buf);
        int r = inflate(&zs, Z_NO_FLUSH);
        size_t produced = sizeof(buf) - zs.avail_out;
        if (out->size() + produced > maxBytes) {
            why = "the decompressed data exceed " + std::to_string(maxBytes) + " bytes";
            break;
        }
        out->append(buf, produced);
        size_t consumed = inPos - zs.avail_in;  // offset of the next unread compressed byte
        if (r == Z_STREAM_END) {
            // Another member may follow (gzip -c a b > c); anything else is an error.
            if (consumed == data.size()) break;
            if (!IsGzip(data.substr(consumed))) {
                why = "corrupt gzip data: " + std::to_string(data.size() - consumed) +
                      " unexpected bytes after the end of the compressed stream (at byte " + std::to_string(consumed) + ")";
                break;
            }
            inflateReset(&zs);
            continue;
        }
        if (r == Z_DATA_ERROR || r == Z_NEED_DICT || r == Z_STREAM_ERROR) {
            why = std::string("corrupt gzip data (detected after ") + std::to_string(consumed) + " of " +
                  std::to_string(data.size()) + " bytes): " + (zs.msg ? zs.msg : "invalid compressed data");
            break;
        }
        if (r == Z_MEM_ERROR) {
            why = "out of memory while decompressing";
            break;
        }
        // Z_OK or Z_BUF_ERROR: progress is possible only with more input or output space.
        if (produced == 0 && zs.avail_in == 0 && inPos == data.size()) {
            why = "truncated gzip data (the compressed stream ends after " + std::to_string(data.size()) +
                  " bytes, before its end marker)";
            break;
        }
    }
    inflateEnd(&zs);
    if (!why.empty()) out->clear();
    return why;
}

std::string ReadFileGunzipped(const std::string &path, std::string *contents, size_t maxBytes, bool *corrupt) {
    if (corrupt) *corrupt = false;
    std::string raw;
    std::string why = ReadFileBytes(path, &raw, maxBytes);
    if (!why.empty()) return why;
    if (!IsGzip(raw)) {
        *contents = std::move(raw);
        return "";
    }
    why = Gunzip(raw, contents, maxBytes);
    if (!why.empty() && corrupt) *corrupt = true;
    return why;
}

}  // namespace lu
