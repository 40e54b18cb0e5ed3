/* SPDX-License-Identifier: BSD-3-Clause */
/* Markov states and Gillespie's method in model files, with XPPAUT's meaning (its manual,
 * "Markov models" and the `markov` statement; XPPAUT 6.11's `special NAME=gill(...)`):
 *
 *   markov z 2           a state z with values 0, 1; the next 2 lines are its rows of
 *   {0} {alpha(v)}       transition rates: from 0 to 1 at alpha(v), from 1 to 0 at beta(v)
 *   {beta(v)} {0}        (the diagonal is read and ignored)
 *
 * z is held over each step and jumps at its start, from i to j with probability
 * h * rate(i, j) (dyn_markov_step, src/ode/markov.c), all chains from the rates at the same
 * (t, y); its uniform number is a noise slot of its own, so a run's jumps are fixed by its
 * seed and stream like its other noise.
 *
 *   special z=gill(0, r1, r2, ...)   (or r{1-4}: r1 .. r4)
 *
 * z(0) is the waiting time to the next reaction and z(k) is 1 for the reaction k that
 * happens (rates r1 .. rm, Gillespie's direct method: dyn_gillespie_step), drawn once per
 * step of a discrete map from two uniform noise slots: a map x(t+1) = x + z(1) - z(2) is
 * the chain of reactions, t counts them and a state tr(t+1) = tr + z(0) is the time.
 *
 * The rates are fixed quantities without a name (read by nothing else), so they are
 * resolved, ordered and written as every fixed quantity. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dynkit/sde.h"
#include "lang/lang_internal.h"

#define MARKOV_MAX_STATES 50 /* XPPAUT's limit (markov.c: 50 states) */
#define GILL_MAX_REACTIONS 1000 /* XPPAUT's limit (its gill's list holds 1000) */

static int hidden_fix(lang_ctx *c, const char *what, lpos pos, node *e)
{
    lang_formula *f = lvec_push(c, &c->m.fixes, sizeof *f);
    f->name = what;
    f->pos = pos;
    f->expr = e;
    return c->m.fixes.n - 1;
}

/* A whole number written at the cursor (after blanks), from lo to hi. */
static long whole_number(lang_lexer *lx, long lo, long hi, const char *what)
{
    lang_skip_blanks(lx);
    const lpos pos = lang_here(lx);
    const char *s = lx->line->text + lx->i;
    int k = 0;
    while (lx->i + k < lx->end && isdigit((unsigned char)s[k]))
        k++;
    const long v = k > 0 && k < 9 ? strtol(s, NULL, 10) : -1;
    if (k == 0 || v < lo || v > hi)
        lang_fail(lx->c, pos, "expected %s (a whole number from %ld to %ld)", what, lo, hi);
    lx->i += k;
    return v;
}

void lang_markov_parse(lang_ctx *c, lang_lexer *lx, lpos kpos)
{
    (void)kpos;
    lpos npos;
    const char *name = lang_read_name(lx, &npos, "expected the Markov state's name after "
                                                 "'markov' (markov NAME NSTATES)");
    if (lang_is_reserved(name))
        lang_fail(c, npos, "'%s' is a reserved word of XPPAUT and cannot be declared", name);
    lang_markov *mk = lvec_push(c, &c->m.markovs, sizeof *mk);
    mk->name = name;
    mk->pos = npos;
    mk->n = (int)whole_number(lx, 1, MARKOV_MAX_STATES, "the number of states after the Markov "
                                                         "state's name");
    lang_expect_end(lx, "markov NAME NSTATES (its rows of rates follow on the next lines)");
    mk->rate = lang_alloc(c, (size_t)mk->n * (size_t)mk->n * sizeof *mk->rate);
}

int lang_markov_row(lang_ctx *c, lang_lexer *lx)
{
    lang_model *m = &c->m;
    if (m->markovs.n == 0)
        return 0;
    lang_markov *mk = &LVEC_AT(m->markovs, lang_markov, m->markovs.n - 1);
    if (mk->rows == mk->n)
        return 0;
    const int i = mk->rows;
    for (int j = 0; j < mk->n; j++) {
        if (lang_skip_blanks(lx) != '{')
            lang_fail(c, lang_here(lx),
                      "expected '{' of rate %d of row %d of the Markov state '%s' (its %d rows "
                      "follow 'markov %s %d', each with %d formulas in { })",
                      j, i, mk->name, mk->n, mk->name, mk->n, mk->n);
        const lpos pos = lang_here(lx);
        lx->i++;
        node *e = lang_parse_expr(lx);
        lang_expect_char(lx, '}', "expected '}' after the rate");
        mk->rate[i * mk->n + j] =
            i == j ? -1 /* XPPAUT ignores the diagonal */
                   : hidden_fix(c, lang_printf(c, "the rate of %s from %d to %d", mk->name, i, j),
                                pos, e);
    }
    lang_expect_end(lx, "the row of rates");
    mk->rows++;
    return 1;
}

