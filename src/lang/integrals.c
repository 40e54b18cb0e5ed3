/* SPDX-License-Identifier: BSD-3-Clause */
/* Volterra integrals in model files (XPPAUT's manual, "Volterra equations" and the
 * examples voltex1/voltex2): int{g} is int_t0^t g(t, t') dt', int{K#u} the convolution
 * int_t0^t K(t-t') u(t') dt', and int[mu]{...} multiplies the integrand by (t-t')^-mu,
 * 0 <= mu < 1 a number. In the integrand, t' is the time of integration and the states and
 * fixed quantities are read at t'; t is the time of the integral. Each integral of a line
 * is read here into c->m.volts and its text replaced by a name of its own (a SYM_VOLT,
 * resolved to N_VOLT): the rest of the translator sees one value, which the solver
 * (dynkit/volterra.h) writes into the parameter array before each evaluation. Also the C
 * text of the integrands, the kernels and the model's dyn_volterra_model. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/volterra.h"
#include "lang/lang_internal.h"

#define VOLT_MAX 1000 /* integrals of one model (the names _v0 .. _v999 fit in "int{x}") */
#define TPRIME "_tp"  /* t' in an integrand's text */

static int at_word(const lang_line *l, int i, const char *w)
{
    const int n = (int)strlen(w);
    if (i + n > l->len || (i > 0 && lang_is_ident_char((unsigned char)l->text[i - 1])))
        return 0;
    for (int k = 0; k < n; k++)
        if (tolower((unsigned char)l->text[i + k]) != w[k])
            return 0;
    return i + n == l->len || !lang_is_ident_char((unsigned char)l->text[i + n]);
}

static int skip_blanks(const lang_line *l, int k)
{
    while (k < l->len && (l->text[k] == ' ' || l->text[k] == '\t'))
        k++;
    return k;
}

/* The text [a, b) of l as an expression, t' read as TPRIME. */
static node *parse_part(lang_ctx *c, const lang_line *l, int a, int b, const char *what)
{
    lang_line sub;
    sub.text = lang_alloc(c, 3 * (size_t)(b - a) + 1);
    sub.pos = lang_alloc(c, (3 * (size_t)(b - a) + 1) * sizeof *sub.pos);
    int n = 0;
    for (int k = a; k < b; k++) {
        if ((l->text[k] == 't' || l->text[k] == 'T') && k + 1 < b && l->text[k + 1] == '\'' &&
            (k == a || !lang_is_ident_char((unsigned char)l->text[k - 1]))) {
            for (const char *s = TPRIME; *s; s++) {
                sub.pos[n] = l->pos[k];
                sub.text[n++] = *s;
            }
            k++;
            continue;
        }
        sub.pos[n] = l->pos[k];
        sub.text[n++] = l->text[k];
    }
    sub.pos[n] = l->pos[b];
    sub.text[n] = '\0';
    sub.len = n;
    lang_lexer lx = {c, &sub, 0, n};
    if (!lang_skip_blanks(&lx))
        lang_fail(c, l->pos[a], "%s is empty", what);
    node *e = lang_parse_expr(&lx);
    lang_expect_end(&lx, what);
    return e;
}

/* In an integrand: t is the time of the integral (N_VOLT -1), t' the time of integration
 * (N_TIME). In a kernel, t is the lag and t' has no meaning. */
static void swap_times(lang_ctx *c, node *e, int kernel)
{
    LANG_WORK(c, e->pos);
    if (e->kind == N_NAME && strcmp(e->name, TPRIME) == 0) {
        if (kernel)
            lang_fail(c, e->pos, "the kernel K of int{K#u} is a function of the lag t; t' "
                                 "belongs to the integrand u");
        e->kind = N_TIME;
        return;
    }
    if (e->kind == N_TIME && !kernel) {
        e->kind = N_VOLT;
        e->index = -1;
        return;
    }
    for (int i = 0; i < e->nargs; i++)
        swap_times(c, e->args[i], kernel);
}

