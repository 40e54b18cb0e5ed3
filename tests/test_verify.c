/* SPDX-License-Identifier: BSD-3-Clause */
/* test_verify.c — dyn_verify_run (dynkit/verify.h) and `dynkit verify`:
 * - the quick table has every problem and every method (cvode when built), each run did what
 *   it should, errors of finished runs are finite and match an independent solve, and the
 *   errors of the adaptive methods fall with the tolerance;
 * - fixed-step rows show the methods' orders (Euler 1, Heun 2, RK4 4) and halve the step;
 * - explicit methods stop at their step limit on the stiff problems and say so, fixed-step
 *   methods are skipped there; rodas4 meets the references to its tolerance;
 * - --problem and --method filter, unknown names are usage errors naming what is accepted;
 * - `dynkit verify --quick` exits 0 and prints the table; --json is valid JSON whose rows
 *   carry the same facts. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

/* ---- the library ---- */

static dyn_verify_row *run_rows(const dyn_verify_opts *o, long *n)
{
    char err[512];
    long count = dyn_verify_count(o, err, sizeof err);
    CHECK(count > 0, "count: %s", err);
    dyn_verify_row *rows = calloc((size_t)count, sizeof *rows);
    assert_non_null(rows);
    int rc = dyn_verify_run(o, rows, count, n, err, sizeof err);
    CHECK(rc == DYN_OK, "run: %s", err);
    assert_int_equal(*n, count);
    return rows;
}

static const dyn_verify_row *find_row(const dyn_verify_row *rows, long n, const char *problem,
                                      const char *method, double rtol, long steps)
{
    for (long k = 0; k < n; k++)
        if (strcmp(rows[k].problem->name, problem) == 0 && strcmp(rows[k].method, method) == 0 &&
            (rtol > 0 ? rows[k].adaptive && rows[k].rtol == rtol
                      : !rows[k].adaptive && rows[k].steps == steps))
            return &rows[k];
    return NULL;
}

static void test_quick_table(void **state)
{
    (void)state;
    dyn_verify_opts o = {.quick = 1};
    long n;
    dyn_verify_row *rows = run_rows(&o, &n);
    /* every problem with every method (but the discrete map, which integrates nothing) */
    for (int i = 0; i < dyn_verify_problem_count(); i++) {
        const dyn_verify_problem *p = dyn_verify_problem_at(i);
        for (int k = 0; k < dyn_method_count(); k++) {
            if (dyn_method_is_map(dyn_method_at(k)))
                continue;
            const char *m = dyn_method_at(k)->name;
            long found = 0;
            for (long j = 0; j < n; j++)
                found += rows[j].problem == p && strcmp(rows[j].method, m) == 0;
            CHECK(found >= 1, "no row for %s with %s", p->name, m);
        }
    }
    for (long j = 0; j < n; j++) {
        const dyn_verify_row *r = &rows[j];
        CHECK(r->ok, "%s %s: %s", r->problem->name, r->method, r->note);
        if (r->outcome == DYN_VERIFY_DONE) {
            CHECK(isfinite(r->error) && r->error >= 0.0, "%s %s: error %g", r->problem->name,
                  r->method, r->error);
            assert_true(r->stats.rhs_calls > 0 && r->stats.accepted > 0 && r->seconds >= 0.0);
            assert_true(r->t_reached == r->problem->t1);
            assert_true(fabs(r->digits + log10(r->error)) < 1e-12 || r->error == 0.0);
            /* stiff methods count their Jacobians, explicit ones have none */
            assert_true(r->stiff_method ? r->stats.jac_calls > 0 : r->stats.jac_calls == 0);
        }
        /* the stiff problems: fixed steps skipped, explicit pairs at their limit */
        if (r->problem->stiff && !r->adaptive)
            assert_int_equal(r->outcome, DYN_VERIFY_SKIPPED);
        if (r->problem->stiff && r->stiff_method)
            CHECK(r->outcome == DYN_VERIFY_DONE, "%s %s: %s", r->problem->name, r->method,
                  r->note);
    }
    /* the adaptive errors fall with the tolerance */
    for (long j = 0; j < n; j++) {
        const dyn_verify_row *a = &rows[j];
        if (!a->adaptive || a->rtol != 1e-3 || a->outcome != DYN_VERIFY_DONE)
            continue;
        const dyn_verify_row *b = find_row(rows, n, a->problem->name, a->method, 1e-6, 0);
        assert_non_null(b);
        CHECK(b->outcome == DYN_VERIFY_DONE && b->error < a->error,
              "%s %s: error %g at rtol 1e-3, %g at 1e-6", a->problem->name, a->method, a->error,
              b->error);
        CHECK(b->stats.rhs_calls > a->stats.rhs_calls, "%s %s: no more work for rtol 1e-6",
              a->problem->name, a->method);
    }
    /* Robertson to 1e11: the explicit pairs give up (20000 steps in the quick table) */
    const dyn_verify_row *r = find_row(rows, n, "robertson", "dp45", 1e-3, 0);
    assert_non_null(r);
    assert_int_equal(r->outcome, DYN_VERIFY_LIMIT);
    assert_int_equal(r->status, DYN_ERR_MAX_STEPS);
    assert_true(r->stats.steps == 20000 && r->t_reached < 1e4);
    assert_non_null(strstr(r->note, "too many steps"));
    assert_non_null(strstr(r->note, "stiff"));
    free(rows);
}

