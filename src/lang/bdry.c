/* SPDX-License-Identifier: BSD-3-Clause */
/* bdry.c — XPPAUT's boundary conditions (`bdry EXPR`, also bndry, boundary, b; XPPAUT's
 * manual, "Boundary value problems"): EXPR = 0 at the two ends of [t0, t0 + total], where a
 * state's name is its value at t0 and the name followed by a prime (x') its value at the
 * right end. The conditions may use the states at both ends, parameters, numbers and
 * functions; not fixed quantities, algebraic variables, noise, delays or integrals (they are
 * values along a run, not at its ends). The C function dk_bdry(yl, yr, par, g) of
 * dyn_model.bdry writes the residuals, with the two ends as one array y: the left end's
 * states, then the right end's.
 *
 * XPPAUT's `bdry hom_bcs(k)` (its manual's "(H)omoclinic" and "AUTO" sections; the file
 * tsthomi.ode) is the k-th projection condition of a homoclinic or heteroclinic orbit: its
 * row of dk_bdry is 0 and the solver writes the projection (colloc_hom.c). The settings
 * XPPAUT's dialog asks for are read from the file (dyn_hom_bcs, model.h): the flow is the
 * states before the first one whose equation is x'=0; the equilibria are the states with
 * x'=0 that the other conditions use, in the file's order: dim of them hold the equilibrium
 * of both ends, 2 dim the left end's then the right end's. With hom_bcs there is one
 * condition fewer than states: AUTO's integral phase condition is the last. */
#include <ctype.h>
#include <string.h>

#include "lang/lang_internal.h"

/* k of a condition `hom_bcs(k)` at the cursor (read), or -1 (nothing read) */
static int hom_bcs_index(lang_lexer *lx)
{
    static const char word[] = "hom_bcs";
    const char *s = lx->line->text;
    int i = lx->i;
    for (int k = 0; word[k]; k++, i++)
        if (i >= lx->end || tolower((unsigned char)s[i]) != word[k])
            return -1;
    while (i < lx->end && (s[i] == ' ' || s[i] == '\t'))
        i++;
    if (i >= lx->end || s[i] != '(')
        return -1;
    lx->i = i + 1;
    lang_skip_blanks(lx);
    const lpos at = lang_here(lx);
    long k = 0;
    int digits = 0;
    for (i = lx->i; i < lx->end && isdigit((unsigned char)s[i]) && k < 1000; i++, digits++)
        k = 10 * k + (s[i] - '0');
    lx->i = i;
    if (!digits || k >= 1000 || lang_skip_blanks(lx) != ')')
        lang_fail(lx->c, at, "hom_bcs(K) takes a whole number K from 0 (the K-th projection "
                  "condition: the left end's first, then the right end's)");
    lx->i++;
    return (int)k;
}

