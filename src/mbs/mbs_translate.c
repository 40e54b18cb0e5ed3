/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_mech_to_c (dynkit/mbs.h): a mechanism file to the C text of a dyn_model — its
 * statements (mbs_parse.c, inside src/lang's reading of the lines), src/lang's checks, the
 * equations of motion by TMT (mbs_derive.c), then src/lang's C text; with its scene's inputs
 * and an XPPAUT animation's formulas as outputs for live pages (dyn_mech_ani_to_c). */
#include "dynkit/mbs.h"
#include <string.h>

#include "lang/ani_internal.h"
#include "mbs/mbs_internal.h"

mbs_model *mbs_read(lang_ctx *c)
{
    mbs_model *mb = lang_alloc(c, sizeof *mb);
    memset(mb, 0, sizeof *mb);
    mb->alpha = MBS_DEFAULT_ALPHA;
    mb->gravity[0] = mb->gravity[1] = mb->gravity[2] = -1; /* none: 0 */
    c->m.name = lang_base_name(c, c->path, ".mech");
    c->stmt_hook = mbs_statement;
    c->hook_ctx = mb;
    c->no_arrays = 1;
    lang_parse_model(c);
    mbs_finish_parse(c, mb);
    lang_check_table_files(c);
    c->stmt_hook = NULL;
    lang_check(c);
    mbs_resolve_inputs(c, mb);
    mbs_resolve_laws(c, mb);
    mbs_check_units(c, mb);
    c->m.no_jacobian = 1;
    return mb;
}

static void front(lang_ctx *c, int symbolic, int values, int unchecked)
{
    mbs_model *mb = mbs_read(c);
    mb->symbolic = symbolic;
    mb->values = values;
    mb->unchecked = unchecked;
    mbs_derive(c, mb);
}

/* the model, then an output scene:K per fixed quantity K of the file as read (the inputs of
 * the scene's frames, dyn_mech_scene_plan: its reading gives them the same numbers) */
static void scene_front(lang_ctx *c, int unchecked)
{
    mbs_model *mb = mbs_read(c);
    const int n_inputs = c->m.fixes.n;
    mb->unchecked = unchecked;
    mbs_derive(c, mb);
    for (int k = 0; k < n_inputs; k++) {
        lang_formula *f = lvec_push(c, &c->m.auxs, sizeof *f);
        memset(f, 0, sizeof *f);
        f->name = lang_printf(c, "scene:%d", k);
        f->expr = lang_node(c, N_FIX, (lpos){0, 0});
        f->expr->index = k;
    }
}

/* the model with its scene's inputs, then an animation's formulas as outputs ani:K */
typedef struct scene_ani {
    const char *path, *text;
    size_t len;
    int unchecked;
} scene_ani;

static void scene_ani_front(lang_ctx *c)
{
    const scene_ani *a = c->hook_ctx; /* (mbs_read takes hook_ctx for itself) */
    scene_front(c, a->unchecked);
    ani_append_outputs(c, a->path, a->text, a->len);
}

static void mech_front(lang_ctx *c) { front(c, 0, 0, 0); }
static void unchecked_front(lang_ctx *c) { front(c, 0, 0, 1); }
static void scene_checked_front(lang_ctx *c) { scene_front(c, 0); }
static void scene_unchecked_front(lang_ctx *c) { scene_front(c, 1); }
static void values_front(lang_ctx *c) { front(c, 0, 1, 1); }
static void derive_front(lang_ctx *c) { front(c, 1, 0, 1); }
static char *derive_back(lang_ctx *c) { return mbs_text(c, c->hook_ctx); }

int dyn_mech_to_c(const char *path, const char *text, size_t len,
                  const dyn_lang_table_file *tables, int n_tables, char **c_source,
                  dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx)
{
    return lang_translate(path, text, len, tables, n_tables, c_source, diag, note, note_ctx,
                          mech_front, NULL);
}

int dyn_mech_to_c_flags(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, unsigned flags,
                        char **c_source, dyn_lang_diag *diag, dyn_lang_note_fn note,
                        void *note_ctx)
{
    const int unchecked = (flags & DYN_MECH_UNCHECKED_INIT) != 0;
    void (*fr)(lang_ctx *) = unchecked ? unchecked_front : mech_front;
    if (flags & DYN_MECH_SCENE_INPUTS)
        fr = unchecked ? scene_unchecked_front : scene_checked_front;
    return lang_translate(path, text, len, tables, n_tables, c_source, diag, note, note_ctx,
                          fr, NULL);
}

int dyn_mech_ani_to_c(const char *path, const char *text, size_t len,
                      const dyn_lang_table_file *tables, int n_tables, unsigned flags,
                      const char *ani_path, const char *ani_text, size_t ani_len,
                      char **c_source, dyn_lang_diag *diag)
{
    const scene_ani a = {ani_path ? ani_path : "<animation>", ani_text ? ani_text : "",
                         ani_text ? ani_len : 0, (flags & DYN_MECH_UNCHECKED_INIT) != 0};
    return lang_translate_with(path, text, len, tables, n_tables, c_source, diag, NULL, NULL,
                               scene_ani_front, NULL, (void *)&a);
}

int dyn_mech_derive_text(const char *path, const char *text, size_t len, char **out,
                         dyn_lang_diag *diag)
{
    return lang_translate(path, text, len, NULL, 0, out, diag, NULL, NULL, derive_front,
                          derive_back);
}

int dyn_mech_constraints_to_c(const char *path, const char *text, size_t len,
                              const dyn_lang_table_file *tables, int n_tables, char **c_source,
                              dyn_lang_diag *diag)
{
    return lang_translate(path, text, len, tables, n_tables, c_source, diag, NULL, NULL,
                          values_front, NULL);
}
