/* SPDX-License-Identifier: BSD-3-Clause */
/* What a model's right-hand side does with its noise (dyn_noise_class, dynkit/sde.h),
 * read from the formulas: whether each equation is affine in the Wiener slots (the
 * slots enter only as terms c*w, c free of noise, through sums, products with noise-free
 * factors, quotients by noise-free divisors and fixed quantities), which states the
 * coefficients c depend on, and which states each Wiener slot moves. Milstein's scheme
 * applied noise by noise (src/ode/sde.c) is right when the coefficient of each noise j
 * depends on no state that another noise moves (L^k b_j = 0 for k != j: Kloeden and
 * Platen 1992, sec. 10.3, commutative noise); additive noise (no coefficient depends on a
 * state) needs no correction at all. Anything this reading cannot prove affine, and the
 * slots of normal() and ran(), leaves only Euler–Maruyama. The reading is conservative: a
 * user function that uses a noise or a state in a coefficient counts as depending on
 * every state. */
#include <string.h>

#include "dynkit/sde.h"
#include "lang/lang_internal.h"

typedef struct nz_ctx {
    lang_ctx *c;
    int general;            /* a slot that is not a Wiener one, or not affine */
    unsigned char *coef;    /* states the coefficients of the current equation read */
    int *marked, nmarked;   /* ... as a list */
    int coef_all;           /* ... every state */
    int *mover;             /* per state: -1 none, the noise that moves it, -2 several */
    int eq;                 /* the current equation */
    int eq_noise;           /* its noise: -1 none, j, -2 several */
} nz_ctx;

static int has_noise(nz_ctx *x, const node *e);

static int func_has_noise(nz_ctx *x, int f)
{
    return has_noise(x, LVEC_AT(x->c->m.funcs, lang_func, f).body);
}

/* Whether e reads a noise slot, directly or through fixed quantities and functions. */
static int has_noise(nz_ctx *x, const node *e)
{
    LANG_WORK(x->c, e->pos);
    if (e->kind == N_NOISE)
        return 1;
    if (e->kind == N_FIX && has_noise(x, LVEC_AT(x->c->m.fixes, lang_formula, e->index).expr))
        return 1;
    if ((e->kind == N_UFUN || e->kind == N_UFUN_D) && func_has_noise(x, e->index))
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (has_noise(x, e->args[i]))
            return 1;
    return 0;
}

/* The states e reads into x->coef (every state for functions of the state and algebraic
 * variables). */
static void mark_states(nz_ctx *x, const node *e)
{
    LANG_WORK(x->c, e->pos);
    switch (e->kind) {
    case N_STATE:
        if (!x->coef[e->index]) {
            x->coef[e->index] = 1;
            x->marked[x->nmarked++] = e->index;
        }
        break;
    case N_ALG: x->coef_all = 1; break;
    case N_FIX: mark_states(x, LVEC_AT(x->c->m.fixes, lang_formula, e->index).expr); break;
    case N_UFUN:
    case N_UFUN_D: {
        const lang_func *f = &LVEC_AT(x->c->m.funcs, lang_func, e->index);
        if (f->uses_state || f->uses_fix)
            x->coef_all = 1;
        break;
    }
    default: break;
    }
    for (int i = 0; i < e->nargs; i++)
        mark_states(x, e->args[i]);
}

/* The degree of e in the Wiener slots: 0 (free of noise), 1 (affine, not constant), or -1
 * (anything else); for degree 1, the coefficients' states are marked and each Wiener slot
 * met is noted as moving the current equation. */