void lang_volt_line(lang_ctx *c, const lang_line *l)
{
    lang_model *m = &c->m;
    for (int i = 0; i + 3 < l->len; i++) {
        if (!at_word(l, i, "int"))
            continue;
        int k = skip_blanks(l, i + 3);
        if (k >= l->len || (l->text[k] != '{' && l->text[k] != '['))
            continue;
        const lpos pos = l->pos[i];
        double mu = 0.0;
        if (l->text[k] == '[') {
            char *end;
            const int close = k + 1 + (int)strcspn(l->text + k + 1, "]");
            if (close >= l->len)
                lang_fail(c, pos, "int[m]{...}: expected ']' after the exponent m");
            char buf[64];
            const int nb = close - k - 1;
            if (nb <= 0 || nb >= (int)sizeof buf)
                lang_fail(c, l->pos[k], "int[m]{...}: m is a number, 0 <= m < 1 (XPPAUT: not "
                                        "a parameter)");
            memcpy(buf, l->text + k + 1, (size_t)nb);
            buf[nb] = '\0';
            mu = strtod(buf, &end);
            while (*end == ' ' || *end == '\t')
                end++;
            if (end == buf || *end || !(mu >= 0.0 && mu < 1.0))
                lang_fail(c, l->pos[k + 1], "int[%s]{...}: the exponent of (t-t')^-m is a "
                                            "number, 0 <= m < 1 (XPPAUT: not a parameter)",
                          buf);
            k = skip_blanks(l, close + 1);
            if (k >= l->len || l->text[k] != '{')
                lang_fail(c, l->pos[k < l->len ? k : l->len], "int[m]{...}: expected '{'");
        }
        const int open = k;
        int depth = 0, close = -1, hash = -1;
        for (int j = open; j < l->len && close < 0; j++) {
            if (l->text[j] == '{')
                depth++;
            else if (l->text[j] == '}' && --depth == 0)
                close = j;
            else if (l->text[j] == '#' && depth == 1) {
                if (hash >= 0)
                    lang_fail(c, l->pos[j], "int{K#u}: one '#' separates the kernel K from u");
                hash = j;
            }
        }
        if (close < 0)
            lang_fail(c, pos, "int{...}: expected '}' at the end of the integral");
        if (m->volts.n >= VOLT_MAX)
            lang_fail(c, pos, "too many integrals int{...} (at most %d)", VOLT_MAX);
        lang_volt *v = lvec_push(c, &m->volts, sizeof *v);
        v->pos = pos;
        v->mu = mu;
        v->kernel = hash >= 0 ? parse_part(c, l, open + 1, hash, "the kernel K of int{K#u}")
                              : NULL;
        v->integrand = parse_part(c, l, (hash >= 0 ? hash : open) + 1, close,
                                  "the integrand of int{...}");
        if (v->kernel)
            swap_times(c, v->kernel, 1);
        swap_times(c, v->integrand, 0);
        /* the integral's own name in its place, blanks after it */
        char name[16];
        const int len = snprintf(name, sizeof name, "_v%d", m->volts.n - 1);
        for (int j = i; j <= close; j++)
            l->text[j] = j - i < len ? name[j - i] : ' ';
        lang_declare(c, lang_strdup(c, name), pos, SYM_VOLT, m->volts.n - 1);
        i = close;
    }
}

int lang_volt_is_int_formula(lang_ctx *c, const lang_line *l, int from)
{
    for (int i = from; i + 2 < l->len; i++)
        if (l->text[i] == '_' && l->text[i + 1] == 'v' &&
            (i == 0 || !lang_is_ident_char((unsigned char)l->text[i - 1]))) {
            int k = i + 2;
            while (k < l->len && lang_is_ident_char((unsigned char)l->text[k]))
                k++;
            const char *name = lang_strndup(c, l->text + i, (size_t)(k - i));
            const lang_sym *s = lang_lookup(c, name);
            if (s && s->kind == SYM_VOLT)
                return 1;
        }
    return 0;
}

int lang_volt_model(const lang_model *m)
{
    for (int i = 0; i < m->states.n; i++)
        if (LVEC_AT(m->states, lang_state, i).is_int)
            return 1;
    return m->volts.n > 0;
}

void lang_volt_finish(lang_ctx *c)
{
    lang_model *m = &c->m;
    if (!lang_volt_model(m))
        return;
    const lpos pos = m->volts.n ? LVEC_AT(m->volts, lang_volt, 0).pos : (lpos){0, 0};
    if (m->map_eq || m->map_meth)
        lang_fail(c, m->map_pos, "a discrete map with Volterra integrals or integral "
                                 "equations: not supported");
    if (m->has_meth && m->meth_name && tolower((unsigned char)m->meth_name[0]) != 'v')
        lang_note(c, pos, "meth=%s is ignored: a model with Volterra integrals runs with "
                          "XPPAUT's volterra method, as XPPAUT does", m->meth_name);
    m->method = "volterra";
    m->meth_every_dt = 0;
    m->no_jacobian = 1;
}

/* Whether a kernel reads more than the lag and the parameters. */
static const char *kernel_reads(const node *e)
{
    switch (e->kind) {
    case N_STATE: return "a state";
    case N_FIX: return "a fixed quantity";
    case N_ALG: return "an algebraic variable";
    case N_VOLT: return "another integral";
    case N_NOISE: return "a noise";
    case N_DELAY: return "delay()";
    default: break;
    }
    for (int i = 0; i < e->nargs; i++) {
        const char *r = kernel_reads(e->args[i]);
        if (r)
            return r;
    }
    return NULL;
}