/* The error of a row equals one computed here with the public drivers and references. */
static void test_errors_independent(void **state)
{
    (void)state;
    dyn_verify_opts o = {.problem = "hires", .method = "rodas4"};
    long n;
    dyn_verify_row *rows = run_rows(&o, &n);
    assert_int_equal(n, DYN_VERIFY_N_RTOL);
    const dyn_reference *ref = dyn_reference_find("hires-321.8122");
    const dyn_model *m = dyn_model_find("hires");
    dyn_hires_par par;
    double y0[8], y[8];
    char err[128];
    assert_int_equal(dyn_reference_setup(ref, &par, y0, err, sizeof err), 0);
    const dyn_tableau *meth = dyn_method_find("rodas4");
    for (long k = 0; k < n; k++) {
        dyn_solve_opts so = {0};
        so.rtol = rows[k].rtol;
        so.atol = 1e-4 * rows[k].rtol;
        so.jacobian = m->jacobian;
        int iwork[8];
        so.iwork = iwork;
        static double work[4096];
        assert_true(dyn_solve_work_size(meth, 8, &so) <= sizeof work / sizeof work[0]);
        dyn_system sys = {m->rhs, 8, &par};
        dyn_result res;
        assert_int_equal(dyn_solve(meth, &sys, 0.0, ref->t1, y0, y, work, &so, &res), DYN_OK);
        double e = 0.0;
        for (int i = 0; i < 8; i++)
            e = fmax(e, fabs(y[i] - ref->y[i]) / fabs(ref->y[i]));
        CHECK(e == rows[k].error, "rtol %g: %.17g here, %.17g in the table", rows[k].rtol, e,
              rows[k].error);
        assert_int_equal(res.stats.rhs_calls, rows[k].stats.rhs_calls);
        /* rodas4 meets the published reference to about its tolerance */
        CHECK(e < 30.0 * rows[k].rtol, "rtol %g: relative error %g", rows[k].rtol, e);
    }
    assert_true(rows[2].error < 1e-3 * rows[0].error);
    free(rows);
    /* the references themselves */
    double r[8];
    const dyn_verify_problem *p = dyn_verify_problem_find("oscillator");
    assert_non_null(p);
    assert_int_equal(dyn_verify_reference(p, r, NULL, 0), 0);
    assert_true(r[0] == cos(20.0) && r[1] == -sin(20.0));
    p = dyn_verify_problem_find("arenstorf");
    assert_int_equal(dyn_verify_reference(p, r, NULL, 0), 0);
    for (int i = 0; i < 4; i++) /* back at the start */
        assert_true(fabs(r[i] - dyn_model_find("arenstorf")->y0[i]) < 2e-11);
}

