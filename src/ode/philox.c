/* SPDX-License-Identifier: BSD-3-Clause */
/* Philox4x32-10, the counter-based generator of Salmon, Moraes, Dror and Shaw, "Parallel
 * random numbers: as easy as 1, 2, 3" (SC'11), written from the paper's description (the
 * S-box of two 32x32 -> 64-bit multiplications by 0xD2511F53 and 0xCD9E8D57, the key
 * schedule of the Weyl sequence 0x9E3779B9, 0xBB67AE85 added before each round after the
 * first) and checked against Random123's known-answer vectors (tests/test_sweep_sample.c);
 * and the random numbers of one run (dyn_rng, dynkit/sde.h): uniform numbers of 53 bits,
 * normal ones by the Box–Muller transform. */
#include <math.h>

#include "dynkit/model.h"
#include "dynkit/sde.h"

void dyn_philox4x32(const uint32_t ctr[4], const uint32_t key[2], int rounds,
                    uint32_t out[4])
{
    uint32_t x0 = ctr[0], x1 = ctr[1], x2 = ctr[2], x3 = ctr[3];
    uint32_t k0 = key[0], k1 = key[1];
    for (int r = 0; r < rounds; r++) {
        if (r > 0) {
            k0 += 0x9E3779B9u;
            k1 += 0xBB67AE85u;
        }
        const uint64_t p0 = (uint64_t)0xD2511F53u * x0;
        const uint64_t p1 = (uint64_t)0xCD9E8D57u * x2;
        const uint32_t y0 = (uint32_t)(p1 >> 32) ^ x1 ^ k0;
        const uint32_t y1 = (uint32_t)p1;
        const uint32_t y2 = (uint32_t)(p0 >> 32) ^ x3 ^ k1;
        const uint32_t y3 = (uint32_t)p0;
        x0 = y0;
        x1 = y1;
        x2 = y2;
        x3 = y3;
    }
    out[0] = x0;
    out[1] = x1;
    out[2] = x2;
    out[3] = x3;
}

double dyn_philox_unit(uint32_t hi, uint32_t lo)
{
    const uint64_t x = (((uint64_t)hi << 32) | lo) >> 11;
    return ((double)x + 0.5) * 0x1p-53;
}

void dyn_rng_init(dyn_rng *r, uint64_t seed, uint64_t stream)
{
    r->key[0] = (uint32_t)seed;
    r->key[1] = (uint32_t)(seed >> 32);
    r->stream[0] = (uint32_t)stream;
    r->stream[1] = (uint32_t)(stream >> 32) | 0x80000000u;
    r->block = 0;
    r->spare = 0.0;
    r->has_spare = 0;
}

static void next_block(dyn_rng *r, uint32_t w[4])
{
    const uint32_t ctr[4] = {(uint32_t)r->block, (uint32_t)(r->block >> 32), r->stream[0],
                             r->stream[1]};
    dyn_philox4x32(ctr, r->key, 10, w);
    r->block++;
}

double dyn_rng_normal(dyn_rng *r)
{
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    uint32_t w[4];
    next_block(r, w);
    const double u1 = dyn_philox_unit(w[0], w[1]);
    const double u2 = dyn_philox_unit(w[2], w[3]);
    const double rad = sqrt(-2.0 * log(u1));
    r->spare = rad * sin(2.0 * DYN_PI * u2);
    r->has_spare = 1;
    return rad * cos(2.0 * DYN_PI * u2);
}

double dyn_table_random(uint64_t seed, long call, long k, int kind)
{
    const uint32_t key[2] = {(uint32_t)seed, (uint32_t)(seed >> 32)};
    const uint64_t kk = (uint64_t)k;
    const uint32_t ctr[4] = {(uint32_t)kk, (uint32_t)(kk >> 32), (uint32_t)call, 0x40000000u};
    uint32_t w[4];
    dyn_philox4x32(ctr, key, 10, w);
    if (kind != DYN_NOISE_NORMAL) /* uniform on [0, 1), as dyn_rng_uniform */
        return (double)((((uint64_t)w[0] << 32) | w[1]) >> 11) * 0x1p-53;
    const double u1 = dyn_philox_unit(w[0], w[1]), u2 = dyn_philox_unit(w[2], w[3]);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * DYN_PI * u2);
}

double dyn_rng_uniform(dyn_rng *r)
{
    uint32_t w[4];
    next_block(r, w);
    /* [0, 1): 53 bits without the half */
    return (double)((((uint64_t)w[0] << 32) | w[1]) >> 11) * 0x1p-53;
}
