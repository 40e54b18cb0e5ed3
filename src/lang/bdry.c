/* SPDX-License-Identifier: BSD-3-Clause */
/* bdry.c — XPPAUT's boundary conditions (`bdry EXPR`, also bndry, boundary, b; XPPAUT's
 * manual, "Boundary value problems"): EXPR = 0 at the two ends of [t0, t0 + total], where a
 * state's name is its value at t0 and the name followed by a prime (x') its value at the
 * right end. The conditions may use the states at both ends, parameters, numbers and
 * functions; not fixed quantities, algebraic variables, noise, delays or integrals (they are
 * values along a run, not at its ends). XPPAUT's hom_bcs (projections for homoclinic
 * orbits) is refused by the expression reader (expr_parse.c). The C function dk_bdry(yl, yr, par, g) of dyn_model.bdry writes the
 * residuals, with the two ends as one array y: the left end's states, then the right end's. */

#include "lang/lang_internal.h"

void lang_bdry_parse(lang_ctx *c, lang_lexer *lx, lpos wpos)
{
    lang_skip_blanks(lx);
    const int from = lx->i;
    c->in_bdry = 1;
    node *e = lang_parse_expr(lx);
    c->in_bdry = 0;
    lang_expect_end(lx, "the boundary condition");
    int to = lx->end;
    while (to > from && (lx->line->text[to - 1] == ' ' || lx->line->text[to - 1] == '\t'))
        to--;
    lang_formula *f = lvec_push(c, &c->m.bdrys, sizeof *f);
    f->pos = wpos;
    f->expr = e;
    f->name = lang_printf(c, "%d: %.*s", wpos.line, to - from, lx->line->text + from);
}

static void right_end(lang_ctx *c, node *e, int n)
{
    switch (e->kind) {
    case N_STATE:
        if (e->op == 1) {
            e->index += n;
            e->op = 0;
        }
        return;
    case N_FIX:
    case N_ALG:
    case N_NOISE:
    case N_DELAY:
    case N_VOLT:
        lang_fail(c, e->pos, "a boundary condition can use the states at the two ends (NAME, "
                  "NAME'), parameters, numbers and functions; '%s' is a value along the run",
                  e->name ? e->name : "this");
    default:
        break;
    }
    if (e->op == 1 && e->kind != N_BIN && e->kind != N_FUN && e->kind != N_UFUN)
        lang_fail(c, e->pos, "'%s'' in a boundary condition: only a state's name takes a "
                  "prime (its value at the end)", e->name ? e->name : "?");
    for (int i = 0; i < e->nargs; i++)
        right_end(c, e->args[i], n);
}

void lang_bdry_resolved(lang_ctx *c, lang_formula *f)
{
    right_end(c, f->expr, c->m.states.n);
}

void lang_emit_bdry(lang_ctx *c, void (*expr)(lang_ctx *, const node *))
{
    const lang_model *m = &c->m;
    const int n = m->states.n;
    if (m->bdrys.n != n)
        lang_fail(c, LVEC_AT(m->bdrys, lang_formula, 0).pos,
                  "%d boundary condition%s for %d state%s: a boundary-value problem needs one "
                  "condition per state (XPPAUT's rule; a free constant is a state with x'=0)",
                  m->bdrys.n, m->bdrys.n == 1 ? "" : "s", n, n == 1 ? "" : "s");
    LANG_C_CODEF(c, "static int dk_bdry(const double *yl, const double *yr, const void *par, "
                    "double *g)\n{\n    const double *p = (const double *)par;\n"
                    "    double y[%d];\n    const double t = ", 2 * n);
    lang_c_num(c, m->t0);
    LANG_C_CODEF(c, ";\n    (void)t;\n    (void)p;\n    for (int i = 0; i < %d; i++) {\n"
                    "        y[i] = yl[i];\n        y[%d + i] = yr[i];\n    }\n", n, n);
    for (int k = 0; k < m->bdrys.n; k++) {
        const lang_formula *f = &LVEC_AT(m->bdrys, lang_formula, k);
        LANG_C_CODEF(c, "    g[%d] = ", k);
        expr(c, f->expr);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    return 0;\n}\n\nstatic const char *const dk_bdry_text[] = {\n");
    for (int k = 0; k < m->bdrys.n; k++) {
        LANG_C_CODE(c, "    ");
        lang_c_str(c, LVEC_AT(m->bdrys, lang_formula, k).name);
        LANG_C_CODE(c, ",\n");
    }
    LANG_C_CODE(c, "};\n\n");
}