static void test_fixed_orders(void **state)
{
    (void)state;
    static const struct {
        const char *problem, *method;
        double order;
    } cases[] = {{"vanderpol-mu1", "euler", 1.0},  {"vanderpol-mu1", "heun", 2.0},
                 {"vanderpol-mu1", "rk4", 4.0},    {"oscillator", "midpoint", 2.0},
                 {"oscillator", "rk4", 4.0},       {"oscillator", "rk38", 4.0},
                 {"arenstorf", "rk4", 4.0}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        dyn_verify_opts o = {.problem = cases[c].problem, .method = cases[c].method};
        long n;
        dyn_verify_row *rows = run_rows(&o, &n);
        assert_int_equal(n, 3);
        assert_true(isnan(rows[0].order));
        for (long k = 1; k < n; k++) {
            assert_int_equal(rows[k].steps, 2 * rows[k - 1].steps);
            assert_true(rows[k].h == rows[0].h / (double)(1L << k) ||
                        fabs(rows[k].h * (double)(1L << k) / rows[0].h - 1.0) < 1e-15);
            assert_int_equal(rows[k].stats.accepted, rows[k].steps);
        }
        CHECK(fabs(rows[2].order - cases[c].order) < 0.15, "%s %s: observed order %.3f",
              cases[c].problem, cases[c].method, rows[2].order);
        free(rows);
    }
}

static void test_filters_and_names(void **state)
{
    (void)state;
    char err[512];
    dyn_verify_opts o = {.problem = "nosuch"};
    assert_int_equal(dyn_verify_count(&o, err, sizeof err), -1);
    assert_non_null(strstr(err, "'nosuch'"));
    assert_non_null(strstr(err, "robertson"));
    o = (dyn_verify_opts){.method = "nosuch"};
    assert_int_equal(dyn_verify_count(&o, err, sizeof err), -1);
    assert_non_null(strstr(err, "rodas4"));
    /* aliases, filters */
    o = (dyn_verify_opts){.method = "ode45", .problem = "oscillator"};
    assert_int_equal(dyn_verify_count(&o, err, sizeof err), DYN_VERIFY_N_RTOL);
    o = (dyn_verify_opts){.method = "rk4"};
    /* 3 step sizes on 3 non-stiff problems, one skipped row on each stiff one */
    assert_int_equal(dyn_verify_count(&o, err, sizeof err), 3 * 3 + 4);
    /* too little room */
    dyn_verify_row row;
    long made = -1;
    assert_int_equal(dyn_verify_run(&o, &row, 1, &made, err, sizeof err), DYN_ERR_ARG);
    assert_int_equal(made, 0);
    /* an extra method comes in through the callback */
    assert_int_equal(dyn_verify_problem_count(), 7);
    assert_null(dyn_verify_problem_find("nosuch"));
}

/* An extra method: forward to rodas4 with the problem's Jacobian, counting the calls. */
static int extra_calls;
static int extra_solve(const dyn_system *sys, dyn_jac_fn jac, double t0, double t1,
                       const double *y0, double rtol, double atol, long max_steps, double *y,
                       dyn_result *res, void *ctx)
{
    (void)ctx;
    extra_calls++;
    dyn_solve_opts o = {0};
    o.rtol = rtol;
    o.atol = atol;
    o.max_steps = max_steps;
    o.jacobian = jac;
    int iwork[64];
    o.iwork = iwork;
    static double work[8192];
    const dyn_tableau *m = dyn_method_find("rodas4");
    assert_true(dyn_solve_work_size(m, sys->n, &o) <= sizeof work / sizeof work[0]);
    return dyn_solve(m, sys, t0, t1, y0, y, work, &o, res);
}

