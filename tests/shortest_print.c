/* SPDX-License-Identifier: BSD-3-Clause */
/* For tests/shortest_oracle.py: reads doubles as 16 hexadecimal digits of their bits, one a
 * line, from standard input and writes each as dyn_format_double does, one a line. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/io.h"
#include "dynkit/ode.h"

int main(void)
{
    static dyn_text_writer w;
    dyn_text_writer_init(&w, stdout);
    char line[64];
    while (fgets(line, sizeof line, stdin)) {
        uint64_t bits;
        double x;
        if (sscanf(line, "%" SCNx64, &bits) != 1) {
            fprintf(stderr, "shortest_print: not a hexadecimal bit pattern: %s", line);
            return 2;
        }
        memcpy(&x, &bits, sizeof x);
        dyn_text_write_double(&w, x);
        dyn_text_write(&w, "\n", 1);
    }
    if (dyn_text_writer_flush(&w) != DYN_OK || fflush(stdout) != 0) {
        fprintf(stderr, "shortest_print: writing failed\n");
        return 1;
    }
    return 0;
}
