/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer harness of a mechanism file's unit reader (src/mbs/mbs_units.c, mbs_parse.c):
 * the input is a unit written in brackets after a coordinate, after a parameter and
 * without brackets after a parameter's value, in a small mechanism read by dyn_mech_to_c.
 * Each either translates or fails with a diagnostic at FILE:LINE:COL that formats;
 * nothing may crash (units nested without bound were a stack overflow), leak or read out of
 * bounds (built with -fsanitize=fuzzer,address,undefined; see fuzz/CMakeLists.txt).
 *   fuzz_unit -max_total_time=300 -dict=fuzz/unit.dict fuzz/corpus/unit */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "dynkit/mbs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void translate(const char *text, size_t len)
{
    char *out = (char *)1;
    dyn_lang_diag d;
    const int rc = dyn_mech_to_c("fuzz.mech", text, len, NULL, 0, &out, &d, NULL, NULL);
    if (rc == 0) {
        if (!out || strstr(out, "dynkit_model(void)") == NULL)
            abort();
        free(out);
        return;
    }
    if (out != NULL || (rc != 1 && rc != 2))
        abort();
    char buf[2048];
    dyn_lang_diag_format(&d, buf, sizeof buf);
    if (!strstr(buf, "error"))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (memchr(data, '\n', size) || memchr(data, ']', size) || memchr(data, '\0', size))
        return 0; /* one unit, inside its brackets */
    static const char *const forms[3][2] = {
        {"coord q=0.1 [", "]\npar m=1 [kg]\npoint p mass=m at (q, 0, 0)\n"},
        {"coord q=0.1 [m]\npar m=1 [kg], k=2 [", "]\npoint p mass=m at (q, 0, 0)\n"
                                                 "force f on p = (k*q, 0, 0)\n"},
        {"coord q=0.1 [m]\npar m=1 [kg], k=2 ", "\npoint p mass=m at (q, 0, 0)\n"},
    };
    for (int k = 0; k < 3; k++) {
        const size_t a = strlen(forms[k][0]), b = strlen(forms[k][1]);
        char *text = malloc(a + size + b + 1);
        if (!text)
            return 0;
        memcpy(text, forms[k][0], a);
        memcpy(text + a, data, size);
        memcpy(text + a + size, forms[k][1], b + 1);
        translate(text, a + size + b);
        free(text);
    }
    return 0;
}