static void test_extra_method(void **state)
{
    (void)state;
    const dyn_verify_method extra = {"mine", 1, extra_solve, NULL};
    dyn_verify_opts o = {.quick = 1, .extra = &extra, .n_extra = 1, .method = "mine"};
    long n;
    extra_calls = 0;
    dyn_verify_row *rows = run_rows(&o, &n);
    assert_int_equal(n, 2 * dyn_verify_problem_count());
    assert_int_equal(extra_calls, n);
    for (long k = 0; k < n; k++) {
        assert_string_equal(rows[k].method, "mine");
        assert_true(rows[k].ok && rows[k].outcome == DYN_VERIFY_DONE);
        const dyn_verify_row *same = NULL;
        dyn_verify_opts r = {.quick = 1, .problem = rows[k].problem->name, .method = "rodas4"};
        long m;
        dyn_verify_row *ro = run_rows(&r, &m);
        same = find_row(ro, m, rows[k].problem->name, "rodas4", rows[k].rtol, 0);
        assert_non_null(same);
        if (strcmp(rows[k].problem->name, "brusselator") != 0) {
            assert_true(same->error == rows[k].error);
        } else {
            /* the built-in rodas4 uses the model's band matrices, the extra method (whose
             * interface has no band) dense ones: the same method, other rounding */
            CHECK(fabs(same->error - rows[k].error) <= 0.01 * same->error,
                  "band %g, dense %g", same->error, rows[k].error);
        }
        free(ro);
    }
    free(rows);
}

/* ---- the command line ---- */

/* A small JSON reader: validates RFC 8259 syntax and keeps what the tests look at. */
typedef struct jval jval;
typedef enum { JN_NULL, JN_BOOL, JN_NUM, JN_STR, JN_ARR, JN_OBJ } jtype;
struct jval {
    jtype type;
    double num;
    char *str;
    int n;
    jval *items;   /* arrays and objects (values) */
    char **keys;   /* objects */
};

static const char *jskip(const char *p)
{
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r')
        p++;
    return p;
}

static const char *jstring(const char *p, char **out)
{
    if (*p != '"')
        return NULL;
    p++;
    size_t cap = 64, len = 0;
    char *s = malloc(cap);
    while (*p && *p != '"') {
        char c = *p++;
        if ((unsigned char)c < 0x20) {
            free(s);
            return NULL;
        }
        if (c == '\\') {
            c = *p++;
            if (c == 'u') {
                for (int i = 0; i < 4; i++)
                    if (!isxdigit((unsigned char)p[i])) {
                        free(s);
                        return NULL;
                    }
                p += 4;
                c = '?';
            } else if (!strchr("\"\\/bfnrt", c)) {
                free(s);
                return NULL;
            }
        }
        if (len + 2 > cap)
            s = realloc(s, cap *= 2);
        s[len++] = c;
    }
    if (*p != '"') {
        free(s);
        return NULL;
    }
    s[len] = '\0';
    *out = s;
    return p + 1;
}

static const char *jvalue(const char *p, jval *v, int depth);

static const char *jitems(const char *p, jval *v, int object, int depth)
{
    char close = object ? '}' : ']';
    p = jskip(p + 1);
    int cap = 8;
    v->items = calloc((size_t)cap, sizeof *v->items);
    v->keys = object ? calloc((size_t)cap, sizeof *v->keys) : NULL;
    if (*p == close)
        return p + 1;
    while (1) {
        if (v->n == cap) {
            cap *= 2;
            v->items = realloc(v->items, (size_t)cap * sizeof *v->items);
            if (object)
                v->keys = realloc(v->keys, (size_t)cap * sizeof *v->keys);
        }
        if (object) {
            p = jstring(jskip(p), &v->keys[v->n]);
            if (!p)
                return NULL;
            p = jskip(p);
            if (*p++ != ':')
                return NULL;
        }
        memset(&v->items[v->n], 0, sizeof v->items[v->n]);
        p = jvalue(p, &v->items[v->n], depth + 1);
        if (!p)
            return NULL;
        v->n++;
        p = jskip(p);
        if (*p == ',') {
            p++;
            continue;
        }
        return *p == close ? p + 1 : NULL;
    }
}

