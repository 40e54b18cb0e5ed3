/* SPDX-License-Identifier: BSD-3-Clause */
/* The zlib streams live pages carry their module in (cli/pages/zlib_write.c) inflate, with
 * Python's zlib (an independent inflater that checks the stream's Adler-32), to the bytes
 * they were made of: nothing, one byte, every byte value, pseudo-random bytes, long runs of
 * one byte, a block repeated beyond DEFLATE's 32 KiB window and within it, text, and
 * WebAssembly code of the build when there is some. Built with zlib, the repeats within
 * the window, the runs and the text shrink, and the code at least 2.2 times; without it,
 * the stream holds the bytes in stored blocks: 6 bytes and 5 a block of 65535 more.
 * Skipped without Python. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "pages/pages.h"

#define PYTHON "/usr/bin/python3"

#ifdef DYNKIT_HAVE_ZLIB
enum { COMPRESSED = 1 };
#else
enum { COMPRESSED = 0 };
#endif

static int write_bytes(const char *path, const unsigned char *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    const int bad = fwrite(p, 1, n, f) != n;
    return fclose(f) != 0 || bad ? -1 : 0;
}

/* data compressed, then inflated by Python and compared with data; the stream's size */
static size_t round_trip(const unsigned char *data, size_t n)
{
    size_t zn = 0;
    unsigned char *z = cli_zlib_compress(data, n, &zn);
    assert_non_null(z);
    assert_true(zn <= n + n / 8 + 16);
    if (!COMPRESSED)
        assert_int_equal(zn, n + 6 + 5 * (n ? (n + 65534) / 65535 : 1));
    char raw[] = "/tmp/dynkit-zlib-raw-XXXXXX", packed[] = "/tmp/dynkit-zlib-z-XXXXXX";
    const int fr = mkstemp(raw), fz = mkstemp(packed);
    assert_true(fr >= 0 && fz >= 0);
    close(fr);
    close(fz);
    assert_int_equal(write_bytes(raw, data, n), 0);
    assert_int_equal(write_bytes(packed, z, zn), 0);
    char cmd[512];
    snprintf(cmd, sizeof cmd,
             PYTHON " -c \"import sys, zlib; raw = open(sys.argv[1], 'rb').read(); "
                    "z = open(sys.argv[2], 'rb').read(); sys.exit(0 if zlib.decompress(z) == raw "
                    "else 3)\" %s %s",
             raw, packed);
    const int rc = system(cmd);
    unlink(raw);
    unlink(packed);
    free(z);
    if (rc != 0)
        fail_msg("Python's zlib did not inflate the stream of %zu bytes to them (status %d)", n,
                 rc);
    return zn;
}

/* xorshift: bytes no match shortens */
static void random_bytes(unsigned char *p, size_t n, uint32_t seed)
{
    for (size_t i = 0; i < n; i++) {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        p[i] = (unsigned char)(seed >> 24);
    }
}

static void test_small(void **state)
{
    (void)state;
    round_trip((const unsigned char *)"", 0);
    round_trip((const unsigned char *)"a", 1);
    round_trip((const unsigned char *)"abc", 3);
    round_trip((const unsigned char *)"abcabcabcabcabca", 16);
    unsigned char all[512];
    for (int i = 0; i < 512; i++)
        all[i] = (unsigned char)(i < 256 ? i : 511 - i);
    round_trip(all, sizeof all);
}

static void test_random_and_runs(void **state)
{
    (void)state;
    const size_t n = 100000;
    unsigned char *p = malloc(n);
    assert_non_null(p);
    random_bytes(p, n, 12345u);
    const size_t zn = round_trip(p, n);
    assert_true(zn > n); /* nothing to find */
    memset(p, 'x', n);
    const size_t runs = round_trip(p, n);
    if (COMPRESSED)
        assert_true(runs < n / 50);
    free(p);
}

static void test_window(void **state)
{
    (void)state;
    /* a random block twice: 40 000 bytes apart, beyond the window; 20 000, within it */
    for (size_t block = 40000; block >= 20000; block -= 20000) {
        unsigned char *p = malloc(2 * block);
        assert_non_null(p);
        random_bytes(p, block, 777u);
        memcpy(p + block, p, block);
        const size_t zn = round_trip(p, 2 * block);
        if (block > 32768)
            assert_true(zn > 2 * block);
        else if (COMPRESSED)
            assert_true(zn < block + block / 8 + 100);
        free(p);
    }
}

static void test_text(void **state)
{
    (void)state;
    char text[30000];
    size_t n = 0;
    for (int k = 0; n + 80 < sizeof text; k++)
        n += (size_t)snprintf(text + n, sizeof text - n, "sample %d: y = %.6g, y' = %.6g\n", k,
                              k * 0.37, 1.0 / (k + 1));
    const size_t zn = round_trip((const unsigned char *)text, n);
    if (COMPRESSED)
        assert_true(zn < n / 2);
}

/* WebAssembly code of the build (the wasm32 object of src/ode/fixed_driver.c), when dynkit
 * was built with the WebAssembly library */
static void test_wasm(void **state)
{
    (void)state;
    FILE *f = fopen(DYNKIT_BUILD_DIR "/wasm32/obj/src_ode_fixed_driver.c.o", "rb");
    if (!f)
        skip();
    const size_t cap = (size_t)1 << 20;
    unsigned char *buf = malloc(cap);
    assert_non_null(buf);
    const size_t n = fread(buf, 1, cap, f);
    fclose(f);
    assert_true(n > 8 && memcmp(buf, "\0asm", 4) == 0);
    const size_t zn = round_trip(buf, n);
    if (COMPRESSED)
        assert_true(2.2 * (double)zn < (double)n);
    free(buf);
}

int main(void)
{
    if (access(PYTHON, X_OK) != 0) {
        printf("SKIP: " PYTHON " is missing (scripts/install-deps.sh)\n");
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small),
        cmocka_unit_test(test_random_and_runs),
        cmocka_unit_test(test_window),
        cmocka_unit_test(test_text),
        cmocka_unit_test(test_wasm),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
