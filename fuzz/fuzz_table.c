/* libFuzzer harness of the CSV table reader of force tables (dyn_table_read, dynkit/io.h,
 * src/io/table_read.c): any bytes, given as a stream (fmemopen), either read into a table
 * whose shape, names and numbers hold what io.h promises, or fail with DYN_ERR_ARG and a
 * "SOURCE:LINE: ..." message; nothing may crash, leak or read out of bounds (built with
 * -fsanitize=fuzzer,address,undefined; see fuzz/CMakeLists.txt).
 *   fuzz_table -max_total_time=300 -dict=fuzz/table.dict fuzz/corpus/table */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(const uint8_t *data, size_t size, unsigned flags)
{
    /* fmemopen refuses a zero size: read an empty input from an empty string instead */
    static char empty[1];
    FILE *in = size ? fmemopen((void *)data, size, "r") : fmemopen(empty, 1, "r");
    if (!in)
        return;
    if (!size)
        fgetc(in); /* at the end: the empty input */
    dyn_table t;
    char err[512];
    memset(err, 0, sizeof err);
    const int rc = dyn_table_read(in, "fuzz.csv", flags, &t, err, sizeof err);
    fclose(in);
    if (rc == DYN_OK) {
        if (t.rows < 1 || t.cols < 1 || !t.data || !t.names ||
            (double)t.rows * t.cols > (double)DYN_TABLE_MAX_CELLS)
            abort();
        for (int j = 0; j < t.cols; j++) {
            if (!t.names[j] || !t.names[j][0] || dyn_table_column(&t, t.names[j]) != j)
                abort();
        }
        for (long k = 0; k < t.rows * t.cols; k++)
            if (!isfinite(t.data[k]))
                abort();
        if (flags & DYN_TABLE_TIME_FIRST)
            for (long r = 1; r < t.rows; r++)
                if (!(t.data[r * t.cols] > t.data[(r - 1) * t.cols]))
                    abort();
        dyn_table_free(&t);
        if (t.data || t.names || t.rows || t.cols)
            abort();
    } else {
        if (rc != DYN_ERR_ARG && rc != DYN_ERR_CAPACITY)
            abort();
        if (t.data || t.names || t.rows || t.cols || strncmp(err, "fuzz.csv:", 9) != 0 ||
            !memchr(err, '\0', sizeof err))
            abort();
        dyn_table_free(&t); /* safe on the emptied table */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check(data, size, 0);
    check(data, size, DYN_TABLE_TIME_FIRST);
    return 0;
}
