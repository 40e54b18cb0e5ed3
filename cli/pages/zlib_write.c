/* SPDX-License-Identifier: BSD-3-Clause */
/* A zlib stream (RFC 1950) of a buffer: how a live page carries its WebAssembly module
 * (cli/pages/live_page.c), which the page inflates with the browser's
 * DecompressionStream('deflate'). Compressed by the zlib library at level 9 when dynkit is
 * built with it (DYNKIT_HAVE_ZLIB: 2.4 times smaller on a module); without it, the same
 * stream format of stored DEFLATE blocks (RFC 1951, 3.2.4: the bytes themselves, a page then
 * 1.3 times larger), so a page is written either way. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pages.h"

#ifdef DYNKIT_HAVE_ZLIB
#include <zlib.h>

unsigned char *cli_zlib_compress(const unsigned char *data, size_t n, size_t *out_n)
{
    uLongf cap = compressBound((uLong)n);
    unsigned char *z = malloc(cap ? cap : 1);
    if (!z || compress2(z, &cap, n ? data : (const Bytef *)"", (uLong)n, 9) != Z_OK) {
        free(z);
        return NULL;
    }
    *out_n = cap;
    return z;
}

#else

static uint32_t adler32(const unsigned char *p, size_t n)
{
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < n; i++) {
        a = (a + p[i]) % 65521u;
        b = (b + a) % 65521u;
    }
    return b << 16 | a;
}

unsigned char *cli_zlib_compress(const unsigned char *data, size_t n, size_t *out_n)
{
    const size_t blocks = n / 65535 + 1;
    unsigned char *z = malloc(2 + 5 * blocks + n + 4), *o = z;
    if (!z)
        return NULL;
    *o++ = 0x78; /* deflate, 32 KiB window */
    *o++ = 0x01; /* no dictionary, fastest: the check bits make 0x7801 a multiple of 31 */
    size_t at = 0;
    do {
        const size_t len = n - at < 65535 ? n - at : 65535;
        *o++ = at + len == n; /* BFINAL, BTYPE 00: stored */
        *o++ = (unsigned char)len;
        *o++ = (unsigned char)(len >> 8);
        *o++ = (unsigned char)~len;
        *o++ = (unsigned char)(~len >> 8);
        if (len)
            memcpy(o, data + at, len);
        o += len;
        at += len;
    } while (at < n);
    const uint32_t check = adler32(data, n);
    for (int shift = 24; shift >= 0; shift -= 8)
        *o++ = (unsigned char)(check >> shift);
    *out_n = (size_t)(o - z);
    return z;
}

#endif
