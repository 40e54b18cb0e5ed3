/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_ode_auto_options (dynkit/lang.h): AUTO's settings of a model file's @ lines, as the
 * statements' parser (ode_parse.c) keeps them, handed to the caller in the file's order.
 * The one reader of those lines: dynkit continue takes its settings from here. XPPAUT's
 * manual, "AUTO", names the settings. */
#include <string.h>

#include "lang/lang_internal.h"

/* where the settings go: carried by the context's note_ctx (no notes are asked for) */
typedef struct setting_sink {
    dyn_lang_setting_fn fn;
    void *ctx;
} setting_sink;

static void parse_only(lang_ctx *c)
{
    c->m.name = lang_base_name(c, c->path, ".ode");
    lang_parse_model(c);
}

/* the back end: no text, every setting to the caller */
static char *hand_over(lang_ctx *c)
{
    const setting_sink *sink = c->note_ctx;
    for (int k = 0; k < c->m.auto_opts.n; k++) {
        const lang_auto_option *o = &LVEC_AT(c->m.auto_opts, lang_auto_option, k);
        sink->fn(o->name, o->value, o->pos.line, o->pos.col, sink->ctx);
    }
    return NULL;
}

int dyn_ode_auto_options(const char *path, const char *text, size_t len, dyn_lang_setting_fn fn,
                         void *ctx, dyn_lang_diag *diag)
{
    if (!fn) {
        if (diag) {
            memset(diag, 0, sizeof *diag);
            strcpy(diag->message, "no function for the settings (a NULL argument)");
        }
        return 2;
    }
    setting_sink sink = {fn, ctx};
    char *none = NULL;
    return lang_translate(path, text, len, NULL, 0, &none, diag, NULL, &sink, parse_only,
                          hand_over);
}
