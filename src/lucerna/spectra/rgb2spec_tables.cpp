// Lucerna: the Jakob-Hanika coefficient tables of the four color spaces (ColorSpaceId order),
// fitted at build time by tools/rgb2spec_gen.cpp and embedded here with .incbin (layout
// documented in that tool).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "lucerna/spectra/registry.h"

#if !defined(LU_RGB2SPEC_BIN0) || !defined(LU_RGB2SPEC_BIN3) || !defined(LU_RGB2SPEC_RES)
#error "LU_RGB2SPEC_BIN0..3 must name the generated tables (set by src/lucerna/spectra/CMakeLists.txt)"
#endif

#define LU_EMBED_TABLE(sym, file)                 \
    __asm__(".section .rodata\n"                  \
            ".balign 64\n"                        \
            ".globl " #sym "\n"                   \
            ".type " #sym ", @object\n" #sym ":\n" \
            ".incbin \"" file "\"\n" #sym "_end:\n" \
            ".size " #sym ", " #sym "_end - " #sym "\n" \
            ".previous\n")

LU_EMBED_TABLE(lu_rgb2spec_data0, LU_RGB2SPEC_BIN0);
LU_EMBED_TABLE(lu_rgb2spec_data1, LU_RGB2SPEC_BIN1);
LU_EMBED_TABLE(lu_rgb2spec_data2, LU_RGB2SPEC_BIN2);
LU_EMBED_TABLE(lu_rgb2spec_data3, LU_RGB2SPEC_BIN3);

extern "C" const unsigned char lu_rgb2spec_data0[], lu_rgb2spec_data1[], lu_rgb2spec_data2[], lu_rgb2spec_data3[];

namespace lu {

namespace {

RGBToSpectrumTableData Decode(const unsigned char *data) {
    const uint32_t *header = reinterpret_cast<const uint32_t *>(data);
    if (header[0] != 0x3252554Cu || header[1] != LU_RGB2SPEC_RES) {
        std::fprintf(stderr, "lucerna: embedded RGB->spectrum table is corrupt\n");
        std::abort();
    }
    RGBToSpectrumTableData t;
    t.res = header[1];
    t.zNodes = reinterpret_cast<const Float *>(data + 16);
    t.coeffs = t.zNodes + t.res;
    return t;
}

}  // namespace

RGBToSpectrumTableData RGBToSpectrumTable(ColorSpaceId cs) {
    static const RGBToSpectrumTableData tables[NumColorSpaces] = {
        Decode(lu_rgb2spec_data0), Decode(lu_rgb2spec_data1), Decode(lu_rgb2spec_data2), Decode(lu_rgb2spec_data3)};
    return tables[uint32_t(cs) < NumColorSpaces ? uint32_t(cs) : 0];
}

RGBToSpectrumTableData SRGBToSpectrumTable() { return RGBToSpectrumTable(ColorSpaceId::SRGB); }

}  // namespace lu
