// Tests of the checkpoint format (render/film.cpp): an exact round trip; any changed byte (every
// single byte flipped, 16 bytes of 0xff in the middle), a truncation at any length or an appended
// byte is refused with a message naming the file; format 1 and unknown versions are refused by
// version; a refused file leaves the film as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lucerna/render/film.h"
#include "support/test_support.h"

namespace lu {
namespace {

FilmAccumulator SmallFilm(int w = 3, int h = 2, uint32_t passes = 7) {
    FilmAccumulator film;
    film.Resize(w, h);
    film.passes = passes;
    for (size_t i = 0; i < film.xyzw.size(); ++i) film.xyzw[i] = std::sin(double(i) + 0.25) * 1e3 + 1e-9 * double(i);
    return film;
}

CheckpointInfo SmallInfo() {
    CheckpointInfo info;
    info.sceneFile = "scenes/some scene.pbrt";
    info.integrator = "regpath";
    info.seed = 4242;
    info.sceneHash = 0x0123456789abcdefull;
    info.seconds = 12.5;
    return info;
}

std::string Bytes(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

void Put(const std::string &path, const std::string &bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

// The message LoadCheckpoint throws ("" when it accepts the file); a refused file must leave the
// film untouched.
std::string LoadError(const std::string &path) {
    FilmAccumulator film = SmallFilm(1, 1, 99);
    CheckpointInfo info;
    try {
        LoadCheckpoint(path, &film, &info);
    } catch (const std::runtime_error &e) {
        EXPECT_EQ(film.passes, 99u);
        EXPECT_EQ(film.width, 1);
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Checkpoint, RoundTripIsExact) {
    std::string dir = test::TempDir("ckpt_roundtrip");
    FilmAccumulator film = SmallFilm();
    CheckpointInfo info = SmallInfo();
    SaveCheckpoint(dir + "/c.ckpt", film, info);
    FilmAccumulator back;
    CheckpointInfo backInfo;
    LoadCheckpoint(dir + "/c.ckpt", &back, &backInfo);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.passes, 7u);
    ASSERT_EQ(back.xyzw.size(), film.xyzw.size());
    EXPECT_EQ(std::memcmp(back.xyzw.data(), film.xyzw.data(), film.xyzw.size() * sizeof(double)), 0);
    EXPECT_EQ(backInfo.sceneFile, info.sceneFile);
    EXPECT_EQ(backInfo.integrator, info.integrator);
    EXPECT_EQ(backInfo.seed, info.seed);
    EXPECT_EQ(backInfo.sceneHash, info.sceneHash);
    EXPECT_EQ(backInfo.seconds, info.seconds);
    EXPECT_EQ(Bytes(dir + "/c.ckpt").substr(0, 8), "LUCKPT02");
}

// Every byte of the file matters: one bit or all eight flipped, at any offset, is refused.
TEST(Checkpoint, EveryChangedByteIsRefused) {
    std::string dir = test::TempDir("ckpt_flip");
    std::string path = dir + "/c.ckpt";
    SaveCheckpoint(path, SmallFilm(), SmallInfo());
    const std::string good = Bytes(path);
    ASSERT_EQ(LoadError(path), "");
    for (size_t i = 0; i < good.size(); ++i) {
        for (unsigned char mask : {0x01, 0xff}) {
            std::string bad = good;
            bad[i] = char(bad[i] ^ mask);
            Put(path, bad);
            std::string e = LoadError(path);
            ASSERT_NE(e, "") << "byte " << i << " ^ " << int(mask) << " accepted";
            ASSERT_EQ(e.rfind(path + ": ", 0), 0u) << e;
        }
    }
}

// The case of the issue: 16 bytes of 0xff in the middle of the sums made NaN pixels.
TEST(Checkpoint, SixteenBytesOfOnesAreAChecksumMismatch) {
    std::string dir = test::TempDir("ckpt_ones");
    std::string path = dir + "/c.ckpt";
    SaveCheckpoint(path, SmallFilm(16, 16), SmallInfo());
    std::string bad = Bytes(path);
    for (size_t i = 0; i < 16; ++i) bad[bad.size() / 2 + i] = char(0xff);
    Put(path, bad);
    std::string e = LoadError(path);
    EXPECT_NE(e.find(path + ": corrupt checkpoint: checksum mismatch (stored CRC-32 "), std::string::npos) << e;
}

TEST(Checkpoint, TruncatedOrExtendedIsRefused) {
    std::string dir = test::TempDir("ckpt_trunc");
    std::string path = dir + "/c.ckpt";
    SaveCheckpoint(path, SmallFilm(), SmallInfo());
    const std::string good = Bytes(path);
    for (size_t n = 0; n < good.size(); ++n) {
        Put(path, good.substr(0, n));
        ASSERT_NE(LoadError(path), "") << "truncated to " << n << " bytes and accepted";
    }
    Put(path, good + '\0');
    EXPECT_NE(LoadError(path), "");
    EXPECT_NE(LoadError(dir + "/missing.ckpt").find("cannot open checkpoint"), std::string::npos);
}

TEST(Checkpoint, OtherVersionsAreRefusedByVersion) {
    std::string dir = test::TempDir("ckpt_version");
    std::string path = dir + "/c.ckpt";
    // A format-1 file as the previous Lucerna wrote it: magic, sizes, passes, seed, hash, seconds,
    // two strings, the sums, the magic again.
    std::string v1 = "LUCKPT01";
    auto add = [&](const void *p, size_t n) { v1.append(static_cast<const char *>(p), n); };
    int32_t wh[2] = {1, 1};
    uint32_t passes = 3, seed = 1, len = 1;
    uint64_t hash = 5;
    double seconds = 1, sums[4] = {1, 2, 3, 4};
    add(wh, 8), add(&passes, 4), add(&seed, 4), add(&hash, 8), add(&seconds, 8);
    add(&len, 4), v1 += "s", add(&len, 4), v1 += "p";
    add(sums, sizeof sums);
    v1 += "LUCKPT01";
    Put(path, v1);
    std::string e = LoadError(path);
    EXPECT_NE(e.find(path + ": checkpoint format version 1 (an older Lucerna's, without a checksum) is not read by this "
                            "Lucerna, which reads version 2"),
              std::string::npos) << e;
    Put(path, "LUCKPT03" + std::string(64, '\0'));
    EXPECT_NE(LoadError(path).find("checkpoint format version 3 is not read"), std::string::npos) << LoadError(path);
    Put(path, "LUCKPTxx" + std::string(64, '\0'));
    EXPECT_NE(LoadError(path).find("no format version"), std::string::npos);
    Put(path, "not a checkpoint at all");
    EXPECT_NE(LoadError(path).find("not a Lucerna checkpoint"), std::string::npos);
}

TEST(Checkpoint, SaveIsAtomicAndReportsFailure) {
    std::string dir = test::TempDir("ckpt_atomic");
    SaveCheckpoint(dir + "/c.ckpt", SmallFilm(), SmallInfo());
    for (auto &e : std::filesystem::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), "c.ckpt");
    EXPECT_THROW(SaveCheckpoint(dir + "/no/such/folder/c.ckpt", SmallFilm(), SmallInfo()), std::runtime_error);
}

}  // namespace lu
