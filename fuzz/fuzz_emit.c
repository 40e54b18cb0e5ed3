/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer harness of what the .ode translator writes (src/lang/emit_out.c states the
 * rule: nothing from outside reaches the C text but as an escaped string literal). The
 * input is a path (the bytes before the first newline, up to a NUL) and the model text
 * (the rest). Every translation must pass the token check of emit_check.h: literals,
 * numbers, punctuators, the translator's own identifiers (its list, or a prefix and
 * numbers) and comments, nothing else. Built with libtcc (FUZZ_TCC), each translation is
 * also compiled in memory with -Werror, and must compile.
 *   fuzz_emit -max_total_time=300 -dict=fuzz/emit.dict fuzz/corpus/emit */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "emit_check.h"
#include "lang/lang_internal.h"

#ifdef FUZZ_TCC
#include <libtcc.h>

static void tcc_message(void *ctx, const char *msg)
{
    fprintf(stderr, "libtcc: %s\n", msg);
    *(int *)ctx = 1;
}

/* The C text compiles (in memory, not linked) without an error or warning. */
static void compiles(const char *text)
{
    TCCState *s = tcc_new();
    if (!s)
        abort();
    int failed = 0;
    tcc_set_error_func(s, &failed, tcc_message);
    tcc_set_lib_path(s, FUZZ_TCC_LIB_DIR);
    tcc_add_include_path(s, FUZZ_TCC_LIB_DIR "/include");
    tcc_add_include_path(s, FUZZ_DYNKIT_INCLUDE);
    tcc_set_options(s, "-Werror");
    tcc_set_output_type(s, TCC_OUTPUT_MEMORY);
    if (tcc_compile_string(s, text) < 0 || failed) {
        fputs(text, stderr);
        abort();
    }
    tcc_delete(s);
}
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nl = memchr(data, '\n', size);
    const size_t plen = nl ? (size_t)(nl - data) : 0;
    char path[1024];
    size_t k = 0;
    for (; k < plen && k + 1 < sizeof path && data[k]; k++)
        path[k] = (char)data[k];
    path[k] = '\0';
    const char *text = (const char *)data + (nl ? plen + 1 : 0);
    const size_t len = size - (nl ? plen + 1 : 0);
    char *out = NULL;
    dyn_lang_diag d;
    if (dyn_ode_to_c(path, text, len, &out, &d, NULL, NULL) != 0)
        return 0;
    char why[512];
    if (emit_check(out, lang_alg_solver_text(), why, sizeof why) != 0) {
        fprintf(stderr, "the C text breaks the rule: %s\n", why);
        abort();
    }
#ifdef FUZZ_TCC
    compiles(out);
#endif
    free(out);
    return 0;
}