static const char *jvalue(const char *p, jval *v, int depth)
{
    if (depth > 32)
        return NULL;
    p = jskip(p);
    if (*p == '{') {
        v->type = JN_OBJ;
        return jitems(p, v, 1, depth);
    }
    if (*p == '[') {
        v->type = JN_ARR;
        return jitems(p, v, 0, depth);
    }
    if (*p == '"') {
        v->type = JN_STR;
        return jstring(p, &v->str);
    }
    if (strncmp(p, "true", 4) == 0 || strncmp(p, "false", 5) == 0) {
        v->type = JN_BOOL;
        v->num = *p == 't';
        return p + (*p == 't' ? 4 : 5);
    }
    if (strncmp(p, "null", 4) == 0) {
        v->type = JN_NULL;
        return p + 4;
    }
    /* number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)? */
    const char *s = p;
    if (*p == '-')
        p++;
    if (*p == '0')
        p++;
    else if (isdigit((unsigned char)*p))
        while (isdigit((unsigned char)*p))
            p++;
    else
        return NULL;
    if (*p == '.') {
        p++;
        if (!isdigit((unsigned char)*p))
            return NULL;
        while (isdigit((unsigned char)*p))
            p++;
    }
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-')
            p++;
        if (!isdigit((unsigned char)*p))
            return NULL;
        while (isdigit((unsigned char)*p))
            p++;
    }
    v->type = JN_NUM;
    v->num = strtod(s, NULL);
    return p;
}

static void jfree(jval *v)
{
    for (int i = 0; i < v->n; i++) {
        jfree(&v->items[i]);
        if (v->keys)
            free(v->keys[i]);
    }
    free(v->items);
    free(v->keys);
    free(v->str);
}

static const jval *jget(const jval *obj, const char *key)
{
    for (int i = 0; obj->type == JN_OBJ && i < obj->n; i++)
        if (strcmp(obj->keys[i], key) == 0)
            return &obj->items[i];
    return NULL;
}

static const char *jstr(const jval *obj, const char *key)
{
    const jval *v = jget(obj, key);
    assert_non_null(v);
    assert_int_equal(v->type, JN_STR);
    return v->str;
}

static void test_cli_quick_table(void **state)
{
    (void)state;
    cli_result r = cli("verify --quick");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    const char *table = strstr(r.out, "\nPROBLEM          METHOD");
    assert_non_null(table);
    /* every problem and every method the tool lists has rows */
    const int cvode = cli_has_cvode();
    for (int i = 0; i < dyn_verify_problem_count(); i++) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "\n%-16s ", dyn_verify_problem_at(i)->name);
        CHECK(strstr(table, prefix) != NULL, "no rows of %s", dyn_verify_problem_at(i)->name);
    }
    for (int k = 0; k <= dyn_method_count(); k++) {
        const char *m = k < dyn_method_count() ? dyn_method_at(k)->name : "cvode";
        if (k == dyn_method_count() && !cvode)
            break;
        if (k < dyn_method_count() && dyn_method_is_map(dyn_method_at(k)))
            continue;
        char needle[64];
        snprintf(needle, sizeof needle, " %-8s ", m);
        CHECK(strstr(table, needle) != NULL, "no rows of %s", m);
    }
    /* every ERROR field is '-' or a finite number; done rows have numbers */
    long numbers = 0;
    for (const char *line = strchr(table + 1, '\n'); line && line[1] != '\n' && line[1];
         line = strchr(line + 1, '\n')) {
        char problem[32], method[32], tol[32], err[32];
        if (sscanf(line + 1, "%31s %31s %31s %31s", problem, method, tol, err) != 4)
            break;
        if (strcmp(err, "-") != 0) {
            char *end;
            double e = strtod(err, &end);
            CHECK(*end == '\0' && isfinite(e) && e >= 0.0, "%s %s %s: error '%s'", problem,
                  method, tol, err);
            numbers++;
        }
    }
    assert_true(numbers >= 60);
    assert_non_null(strstr(r.out, "every run as expected"));
    assert_non_null(strstr(r.out, "too many steps"));
    assert_non_null(strstr(r.out, "stiff: skipped"));
    cli_free(&r);
}

