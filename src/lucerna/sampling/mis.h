// Lucerna: MIS heuristics (Veach 1997, section 9.2) for techniques whose pdfs share one measure.
// The integrator's weights for each of its techniques are in integrators/mis.h.
#pragma once

#include "lucerna/util/common.h"

namespace lu {

// Power heuristic (beta = 2), weight of technique a against b. An infinite pdfA (a Dirac
// technique) gets weight 1; two zero pdfs give 0.
LU_INLINE Float PowerHeuristic(Float pdfA, Float pdfB) {
    Float a = pdfA * pdfA, b = pdfB * pdfB;
    if (a == Infinity) return 1;
    return a + b > 0 ? a / (a + b) : 0;
}

// Balance heuristic (beta = 1), same conventions.
LU_INLINE Float BalanceHeuristic(Float pdfA, Float pdfB) {
    if (pdfA == Infinity) return 1;
    return pdfA + pdfB > 0 ? pdfA / (pdfA + pdfB) : 0;
}

}  // namespace lu
