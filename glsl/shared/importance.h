// One importance sampler for every technique that draws texels in proportion to a map: VSGL's BRSM
// sampling (RSM texels as VPL candidates, ../shared/MATH.md 10.1) and LightSkin's VAL selection
// (eq. 12). ../shared/MATH.md 9.7 has the tables and the search; this header is the search, compiled
// as GLSL (glsl/passes/importance_sample.comp) and as C++ (core/util/importance_table.cpp, the CPU twin).
//
// Tables, for a W x H map I(u, v) >= 0 (u column, v row):
//   C(u, v) = sum_{v' <= v} I(u, v')   column prefix sums ("vertical"), T(u) = C(u, H-1)
//   R(u)    = sum_{u' <= u} T(u')      prefix sums of the column totals ("horizontal"), total = R(W-1)
// Both are serial recurrences (x_k = x_{k-1} + a_k, one float add per step, in index order) on the
// GPU and on the CPU, so the two sides agree bit for bit. The recurrence also guarantees that a
// zero term leaves the sum bit-identical (x + 0 = x), which is what keeps zero-importance texels out
// of the search below; a log-step (tree) scan adds neighbouring prefixes in different orders and can
// make R(u) > R(u-1) by an ulp when T(u) = 0.
//
// Sampling (MATH.md 9.7): u = the smallest index with R(u) > xi1 * total, then v = the smallest index
// with C(u, v) > xi2 * T(u). With xi in [0, 1) the target is below the total, and a zero term makes
// R(u) = R(u-1) (or C(u, v) = C(u, v-1)), so the strict ">" never stops on a zero-importance texel.
// The per-draw probability is p = I(u, v) / total (MATH.md 9.9: an estimator over N draws divides by
// N p).
//
// The includer provides three table readers, declared before including this header (or defines
// VPLGI_IMPORTANCE_TYPES_ONLY when it only reads draws):
//   GLSL: float importanceMarginal(int u); float importanceColumn(int u, int v); float importanceValue(int u, int v);
//   C++:  the same functions with a leading `const Tables&` argument, found by argument-dependent
//         lookup when sampleImportance<Tables> is instantiated.
#ifndef VPLGI_SHARED_IMPORTANCE_H
#define VPLGI_SHARED_IMPORTANCE_H
#include "compat.h"

#ifdef __cplusplus
#define VPLGI_TABLES_TEMPLATE template <typename Tables>
#define VPLGI_TABLES_PARAM const Tables &tables,
#define VPLGI_TABLES tables,
#else
#define VPLGI_TABLES_TEMPLATE
#define VPLGI_TABLES_PARAM
#define VPLGI_TABLES
#endif

VPLGI_SHARED_BEGIN

// One draw, as the sample kernel writes it (std430, 16 bytes).
struct ImportanceSample {
    int x;             // texel column u; -1 when the map is all zero
    int y;             // texel row v; -1 when the map is all zero
    float probability; // per-draw probability I(u, v) / total
    float importance;  // I(u, v)
};

// A 32-bit integer hash: the PCG-based "pcg" hash of Jarzynski and Olano, "Hash Functions for GPU
// Rendering" (JCGT 2020): one LCG step, then PCG's xorshift-by-random-amount output permutation.
// Integer arithmetic wraps mod 2^32 in both languages, so CPU and GPU agree exactly.
VPLGI_FUNC uint hashPcg(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// 24 hash bits as a float in [0, 1): exact (a 24-bit integer times a power of two), never 1.
VPLGI_FUNC float uniformFromHash(uint h)
{
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

// The two uniform numbers of draw `index` under `seed`: the same on CPU and GPU, independent of
// how draws are spread over threads.
VPLGI_FUNC vec2 importanceUniforms(uint seed, uint index)
{
    uint h1 = hashPcg(hashPcg(seed) ^ index);
    uint h2 = hashPcg(h1);
    return vec2(uniformFromHash(h1), uniformFromHash(h2));
}

#ifndef VPLGI_IMPORTANCE_TYPES_ONLY // (readers of the draws that need no table readers define it)
// MATH.md 9.7 step 1: the smallest u in [0, width) with R(u) > target (width - 1 if none).
VPLGI_TABLES_TEMPLATE
VPLGI_FUNC int searchMarginal(VPLGI_TABLES_PARAM int width, float target)
{
    int lo = 0;
    int hi = width - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (importanceMarginal(VPLGI_TABLES mid) > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

// MATH.md 9.7 step 2: the smallest v in [0, height) with C(u, v) > target (height - 1 if none).
VPLGI_TABLES_TEMPLATE
VPLGI_FUNC int searchColumn(VPLGI_TABLES_PARAM int u, int height, float target)
{
    int lo = 0;
    int hi = height - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (importanceColumn(VPLGI_TABLES u, mid) > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

// Turns two uniform numbers into a texel drawn with probability I(u, v) / total (LightSkin eq. 12,
// the BRSM sampling of VSGL).
VPLGI_TABLES_TEMPLATE
VPLGI_FUNC ImportanceSample sampleImportance(VPLGI_TABLES_PARAM int width, int height, vec2 xi)
{
    ImportanceSample s;
    float total = importanceMarginal(VPLGI_TABLES width - 1);
    if (!(total > 0.0f)) {
        s.x = -1;
        s.y = -1;
        s.probability = 0.0f;
        s.importance = 0.0f;
        return s;
    }
    int u = searchMarginal(VPLGI_TABLES width, xi.x * total);
    float columnTotal = importanceColumn(VPLGI_TABLES u, height - 1);
    int v = searchColumn(VPLGI_TABLES u, height, xi.y * columnTotal);
    s.x = u;
    s.y = v;
    s.importance = importanceValue(VPLGI_TABLES u, v);
    s.probability = s.importance / total;
    return s;
}

#endif // VPLGI_IMPORTANCE_TYPES_ONLY

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::ImportanceSample) == 16, "ImportanceSample must match std430");
#endif

#endif // VPLGI_SHARED_IMPORTANCE_H
