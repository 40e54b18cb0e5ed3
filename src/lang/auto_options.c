/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_ode_auto_options (dynkit/lang.h): AUTO's settings of a model file's @ lines, as the
 * statements' parser (ode_parse.c) keeps them, handed to the caller in the file's order.
 * The one reader of those lines: dynkit continue takes its settings from here. XPPAUT's
 * manual, "AUTO", names the settings. */
#include <stdlib.h>
#include <string.h>

#include "lang/lang_internal.h"

static void parse_only(lang_ctx *c)
{
    c->m.name = lang_base_name(c, c->path, ".ode");
    lang_parse_model(c);
}

int dyn_ode_auto_options(const char *path, const char *text, size_t len, dyn_lang_setting_fn fn,
                         void *ctx, dyn_lang_diag *diag)
{
    dyn_lang_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof *diag);
    if (!path)
        path = "<model>";
    strncpy(diag->path, path, sizeof diag->path - 1);
    if (!fn || (!text && len)) {
        strcpy(diag->message, "no text or no function for the settings (a NULL argument)");
        return 2;
    }
    lang_ctx *c = lang_ctx_new(path, text, len, NULL, 0, diag);
    if (!c) {
        strcpy(diag->message, "out of memory while reading the model");
        return 1;
    }
    jmp_buf fail;
    c->fail = &fail;
    if (setjmp(fail)) {
        const int status = c->status ? c->status : 2;
        lang_ctx_free(c, NULL);
        return status;
    }
    lang_run_front(c, parse_only);
    for (int k = 0; k < c->m.auto_opts.n; k++) {
        const lang_auto_option *o = &LVEC_AT(c->m.auto_opts, lang_auto_option, k);
        fn(o->name, o->value, o->pos.line, o->pos.col, ctx);
    }
    lang_ctx_free(c, NULL);
    return 0;
}