void lang_bdry_parse(lang_ctx *c, lang_lexer *lx, lpos wpos)
{
    lang_skip_blanks(lx);
    const int from = lx->i;
    const int hom = hom_bcs_index(lx);
    node *e = lang_node(c, N_NUM, wpos); /* hom_bcs(k): 0, the solver's row */
    if (hom < 0) {
        c->in_bdry = 1;
        e = lang_parse_expr(lx);
        c->in_bdry = 0;
    }
    lang_expect_end(lx, hom < 0 ? "the boundary condition"
                                : "hom_bcs(K) (a projection condition is a whole bdry line)");
    *(int *)lvec_push(c, &c->m.bdry_hom, sizeof(int)) = hom;
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

/* a state's equation is x'=0 (a constant carried as a state) */
static int constant_state(const lang_model *m, int i)
{
    const node *r = LVEC_AT(m->states, lang_state, i).rhs;
    return r && r->kind == N_NUM && r->num == 0.0 && !LVEC_AT(m->states, lang_state, i).is_int;
}

/* mark in used[] the states (either end) that e reads */
static void mark_states(const node *e, int n, unsigned char *used)
{
    if (e->kind == N_STATE && e->index >= 0)
        used[e->index % n] = 1;
    for (int i = 0; i < e->nargs; i++)
        mark_states(e->args[i], n, used);
}

/* XPPAUT's (H)omoclinic settings read from the file (the rule at the top): dim, left, right
 * into hs (-1 where the file does not give them) */
static void hom_layout(lang_ctx *c, int hs[3])
{
    const lang_model *m = &c->m;
    const int n = m->states.n;
    int dim = 0;
    while (dim < n && !constant_state(m, dim))
        dim++;
    hs[0] = dim > 0 && dim < n ? dim : -1;
    hs[1] = hs[2] = -1;
    if (hs[0] < 0)
        return;
    unsigned char *used = lang_alloc(c, (size_t)n);
    memset(used, 0, (size_t)n);
    for (int k = 0; k < m->bdrys.n; k++)
        if (LVEC_AT(m->bdry_hom, int, k) < 0)
            mark_states(LVEC_AT(m->bdrys, lang_formula, k).expr, n, used);
    int held[2] = {-1, -1}, count = 0, contiguous = 1, last = -2;
    for (int i = dim; i < n; i++)
        if (used[i] && constant_state(m, i)) {
            if (count % dim == 0 && count / dim < 2)
                held[count / dim] = i;
            contiguous &= count % dim == 0 || i == last + 1;
            last = i;
            count++;
        }
    if (!contiguous || (count != dim && count != 2 * dim))
        return;
    hs[1] = held[0];
    hs[2] = count == dim ? held[0] : held[1];
}

void lang_emit_bdry(lang_ctx *c, void (*expr)(lang_ctx *, const node *))
{
    const lang_model *m = &c->m;
    const int n = m->states.n;
    int n_hom = 0;
    for (int k = 0; k < m->bdrys.n; k++)
        n_hom += LVEC_AT(m->bdry_hom, int, k) >= 0;
    if (n_hom && m->bdrys.n != n - 1)
        lang_fail(c, LVEC_AT(m->bdrys, lang_formula, 0).pos,
                  "%d boundary condition%s for %d state%s: with hom_bcs a boundary-value "
                  "problem needs one condition fewer than states (the integral phase "
                  "condition is the last, as in AUTO; a free constant is a state with x'=0)",
                  m->bdrys.n, m->bdrys.n == 1 ? "" : "s", n, n == 1 ? "" : "s");
    if (!n_hom && m->bdrys.n != n)
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
    if (!n_hom)
        return;
    int hs[3];
    hom_layout(c, hs);
    if (hs[0] < 0 || hs[1] < 0) {
        int k = 0;
        while (LVEC_AT(m->bdry_hom, int, k) < 0)
            k++;
        lang_fail(c, LVEC_AT(m->bdrys, lang_formula, k).pos,
                  "hom_bcs: the equilibria are not in the file's layout: the flow is the "
                  "states before the first one with x'=0, and the other conditions must use "
                  "as many x'=0 states (the equilibrium of both ends, homoclinic) or twice as "
                  "many (the left end's, then the right end's, heteroclinic), each group in a "
                  "row");
    }
    LANG_C_CODE(c, "static const int dk_bdry_hom[] = {");
    for (int k = 0; k < m->bdrys.n; k++) {
        if (k)
            LANG_C_CODE(c, ", ");
        LANG_C_CODEF(c, "%d", LVEC_AT(m->bdry_hom, int, k));
    }
    LANG_C_CODEF(c, "};\nstatic const dyn_hom_bcs dk_hom = {dk_bdry_hom, %d, %d, %d};\n\n",
                 hs[0], hs[1], hs[2]);
}

int lang_bdry_has_hom(const lang_model *m)
{
    for (int k = 0; k < m->bdry_hom.n; k++)
        if (LVEC_AT(m->bdry_hom, int, k) >= 0)
            return 1;
    return 0;
}