void lang_markov_finish(lang_ctx *c)
{
    lang_model *m = &c->m;
    const int map = m->map_eq || m->map_meth;
    for (int k = 0; k < m->markovs.n; k++) {
        lang_markov *mk = &LVEC_AT(m->markovs, lang_markov, k);
        if (mk->rows < mk->n)
            lang_fail(c, mk->pos, "the Markov state '%s' has %d states: %d rows of %d rates in "
                      "{ } must follow on the next lines, and %d do", mk->name, mk->n, mk->n,
                      mk->n, mk->rows);
        if (m->events.n)
            lang_fail(c, mk->pos, "Markov states together with events or globals (line %d) are "
                      "not supported: a jump changes the state between two steps, where no "
                      "event is looked for",
                      LVEC_AT(m->events, lang_event, 0).pos.line);
        if (m->algs.n || m->n_delays)
            lang_fail(c, mk->pos, "Markov states together with %s are not supported",
                      m->algs.n ? "algebraic equations" : "delay()");
        mk->state = m->states.n;
        lang_declare(c, mk->name, mk->pos, SYM_STATE, mk->state);
        lang_state *st = lvec_push(c, &m->states, sizeof *st);
        st->name = mk->name;
        st->pos = mk->pos;
        if (map) { /* a map's next value: the value after the jump */
            st->rhs = lang_node(c, N_STATE, mk->pos);
            st->rhs->index = mk->state;
        } else {
            st->rhs = lang_num(c, 0.0);
        }
        mk->slot = m->noises.n;
        lang_noise *nz = lvec_push(c, &m->noises, sizeof *nz);
        nz->name = "markov";
        nz->pos = mk->pos;
        nz->kind = DYN_NOISE_UNIFORM;
    }
    for (int i = 0; i < m->specials.n && !map; i++) {
        const lang_special *sp = &LVEC_AT(m->specials, lang_special, i);
        if (sp->kind == LANG_SUM_GILL)
            lang_fail(c, sp->pos, "'%s' (gill, Gillespie's method) draws one reaction per step "
                      "of a discrete map: give @ meth=discrete (or write x(t+1)= equations)",
                      sp->name);
    }
}

/* ---- gill ---- */

/* One name of gill's list, or NAME{A-B} for NAMEA .. NAMEB (XPPAUT's shorthand), each a
 * rate: a fixed quantity from root on. */
static void gill_names(lang_ctx *c, lang_lexer *lx, const char *gill)
{
    lpos pos;
    const char *name = lang_read_name(lx, &pos, "expected the name of a reaction rate in gill's "
                                                "list");
    long a = 0, b = -1;
    if (lang_skip_blanks(lx) == '{') {
        lx->i++;
        a = whole_number(lx, 0, 1000000, "the first number of NAME{A-B}");
        lang_expect_char(lx, '-', "expected '-' in NAME{A-B}");
        b = whole_number(lx, a, a + GILL_MAX_REACTIONS, "the last number of NAME{A-B}");
        lang_expect_char(lx, '}', "expected '}' after NAME{A-B}");
    }
    for (long k = a; k <= (b < 0 ? a : b); k++) {
        node *e = lang_node(c, N_NAME, pos);
        e->name = b < 0 ? name : lang_printf(c, "%s%ld", name, k);
        hidden_fix(c, lang_printf(c, "%s's rate %s", gill, e->name), pos, e);
    }
}

