/* SPDX-License-Identifier: BSD-3-Clause */
/* A zlib stream (RFC 1950: header, Adler-32) of one DEFLATE block with the fixed Huffman
 * codes (RFC 1951, 3.2.6), its matches found by LZ77 over a 32 KiB window with hash chains:
 * how a live page carries its WebAssembly module (cli/pages/live_page.c), which the page
 * inflates with the browser's DecompressionStream('deflate'). The fixed codes need no table
 * in the stream; on a module they give 2.1 times less than the raw bytes (zlib -9 with its
 * own tables: 2.4). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pages.h"

enum {
    WINDOW = 32768,    /* the farthest match */
    MIN_MATCH = 3,
    MAX_MATCH = 258,
    HASH_BITS = 15,
    CHAIN = 256        /* the earlier places tried for a match */
};

typedef struct bits_out {
    unsigned char *p;
    size_t n;
    uint64_t acc; /* bits not yet written, the first in the lowest */
    int count;
} bits_out;

/* value's low `count` bits, the lowest first (the order of RFC 1951's extra bits) */
static void put_bits(bits_out *o, unsigned value, int count)
{
    o->acc |= (uint64_t)value << o->count;
    o->count += count;
    while (o->count >= 8) {
        o->p[o->n++] = (unsigned char)o->acc;
        o->acc >>= 8;
        o->count -= 8;
    }
}

/* a Huffman code: its bits from the highest */
static void put_code(bits_out *o, unsigned code, int length)
{
    unsigned reversed = 0;
    for (int i = 0; i < length; i++)
        reversed |= (code >> i & 1u) << (length - 1 - i);
    put_bits(o, reversed, length);
}

/* a literal/length symbol 0..287 in the fixed code */
static void put_symbol(bits_out *o, unsigned s)
{
    if (s < 144)
        put_code(o, 0x30 + s, 8);
    else if (s < 256)
        put_code(o, 0x190 + (s - 144), 9);
    else if (s < 280)
        put_code(o, s - 256, 7);
    else
        put_code(o, 0xC0 + (s - 280), 8);
}

static const unsigned short len_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,
                                            15, 17, 19, 23, 27, 31, 35, 43, 51,  59,
                                            67, 83, 99, 115, 131, 163, 195, 227, 258};
static const unsigned char len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                            2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const unsigned short dist_base[30] = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const unsigned char dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                             6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

static void put_match(bits_out *o, unsigned length, unsigned distance)
{
    int c = 28;
    while (len_base[c] > length)
        c--;
    put_symbol(o, 257u + (unsigned)c);
    put_bits(o, length - len_base[c], len_extra[c]);
    int d = 29;
    while (dist_base[d] > distance)
        d--;
    put_code(o, (unsigned)d, 5);
    put_bits(o, distance - dist_base[d], dist_extra[d]);
}

static unsigned hash3(const unsigned char *p)
{
    const uint32_t v = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
    return (v * 2654435761u) >> (32 - HASH_BITS);
}

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
    /* at most 9 bits a byte, the header, the block's 3 bits, its end and the checksum */
    bits_out o = {malloc(n + n / 8 + 16), 0, 0, 0};
    long *head = malloc(sizeof(long) << HASH_BITS);
    long *prev = malloc(sizeof(long) * WINDOW);
    if (!o.p || !head || !prev) {
        free(o.p);
        free(head);
        free(prev);
        return NULL;
    }
    for (size_t i = 0; i < (size_t)1 << HASH_BITS; i++)
        head[i] = -1;
    o.p[o.n++] = 0x78; /* deflate, a 32 KiB window */
    o.p[o.n++] = 0x01; /* no dictionary; 0x7801 is a multiple of 31 */
    put_bits(&o, 1, 1); /* the last block */
    put_bits(&o, 1, 2); /* of the fixed codes */
    size_t i = 0;
    /* every place up to `to` entered into the chains */
    size_t inserted = 0;
#define INSERT_UP_TO(to)                                                                     \
    for (; inserted < (to) && inserted + MIN_MATCH <= n; inserted++) {                      \
        const unsigned h = hash3(data + inserted);                                          \
        prev[inserted % WINDOW] = head[h];                                                  \
        head[h] = (long)inserted;                                                           \
    }
    while (i < n) {
        unsigned best = 0, best_dist = 0;
        if (i + MIN_MATCH <= n) {
            const size_t limit = n - i < MAX_MATCH ? n - i : MAX_MATCH;
            long cand = head[hash3(data + i)];
            for (int tries = 0; cand >= 0 && tries < CHAIN; tries++) {
                const size_t dist = i - (size_t)cand;
                if (dist > WINDOW)
                    break;
                if (data[cand + best] == data[i + best]) {
                    size_t len = 0;
                    while (len < limit && data[cand + len] == data[i + len])
                        len++;
                    if (len > best) {
                        best = (unsigned)len;
                        best_dist = (unsigned)dist;
                        if (len == limit)
                            break;
                    }
                }
                const long next = prev[cand % WINDOW];
                if (next >= cand) /* the slot was reused by a later place */
                    break;
                cand = next;
            }
        }
        if (best >= MIN_MATCH) {
            put_match(&o, best, best_dist);
            i += best;
        } else {
            put_symbol(&o, data[i]);
            i++;
        }
        INSERT_UP_TO(i);
    }
#undef INSERT_UP_TO
    put_symbol(&o, 256); /* the end of the block */
    if (o.count > 0)
        put_bits(&o, 0, 8 - o.count);
    const uint32_t check = adler32(data, n);
    for (int k = 3; k >= 0; k--)
        o.p[o.n++] = (unsigned char)(check >> (8 * k));
    free(head);
    free(prev);
    *out_n = o.n;
    return o.p;
}