void lang_volt_resolve(lang_ctx *c, void (*resolve)(lang_ctx *, node *, int kernel))
{
    lang_model *m = &c->m;
    for (int k = 0; k < m->volts.n; k++) {
        lang_volt *v = &LVEC_AT(m->volts, lang_volt, k);
        resolve(c, v->integrand, 0);
        if (v->kernel) {
            resolve(c, v->kernel, 1);
            const char *r = kernel_reads(v->kernel);
            if (r)
                lang_fail(c, v->pos, "the kernel K of int{K#u} reads %s: it is a function of "
                                     "the lag t and the parameters (tabulated once per run); "
                                     "write int{K*u} for a kernel of t, t' and the states",
                          r);
        }
    }
}

void lang_emit_volterra(lang_ctx *c, int offset, void (*expr)(lang_ctx *, const node *),
                        void (*fixes)(lang_ctx *, node *const *, int))
{
    const lang_model *m = &c->m;
    const int nv = m->volts.n;
    node **roots = lang_alloc(c, (size_t)nv * sizeof *roots);
    for (int k = 0; k < nv; k++)
        roots[k] = LVEC_AT(m->volts, lang_volt, k).integrand;
    /* the integrands at t' (the C variable t) seen from t (t_now, in slot offset + nv) */
    LANG_C_CODE(c, "static int dk_volt_integrand(double t_now, double t, const double *y, "
                   "const double *ip, double *g, void *par)\n{\n"
                   "    double *pw = (double *)par;\n");
    LANG_C_CODEF(c, "    pw[%d] = t_now;\n    for (int k = 0; k < %d; k++)\n"
                    "        pw[%d + k] = ip[k];\n",
                 offset + nv, nv, offset);
    LANG_C_CODE(c, "    const double *p = pw;\n    (void)t;\n    (void)y;\n    (void)p;\n");
    fixes(c, roots, nv);
    for (int k = 0; k < nv; k++) {
        LANG_C_CODEF(c, "    g[%d] = ", k);
        expr(c, roots[k]);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    return 0;\n}\n\n");
    /* the kernels of the lag t */
    LANG_C_CODE(c, "static int dk_volt_kernel(double t, double *kv, void *par)\n{\n"
                   "    const double *p = (const double *)par;\n"
                   "    const double *y = (const double *)0;\n    (void)t;\n    (void)y;\n"
                   "    (void)p;\n");
    for (int k = 0; k < nv; k++) {
        const lang_volt *v = &LVEC_AT(m->volts, lang_volt, k);
        if (!v->kernel)
            continue;
        LANG_C_CODEF(c, "    kv[%d] = ", k);
        expr(c, v->kernel);
        LANG_C_CODE(c, ";\n");
    }
    LANG_C_CODE(c, "    return 0;\n}\n\n");
    LANG_C_CODE(c, "static const double dk_volt_mu[] = {");
    if (nv == 0) /* integral equations without integrals (XPPAUT's fr.ode) */
        LANG_C_CODE(c, "0.0");
    for (int k = 0; k < nv; k++) {
        if (k)
            LANG_C_CODE(c, ", ");
        lang_c_num(c, LVEC_AT(m->volts, lang_volt, k).mu);
    }
    LANG_C_CODE(c, "};\nstatic const unsigned char dk_volt_conv[] = {");
    if (nv == 0)
        LANG_C_CODE(c, "0");
    for (int k = 0; k < nv; k++)
        LANG_C_CODEF(c, k ? ", %d" : "%d", LVEC_AT(m->volts, lang_volt, k).kernel != NULL);
    LANG_C_CODE(c, "};\nstatic const unsigned char dk_volt_is_int[] = {");
    for (int i = 0; i < m->states.n; i++)
        LANG_C_CODEF(c, i ? ", %d" : "%d", LVEC_AT(m->states, lang_state, i).is_int);
    LANG_C_CODEF(c, "};\nstatic const dyn_volterra_model dk_volterra_model = {\n"
                    "    .n_int = %d,\n    .mu = dk_volt_mu,\n    .conv = dk_volt_conv,\n"
                    "    .is_int = dk_volt_is_int,\n    .ints_offset = %d * sizeof(double),\n"
                    "    .max_points = %ld,\n    .integrand = dk_volt_integrand,\n"
                    "    .kernel = dk_volt_kernel,\n};\n\n",
                 nv, offset, m->vmaxpts);
}