void lang_gill_parse(lang_ctx *c, lang_lexer *lx, const char *name, lpos npos, lpos kpos)
{
    (void)kpos;
    lang_model *m = &c->m;
    lang_expect_char(lx, '(', "expected '(' after gill");
    lang_skip_blanks(lx);
    const lpos mpos = lang_here(lx);
    const long meth = whole_number(lx, 0, 1, "gill's method: 0 (Gillespie's direct method)");
    if (meth == 1)
        lang_note(c, mpos, "gill's method 1 (tau leaping) is run as 0, Gillespie's direct "
                           "method, as XPPAUT does");
    lang_expect_char(lx, ',', "expected ',' and the reaction rates after gill's method");
    const int root = m->fixes.n;
    for (;;) {
        gill_names(c, lx, name);
        const int sep = lang_skip_blanks(lx);
        if (sep != ',' && sep != ')')
            lang_fail(c, lang_here(lx), "expected ',' or ')' in gill's list of rates");
        lx->i++;
        if (sep == ')')
            break;
    }
    lang_expect_end(lx, "the network sum");
    const int nrx = m->fixes.n - root;
    if (nrx > GILL_MAX_REACTIONS)
        lang_fail(c, npos, "gill '%s' has %d reactions (at most %d)", name, nrx,
                  GILL_MAX_REACTIONS);
    if (lang_is_reserved(name))
        lang_fail(c, npos, "'%s' is a reserved word of XPPAUT and cannot be declared", name);
    lang_special sp = {0};
    sp.name = name;
    sp.pos = npos;
    sp.kind = LANG_SUM_GILL;
    sp.n = nrx + 1;
    sp.m = nrx;
    sp.ulen = nrx;
    sp.root_kind = N_FIX;
    sp.root = root;
    sp.table = -1;
    sp.slot = m->noises.n;
    for (int k = 0; k < 2; k++) {
        lang_noise *nz = lvec_push(c, &m->noises, sizeof *nz);
        nz->name = "gill";
        nz->pos = npos;
        nz->kind = DYN_NOISE_UNIFORM;
    }
    lang_declare(c, name, npos, SYM_SPECIAL, m->specials.n);
    *(lang_special *)lvec_push(c, &m->specials, sizeof sp) = sp;
}

/* ---- C text ---- */

void lang_emit_jump(lang_ctx *c, int noise, void (*fixes)(lang_ctx *, node *const *, int))
{
    const lang_model *m = &c->m;
    if (m->markovs.n == 0)
        return;
    int nroots = 0;
    for (int k = 0; k < m->markovs.n; k++) {
        const lang_markov *mk = &LVEC_AT(m->markovs, lang_markov, k);
        nroots += mk->n * mk->n;
    }
    node **roots = lang_alloc(c, (size_t)nroots * sizeof *roots);
    nroots = 0;
    for (int k = 0; k < m->markovs.n; k++) {
        const lang_markov *mk = &LVEC_AT(m->markovs, lang_markov, k);
        for (int q = 0; q < mk->n * mk->n; q++)
            if (mk->rate[q] >= 0) {
                node *r = lang_node(c, N_FIX, mk->pos);
                r->index = mk->rate[q];
                roots[nroots++] = r;
            }
    }
    LANG_C_CODE(c, "static int dk_jump(double t, double h, double *y, void *par)\n{\n"
                   "    const double *p = (const double *)par;\n    (void)t;\n    (void)p;\n");
    fixes(c, roots, nroots);
    LANG_C_CODE(c, "    int bad = 0;\n");
    for (int k = 0; k < m->markovs.n; k++) {
        const lang_markov *mk = &LVEC_AT(m->markovs, lang_markov, k);
        LANG_C_CODEF(c, "    {\n        const double r[%d] = {", mk->n * mk->n);
        for (int q = 0; q < mk->n * mk->n; q++) {
            if (q)
                LANG_C_CODE(c, ", ");
            if (mk->rate[q] < 0)
                LANG_C_CODE(c, "0.0");
            else
                LANG_C_CODEF(c, "v_%d", mk->rate[q]);
        }
        LANG_C_CODEF(c, "};\n        bad |= dyn_markov_step(y + %d, %d, r, h, p[%d]);\n    }\n",
                     mk->state, mk->n, noise + mk->slot);
    }
    LANG_C_CODE(c, "    return bad ? 1 : 0;\n}\n\n");
}

void lang_emit_gill(lang_ctx *c, int i, const lang_special *sp, int noise)
{
    LANG_C_CODEF(c, "    double sp_%d[%d];\n    dyn_gillespie_step(sp_%d, %d, spu_%d, p[%d], p[%d]);\n",
                 i, sp->n, i, sp->ulen, i, noise + sp->slot, noise + sp->slot + 1);
}
