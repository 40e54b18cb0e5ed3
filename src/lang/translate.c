/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_ode_to_c (dynkit/lang.h): an .ode file to the C text of a dyn_model, in four passes —
 * statements (ode_parse.c, on the lines of source.c), names and order (check.c), then the
 * C text with its Jacobian (emit_c.c, deriv.c). The reference for what a file means is
 * XPPAUT (its manual and xppaut itself); docs/model-files.md, "The .ode format", lists
 * what is supported, dynkit's extensions and what is refused. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dynkit/io.h"
#include "lang/lang_internal.h"

const char *lang_base_name(lang_ctx *c, const char *path, const char *ext)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t n = strlen(b);
    const size_t k = strlen(ext);
    if (n > k && strncasecmp(b + n - k, ext, k) == 0)
        n -= k;
    if (!n)
        return "model";
    /* the name is shown wherever the model is (headers, notes, tables): a control byte of
     * the file's name is written \xNN by the one escaper (dynkit/io.h) */
    char *raw = lang_strndup(c, b, n);
    char *shown = lang_alloc(c, 4 * n + 1);
    return dyn_terminal_text(raw, 0, shown, 4 * n + 1);
}

void lang_ode_front(lang_ctx *c)
{
    c->m.name = lang_base_name(c, c->path, ".ode");
    lang_parse_model(c);
    lang_check_table_files(c);
    lang_check(c);
}

void lang_run_front(lang_ctx *c, void (*front)(lang_ctx *c))
{
    if (c->len > LANG_MAX_TEXT)
        lang_fail(c, (lpos){0, 0}, "file too large (%zu bytes; at most %u)", c->len,
                  LANG_MAX_TEXT);
    int lines = 1;
    for (size_t i = 0; i < c->len; i++)
        lines += c->text[i] == '\n';
    c->line_start = lang_alloc(c, (size_t)lines * sizeof *c->line_start);
    c->nlines = 0;
    c->line_start[c->nlines++] = 0;
    for (size_t i = 0; i < c->len; i++)
        if (c->text[i] == '\n' && c->nlines < lines)
            c->line_start[c->nlines++] = i + 1;
    if (c->len > 0 && c->text[c->len - 1] == '\n')
        c->nlines--; /* no empty last line */
    front(c);
    lang_model *m = &c->m;
    if (!m->title || !*m->title) {
        if (m->description && *m->description) {
            const char *nl = strchr(m->description, '\n');
            m->title = nl ? lang_strndup(c, m->description, (size_t)(nl - m->description))
                          : m->description;
        } else {
            m->title = m->name;
        }
    }
    if (!m->description)
        m->description = "";
}

int dyn_ode_to_c(const char *path, const char *text, size_t len, char **c_source,
                 dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx)
{
    return dyn_ode_to_c_tables(path, text, len, NULL, 0, c_source, diag, note, note_ctx);
}

int dyn_ode_to_c_tables(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, char **c_source,
                        dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx)
{
    return lang_translate(path, text, len, tables, n_tables, c_source, diag, note, note_ctx,
                          lang_ode_front, NULL);
}

lang_ctx *lang_ctx_new(const char *path, const char *text, size_t len,
                       const dyn_lang_table_file *tables, int n_tables, dyn_lang_diag *diag)
{
    lang_ctx *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->path = path;
    c->text = text ? text : "";
    c->len = len;
    c->diag = diag;
    c->table_files = tables;
    c->n_table_files = n_tables;
    return c;
}

void lang_ctx_free(lang_ctx *c, void *owner)
{
    if (c)
        lang_free_all(c);
    free(c);
    free(owner);
}

int lang_translate(const char *path, const char *text, size_t len,
                   const dyn_lang_table_file *tables, int n_tables, char **c_source,
                   dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx,
                   void (*front)(lang_ctx *c), char *(*back)(lang_ctx *c))
{
    return lang_translate_with(path, text, len, tables, n_tables, c_source, diag, note,
                               note_ctx, front, back, NULL);
}

int lang_translate_with(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, char **c_source,
                        dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx,
                        void (*front)(lang_ctx *c), char *(*back)(lang_ctx *c),
                        void *front_ctx)
{
    dyn_lang_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof *diag);
    if (!path)
        path = "<model>";
    strncpy(diag->path, path, sizeof diag->path - 1);
    if (c_source)
        *c_source = NULL;
    if (!c_source || (!text && len) || n_tables < 0 || (n_tables > 0 && !tables)) {
        strcpy(diag->message, "no text or no place for the C text (a NULL argument)");
        return 2;
    }
    for (int k = 0; k < n_tables; k++)
        if (!tables[k].name || !tables[k].path) {
            strcpy(diag->message, "a table file without a name or a path (a NULL argument)");
            return 2;
        }
    lang_ctx *c = lang_ctx_new(path, text, len, tables, n_tables, diag);
    if (!c) {
        strcpy(diag->message, "out of memory while translating the model");
        return 1;
    }
    c->note = note;
    c->note_ctx = note_ctx;
    c->hook_ctx = front_ctx;
    jmp_buf fail;
    c->fail = &fail;
    if (setjmp(fail)) {
        const int status = c->status ? c->status : 2;
        free(c->out);
        lang_ctx_free(c, NULL);
        return status;
    }
    c->table_file_used = lang_alloc(c, (size_t)n_tables + 1);
    memset(c->table_file_used, 0, (size_t)n_tables + 1);
    lang_run_front(c, front);
    char *out = back ? back(c) : lang_emit_c(c);
    lang_ctx_free(c, NULL);
    *c_source = out;
    return 0;
}