static int degree(nz_ctx *x, const node *e)
{
    LANG_WORK(x->c, e->pos);
    if (!has_noise(x, e))
        return 0;
    switch (e->kind) {
    case N_NOISE: {
        if (LVEC_AT(x->c->m.noises, lang_noise, e->index).kind != DYN_NOISE_WIENER)
            return -1;
        const int j = e->index;
        x->eq_noise = x->eq_noise == -1 || x->eq_noise == j ? j : -2;
        int *mv = &x->mover[x->eq];
        *mv = *mv == -1 || *mv == j ? j : -2;
        return 1;
    }
    case N_FIX: return degree(x, LVEC_AT(x->c->m.fixes, lang_formula, e->index).expr);
    case N_NEG: return degree(x, e->args[0]);
    case N_BIN: {
        node *a = e->args[0], *b = e->args[1];
        if (e->op == OP_ADD || e->op == OP_SUB) {
            const int da = degree(x, a), db = degree(x, b);
            return da < 0 || db < 0 ? -1 : 1;
        }
        if (e->op == OP_MUL) {
            if (has_noise(x, a) && has_noise(x, b))
                return -1;
            node *w = has_noise(x, a) ? a : b, *k = w == a ? b : a;
            if (degree(x, w) < 0)
                return -1;
            mark_states(x, k);
            return 1;
        }
        if (e->op == OP_DIV && !has_noise(x, b)) {
            if (degree(x, a) < 0)
                return -1;
            mark_states(x, b);
            return 1;
        }
        return -1;
    }
    default: return -1;
    }
}

/* The equation i read once: its degree, noise and coefficients' states (x->coef). */
static int read_equation(nz_ctx *x, int i)
{
    for (int k = 0; k < x->nmarked; k++)
        x->coef[x->marked[k]] = 0;
    x->nmarked = 0;
    x->eq = i;
    x->eq_noise = -1;
    x->coef_all = 0;
    return degree(x, LVEC_AT(x->c->m.states, lang_state, i).rhs);
}

void lang_noise_classify(lang_ctx *c)
{
    lang_model *m = &c->m;
    m->noise_class = DYN_NOISE_ADDITIVE;
    if (!m->noises.n)
        return;
    const int n = m->states.n;
    nz_ctx x = {0};
    x.c = c;
    x.coef = lang_alloc(c, (size_t)n + 1);
    memset(x.coef, 0, (size_t)n + 1);
    x.marked = lang_alloc(c, ((size_t)n + 1) * sizeof(int));
    x.mover = lang_alloc(c, ((size_t)n + 1) * sizeof(int));
    for (int i = 0; i < m->noises.n; i++)
        if (LVEC_AT(m->noises, lang_noise, i).kind != DYN_NOISE_WIENER)
            x.general = 1;
    for (int i = 0; i < m->algeqs.n; i++)
        if (has_noise(&x, LVEC_AT(m->algeqs, lang_formula, i).expr))
            x.general = 1;
    for (int i = 0; i < n; i++)
        x.mover[i] = -1;
    /* first the noises that move each state, then each equation's coefficients against them */
    for (int i = 0; i < n && !x.general; i++)
        if (read_equation(&x, i) < 0)
            x.general = 1;
    for (int i = 0; i < n && !x.general; i++) {
        if (x.mover[i] == -1)
            continue;
        read_equation(&x, i);
        if (x.coef_all || x.nmarked)
            m->noise_class = DYN_NOISE_COMMUTATIVE;
        /* a state a coefficient reads may be moved only by that equation's one noise */
        for (int l = 0; l < n && x.coef_all; l++)
            if (x.mover[l] != -1 && (x.eq_noise < 0 || x.mover[l] != x.eq_noise))
                x.general = 1;
        for (int k = 0; k < x.nmarked; k++) {
            const int l = x.marked[k];
            if (x.mover[l] != -1 && (x.eq_noise < 0 || x.mover[l] != x.eq_noise))
                x.general = 1;
        }
    }
    if (x.general)
        m->noise_class = DYN_NOISE_GENERAL;
}

const char *lang_noise_method(lang_ctx *c)
{
    const lang_model *m = &c->m;
    if (m->method && (strcmp(m->method, "euler") == 0 || strcmp(m->method, "discrete") == 0))
        return m->method;
    const char *use = m->noise_class == DYN_NOISE_GENERAL ? "euler" : "rkmil";
    if (m->method && m->has_meth)
        lang_note(c, (lpos){0, 0},
                  "meth=%s does not integrate noise: the default run uses %s (%s)",
                  m->meth_name ? m->meth_name : m->method, use,
                  m->noise_class == DYN_NOISE_GENERAL
                      ? "Euler-Maruyama"
                      : "Runge-Kutta Milstein, strong order 1, adaptive");
    return use;
}
