// Lucerna: the deterministic randomness used inside stochastic BSDFs (the layered coateddiffuse
// model): pbrt-v4's Hash(...) and PCG32 RNG, shared with the samplers (sampling/hash.h, rng.h).
#pragma once

#include "lucerna/sampling/hash.h"
#include "lucerna/sampling/rng.h"
