/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer harness of the .ode translator (dynkit/lang.h): any bytes either translate into
 * C text or fail with a diagnostic that formats; nothing may crash, leak or read out of
 * bounds (built with -fsanitize=fuzzer,address,undefined; see fuzz/CMakeLists.txt).
 *   fuzz_ode -max_total_time=300 fuzz/corpus/ode */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"

static void note(const char *path, int line, const char *message, void *ctx)
{
    size_t *n = ctx;
    *n += strlen(path) + strlen(message) + (size_t)(line > 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *out = (char *)1;
    dyn_lang_diag d;
    size_t noted = 0;
    const int rc = dyn_ode_to_c("fuzz.ode", (const char *)data, size, &out, &d, note, &noted);
    if (rc == 0) {
        if (!out || strstr(out, "dynkit_model(void)") == NULL)
            abort();
        free(out);
    } else {
        if (out != NULL || (rc != 1 && rc != 2))
            abort();
        char buf[2048];
        dyn_lang_diag_format(&d, buf, sizeof buf);
        if (!strstr(buf, "error"))
            abort();
    }
    return 0;
}
