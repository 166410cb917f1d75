// Lucerna: the sRGB Jakob-Hanika coefficient table, fitted at build time by
// tools/rgb2spec_gen.cpp and embedded here with .incbin (layout documented in that tool).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "lucerna/spectra/registry.h"

#ifndef LU_RGB2SPEC_BIN
#error "LU_RGB2SPEC_BIN must name the generated table (set by src/lucerna/spectrum/CMakeLists.txt)"
#endif

__asm__(".section .rodata\n"
        ".balign 64\n"
        ".globl lu_srgb_rgb2spec_data\n"
        ".type lu_srgb_rgb2spec_data, @object\n"
        "lu_srgb_rgb2spec_data:\n"
        ".incbin \"" LU_RGB2SPEC_BIN "\"\n"
        "lu_srgb_rgb2spec_data_end:\n"
        ".size lu_srgb_rgb2spec_data, lu_srgb_rgb2spec_data_end - lu_srgb_rgb2spec_data\n"
        ".previous\n");

extern "C" const unsigned char lu_srgb_rgb2spec_data[];

namespace lu {

RGBToSpectrumTableData SRGBToSpectrumTable() {
    static const RGBToSpectrumTableData table = [] {
        const uint32_t *header = reinterpret_cast<const uint32_t *>(lu_srgb_rgb2spec_data);
        if (header[0] != 0x3252554Cu || header[1] != LU_RGB2SPEC_RES) {
            std::fprintf(stderr, "lucerna: embedded RGB->spectrum table is corrupt\n");
            std::abort();
        }
        RGBToSpectrumTableData t;
        t.res = header[1];
        t.zNodes = reinterpret_cast<const Float *>(lu_srgb_rgb2spec_data + 16);
        t.coeffs = t.zNodes + t.res;
        return t;
    }();
    return table;
}

}  // namespace lu