static void test_cli_json(void **state)
{
    (void)state;
    cli_result r = cli("verify --quick --json");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    jval doc = {0};
    const char *end = jvalue(r.out, &doc, 0);
    CHECK(end != NULL && *jskip(end) == '\0', "not one JSON value: %.200s", r.out);
    assert_int_equal(doc.type, JN_OBJ);
    const jval *problems = jget(&doc, "problems"), *rows = jget(&doc, "rows");
    assert_true(problems && problems->type == JN_ARR && problems->n == dyn_verify_problem_count());
    assert_true(rows && rows->type == JN_ARR && rows->n > 100);
    const jval *secs = jget(&doc, "seconds");
    assert_true(secs && secs->type == JN_NUM && secs->num > 0.0 && secs->num < 30.0);
    for (int i = 0; i < problems->n; i++) {
        const jval *p = &problems->items[i];
        const char *norm = jstr(p, "error_norm");
        assert_true(strcmp(norm, "absolute") == 0 || strcmp(norm, "relative") == 0);
        assert_true(strlen(jstr(p, "reference")) > 10);
        const jval *y = jget(p, "y_reference");
        assert_true(y && y->type == JN_ARR && y->n >= 2);
    }
    /* done rows: finite errors; adaptive errors fall from rtol 1e-3 to 1e-6 */
    int compared = 0;
    for (int k = 0; k < rows->n; k++) {
        const jval *a = &rows->items[k];
        const jval *ok = jget(a, "ok");
        assert_true(ok && ok->type == JN_BOOL && ok->num == 1);
        if (strcmp(jstr(a, "outcome"), "done") != 0)
            continue;
        const jval *e = jget(a, "error");
        assert_true(e && e->type == JN_NUM && isfinite(e->num));
        const jval *rt = jget(a, "rtol");
        if (!rt || rt->num != 1e-3)
            continue;
        for (int j = 0; j < rows->n; j++) {
            const jval *b = &rows->items[j];
            const jval *rb = jget(b, "rtol");
            if (rb && rb->num == 1e-6 && strcmp(jstr(a, "problem"), jstr(b, "problem")) == 0 &&
                strcmp(jstr(a, "method"), jstr(b, "method")) == 0) {
                const jval *eb = jget(b, "error");
                CHECK(eb->type == JN_NUM && eb->num < e->num, "%s %s: %g then %g",
                      jstr(a, "problem"), jstr(a, "method"), e->num, eb->num);
                compared++;
            }
        }
    }
    assert_true(compared >= 18); /* 4 core adaptive methods x 3 problems, rodas4 on the
                                  * stiff ones, the explicit pairs on hires */
    jfree(&doc);
    cli_free(&r);
}

static void test_cli_options(void **state)
{
    (void)state;
    cli_result r = cli("verify --problem robertson --method rodas4");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    assert_int_equal(strstr(r.out, "\nhires ") == NULL, 1);
    assert_non_null(strstr(r.out, "\nrobertson        rodas4   rtol=1e-09"));
    assert_non_null(strstr(r.out, "Test Set for IVP Solvers"));
    cli_free(&r);
    r = cli("verify --problem nosuch");
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "'nosuch'"));
    assert_non_null(strstr(r.err, "hires"));
    cli_free(&r);
    r = cli("verify --method nosuch");
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "dop853"));
    cli_free(&r);
    r = cli("verify --bogus");
    assert_int_equal(r.status, 2);
    cli_free(&r);
    r = cli("verify --method cvode --problem oscillator --quick");
    if (cli_has_cvode()) {
        CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
        assert_non_null(strstr(r.out, "oscillator       cvode    rtol=1e-06"));
    } else {
        assert_int_equal(r.status, 2);
        assert_non_null(strstr(r.err, "without SUNDIALS"));
    }
    cli_free(&r);
    r = cli("verify --help");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "Usage: dynkit verify"));
    cli_free(&r);
    r = cli("--help");
    assert_non_null(strstr(r.out, "verify"));
    cli_free(&r);
}

static int teardown(void **state)
{
    (void)state;
    return cli_teardown_files(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quick_table),
        cmocka_unit_test(test_errors_independent),
        cmocka_unit_test(test_fixed_orders),
        cmocka_unit_test(test_filters_and_names),
        cmocka_unit_test(test_extra_method),
        cmocka_unit_test(test_cli_quick_table),
        cmocka_unit_test(test_cli_json),
        cmocka_unit_test(test_cli_options),
    };
    return cmocka_run_group_tests(tests, cli_setup, teardown);
}
