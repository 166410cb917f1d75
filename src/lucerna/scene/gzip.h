// Lucerna scene reader: gzip-compressed inputs (.pbrt.gz, .ply.gz), read through zlib (host only).
// Compression is detected by the gzip magic bytes (1f 8b), whatever the file is called.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace lu {

// True if data starts with the gzip magic bytes.
bool IsGzip(std::string_view data);

// Decompresses gzip data (one member or several concatenated, as gzip writes them) into *out,
// at most maxBytes. Returns "" on success, else why: "truncated gzip data (...)", "corrupt gzip
// data (detected after N of M bytes): <zlib's reason>", "the decompressed data exceed N bytes".
std::string Gunzip(std::string_view data, std::string *out, size_t maxBytes);

// ReadFileBytes (tokenizer.h), then Gunzip if the bytes are gzip data. Returns "" on success,
// else why; *corrupt (if given) tells a decompression failure from a failure to read the file.
std::string ReadFileGunzipped(const std::string &path, std::string *contents, size_t maxBytes,
                              bool *corrupt = nullptr);

}  // namespace lu
