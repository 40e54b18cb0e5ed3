/* SPDX-License-Identifier: BSD-3-Clause */
/* test_report.c — a golden check of `dynkit report --json` (and the text report) against
 * an independent implementation of the homework's MATLAB code: Integrate_Euler /
 * Integrate_ModifiedEuler / Integrate_RungeKutta4 loops, vanderpoldemo,
 * plane_equationsofmotion with R = R_phi R_theta R_psi, cart_equationsofmotion with the l/2
 * fix, inversedynamics_cart. Source: the homework text (seeds/000_15c6a7b0ccf1c4bd.txt) and
 * the readings of its damaged passages in DESIGN.md ("Seed text", "Plane run length").
 *
 * Nothing here calls the library for the physics: the integrators, right-hand sides,
 * rotation matrices and the cart's 3x3 solve (Cramer's rule) are written out again the way
 * the MATLAB code does it (explicit loops over tout = t0:Ts:tend, matrices as 2D arrays).
 * The report is read from the CLI (popen) and parsed with the small JSON reader below.
 *
 * What is compared, and how tightly:
 * - pendulum (1a, 1c, 1e): closed forms and one Euler step to 1e-12, the nonlinear solution
 *   (RK4 at h = 1e-5 s here) to 1e-10, relative;
 * - van der Pol (2): Euler and modified Euler to 1e-15 (the same arithmetic, y + h k and
 *   y + 0.5 h (k2 + k1)), RK4 to 1e-12, relative;
 * - plane (3): RK4 at 0.01 s over 5 s, the 12 final states to 1e-8 (relative, absolute
 *   below 1). The Euler run at this step is chaotic with respect to rounding, so its final
 *   state is not compared; instead: the report's distance and principal angle follow from its
 *   own final_euler / final_rk4 arrays, and this file's Euler run lands inside (or within
 *   20 % of the width of) the spread the report gives for them;
 * - cart (4): dsY(0), the final forces of the inverse dynamics, the forward run with modified
 *   Euler and the force table held at index round(t/Ts), the largest rear-axle constraint
 *   force over that run, the friction limit and the slip verdict.
 */
#define _POSIX_C_SOURCE 200809L /* popen */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "test_cli_run.h" /* running the binary only: nothing of the library */

#define PI 3.14159265358979323846

/* ======================================================================================
 * A small reader for the report's flat JSON object: string keys mapped to a number, an
 * array of numbers, a boolean, a string or null. Anything else (nesting) is a parse error.
 * ====================================================================================== */

#define JSON_MAX_KEYS 200
#define JSON_MAX_ARRAY 64

typedef enum { J_NUMBER, J_ARRAY, J_BOOL, J_STRING, J_NULL } json_type;

typedef struct json_entry {
    char key[96];
    json_type type;
    double number;              /* J_NUMBER */
    int boolean;                /* J_BOOL */
    int len;                    /* J_ARRAY: number of elements */
    double arr[JSON_MAX_ARRAY]; /* J_ARRAY: the elements (null -> NaN) */
    int array_has_null;         /* J_ARRAY: some element was null */
} json_entry;

typedef struct json_doc {
    int n;
    json_entry e[JSON_MAX_KEYS];
} json_doc;

static const char *type_name(json_type t)
{
    static const char *const names[] = {"number", "array", "boolean", "string", "null"};
    return names[t];
}

static const char *skip_ws(const char *p)
{
    while (*p && isspace((unsigned char)*p))
        p++;
    return p;
}

/* p at '"'; copies the string (escapes reduced to the escaped character) into out. */
static const char *parse_string(const char *p, char *out, size_t cap)
{
    size_t k = 0;
    if (*p != '"')
        return NULL;
    p++;
    while (*p && *p != '"') {
        char c = *p++;
        if (c == '\\') {
            if (!*p)
                return NULL;
            c = *p++;
        }
        if (k + 1 >= cap)
            return NULL;
        out[k++] = c;
    }
    if (*p != '"')
        return NULL;
    out[k] = '\0';
    return p + 1;
}

/* A JSON number (not NaN/Inf/hex, which strtod would also accept). */
static const char *parse_number(const char *p, double *v)
{
    if (!(*p == '-' || isdigit((unsigned char)*p)))
        return NULL;
    char *end;
    *v = strtod(p, &end);
    return end == p ? NULL : end;
}

static const char *parse_literal(const char *p, const char *word)
{
    size_t n = strlen(word);
    return strncmp(p, word, n) == 0 ? p + n : NULL;
}

static const char *parse_value(const char *p, json_entry *e)
{
    p = skip_ws(p);
    if (*p == '"') {
        char buf[256];
        e->type = J_STRING;
        return parse_string(p, buf, sizeof buf);
    }
    if (*p == 't' || *p == 'f') {
        e->type = J_BOOL;
        e->boolean = *p == 't';
        return parse_literal(p, *p == 't' ? "true" : "false");
    }
    if (*p == 'n') {
        e->type = J_NULL;
        return parse_literal(p, "null");
    }
    if (*p == '[') {
        e->type = J_ARRAY;
        e->len = 0;
        p = skip_ws(p + 1);
        if (*p == ']')
            return p + 1;
        for (;;) {
            double v;
            p = skip_ws(p);
            if (*p == 'n') {
                p = parse_literal(p, "null");
                v = NAN;
                e->array_has_null = 1;
            } else {
                p = parse_number(p, &v);
            }
            if (!p || e->len >= JSON_MAX_ARRAY)
                return NULL;
            e->arr[e->len++] = v;
            p = skip_ws(p);
            if (*p == ']')
                return p + 1;
            if (*p != ',')
                return NULL;
            p++;
        }
    }
    e->type = J_NUMBER;
    return parse_number(p, &e->number);
}

/* 0 on success; -1 on a syntax error, a nested value, a duplicate key or too many keys. */
static int json_parse(const char *text, json_doc *doc)
{
    const char *p = skip_ws(text);
    doc->n = 0;
    if (*p++ != '{')
        return -1;
    p = skip_ws(p);
    if (*p == '}')
        return *skip_ws(p + 1) ? -1 : 0;
    for (;;) {
        if (doc->n >= JSON_MAX_KEYS)
            return -1;
        json_entry *e = &doc->e[doc->n];
        memset(e, 0, sizeof *e);
        p = parse_string(skip_ws(p), e->key, sizeof e->key);
        if (!p)
            return -1;
        for (int i = 0; i < doc->n; i++)
            if (strcmp(doc->e[i].key, e->key) == 0)
                return -1;
        p = skip_ws(p);
        if (*p++ != ':')
            return -1;
        p = parse_value(p, e);
        if (!p)
            return -1;
        doc->n++;
        p = skip_ws(p);
        if (*p == '}')
            return *skip_ws(p + 1) ? -1 : 0;
        if (*p++ != ',')
            return -1;
    }
}

static const json_entry *json_find(const json_doc *doc, const char *key)
{
    for (int i = 0; i < doc->n; i++)
        if (strcmp(doc->e[i].key, key) == 0)
            return &doc->e[i];
    return NULL;
}

/* The entry for key, which must exist with the given type (and length, for arrays). */
static const json_entry *json_get(const json_doc *doc, const char *key, json_type type, int len)
{
    const json_entry *e = json_find(doc, key);
    if (!e) {
        print_error("report key '%s' is missing\n", key);
        fail();
    }
    if (e->type != type) {
        print_error("report key '%s' is a %s, expected a %s\n", key, type_name(e->type),
                    type_name(type));
        fail();
    }
    if (type == J_ARRAY && (e->len != len || e->array_has_null)) {
        print_error("report key '%s' has %d elements%s, expected %d numbers\n", key, e->len,
                    e->array_has_null ? " (some null)" : "", len);
        fail();
    }
    if (type == J_NUMBER && !isfinite(e->number)) {
        print_error("report key '%s' is not a finite number\n", key);
        fail();
    }
    return e;
}

static double json_number(const json_doc *doc, const char *key)
{
    return json_get(doc, key, J_NUMBER, 0)->number;
}

static const double *json_array(const json_doc *doc, const char *key, int len)
{
    return json_get(doc, key, J_ARRAY, len)->arr;
}

/* ---- comparisons: print every one (report, independent, difference), fail at the end ---- */

typedef struct tally {
    int failures;
} tally;

/* |report - mine| <= rtol * max(|report|, |mine|) + atol. */
static void compare(tally *t, const char *what, double report, double mine, double rtol,
                    double atol)
{
    double diff = fabs(report - mine);
    double scale = fmax(fabs(report), fabs(mine));
    int ok = diff <= rtol * scale + atol;
    double rel = scale > 0 ? diff / scale : 0.0;
    printf("  %-34s report % .17g  independent % .17g  diff %.3g (rel %.3g)%s\n", what, report,
           mine, diff, rel, ok ? "" : "   <-- MISMATCH");
    if (!ok)
        t->failures++;
}

static void compare_vec(tally *t, const char *key, const double *report, const double *mine, int n,
                        double rtol, double atol)
{
    for (int i = 0; i < n; i++) {
        char what[128];
        snprintf(what, sizeof what, "%s[%d]", key, i);
        compare(t, what, report[i], mine[i], rtol, atol);
    }
}

static void expect(tally *t, int cond, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("  %s ", cond ? "ok:      " : "FAILED:  ");
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
    if (!cond)
        t->failures++;
}

static void tally_done(const tally *t)
{
    fflush(stdout);
    assert_int_equal(t->failures, 0);
}

/* ======================================================================================
 * The homework's integrators, as the MATLAB functions do it: tout = t0:Ts:tend, and for
 * each sample n: store y_n, then compute y_{n+1}. The MATLAB loop also computes one step
 * past tend that it never stores; here the loop stops at the last sample instead (the cart's
 * force table has no row for t = tend + Ts).
 * ====================================================================================== */

#define MAX_STATES 12

/* odefun(t, y, dy, par): dy/dt of the n states. */
typedef void (*odefun)(double t, const double *y, double *dy, const void *par);

/* Number of samples of tout = t0:Ts:tend (MATLAB's colon, with its tolerance). */
static long num_samples(double t0, double tend, double Ts)
{
    return (long)floor((tend - t0) / Ts + 1e-10) + 1;
}

/* Each fills yout (numsamples x n, row-major) with the states at tout(k) = t0 + k Ts. */
static void Integrate_Euler(odefun f, double t0, double tend, double Ts, const double *y0, int n,
                            const void *par, double *yout)
{
    long numsamples = num_samples(t0, tend, Ts);
    double y_n[MAX_STATES], dy_n[MAX_STATES];
    memcpy(y_n, y0, (size_t)n * sizeof *y0);
    for (long k = 0; k < numsamples; k++) {
        double t_n = t0 + (double)k * Ts;
        memcpy(&yout[k * n], y_n, (size_t)n * sizeof *y_n);
        if (k == numsamples - 1)
            break;
        f(t_n, y_n, dy_n, par);
        for (int i = 0; i < n; i++)
            y_n[i] = y_n[i] + Ts * dy_n[i];
    }
}

static void Integrate_ModifiedEuler(odefun f, double t0, double tend, double Ts, const double *y0,
                                    int n, const void *par, double *yout)
{
    long numsamples = num_samples(t0, tend, Ts);
    double y_n[MAX_STATES], dy_n[MAX_STATES], ytilde[MAX_STATES], dytilde[MAX_STATES];
    memcpy(y_n, y0, (size_t)n * sizeof *y0);
    for (long k = 0; k < numsamples; k++) {
        double t_n = t0 + (double)k * Ts;
        double t_nplus1 = t_n + Ts;
        memcpy(&yout[k * n], y_n, (size_t)n * sizeof *y_n);
        if (k == numsamples - 1)
            break;
        /* (1) derivative, (2) predictor, (3) derivative of the prediction, (4) correction */
        f(t_n, y_n, dy_n, par);
        for (int i = 0; i < n; i++)
            ytilde[i] = y_n[i] + Ts * dy_n[i];
        f(t_nplus1, ytilde, dytilde, par);
        for (int i = 0; i < n; i++)
            y_n[i] = y_n[i] + .5 * Ts * (dytilde[i] + dy_n[i]);
    }
}

static void Integrate_RungeKutta4(odefun f, double t0, double tend, double Ts, const double *y0,
                                  int n, const void *par, double *yout)
{
    long numsamples = num_samples(t0, tend, Ts);
    double y_n[MAX_STATES], k1[MAX_STATES], k2[MAX_STATES], k3[MAX_STATES], k4[MAX_STATES];
    double ytmp[MAX_STATES];
    memcpy(y_n, y0, (size_t)n * sizeof *y0);
    for (long k = 0; k < numsamples; k++) {
        double t_n = t0 + (double)k * Ts;
        memcpy(&yout[k * n], y_n, (size_t)n * sizeof *y_n);
        if (k == numsamples - 1)
            break;
        f(t_n, y_n, k1, par);
        for (int i = 0; i < n; i++)
            ytmp[i] = y_n[i] + Ts / 2 * k1[i];
        f(t_n + Ts / 2, ytmp, k2, par);
        for (int i = 0; i < n; i++)
            ytmp[i] = y_n[i] + Ts / 2 * k2[i];
        f(t_n + Ts / 2, ytmp, k3, par);
        for (int i = 0; i < n; i++)
            ytmp[i] = y_n[i] + Ts * k3[i];
        f(t_n + Ts, ytmp, k4, par);
        for (int i = 0; i < n; i++)
            y_n[i] = y_n[i] + Ts / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
}

typedef void (*integrator)(odefun, double, double, double, const double *, int, const void *,
                           double *);

/* The final state of a run (the last row of yout). */
static void final_state(integrator method, odefun f, double t0, double tend, double Ts,
                        const double *y0, int n, const void *par, double *yfinal)
{
    long numsamples = num_samples(t0, tend, Ts);
    double *yout = malloc((size_t)numsamples * (size_t)n * sizeof *yout);
    assert_non_null(yout);
    method(f, t0, tend, Ts, y0, n, par, yout);
    memcpy(yfinal, &yout[(numsamples - 1) * n], (size_t)n * sizeof *yfinal);
    free(yout);
}

/* ======================================================================================
 * The report, read once for all tests.
 * ====================================================================================== */

static int setup_report(void **state)
{
    int status;
    char *text = cli_capture("'" DYNKIT_CLI "' report --json 2>/dev/null", &status);
    json_doc *doc = calloc(1, sizeof *doc);
    if (!doc || status != 0 || json_parse(text, doc) != 0) {
        fprintf(stderr, "dynkit report --json: exit status %d, %s\n%s\n", status,
                doc ? "output not a flat JSON object" : "out of memory", text);
        free(text);
        free(doc);
        return -1;
    }
    free(text);
    *state = doc;
    return 0;
}

static int teardown_report(void **state)
{
    free(*state);
    return 0;
}

/* ---- every key of the design, with its type ---- */

static void test_keys_and_types(void **state)
{
    const json_doc *doc = *state;
    static const char *const numbers[] = {
        "pendulum.max_height_m",
        "pendulum.phi_small_angle_rad",
        "pendulum.phi_euler_rad",
        "pendulum.phi_nonlinear_rad",
        "plane.step_s",
        "plane.end_time_s",
        "plane.distance_m",
        "plane.principal_angle_rad",
        "cart.initial_dsY_mps",
        "cart.final_Fx_N",
        "cart.final_Fy_N",
        "cart.forward_error_sX_m",
        "cart.max_constraint_force_N",
        "cart.friction_limit_N",
    };
    static const struct {
        const char *key;
        int len;
    } arrays[] = {
        {"vanderpol.euler", 2},    {"vanderpol.modified_euler", 2}, {"vanderpol.rk4", 2},
        {"plane.final_euler", 12}, {"plane.final_rk4", 12},
    };
    for (size_t i = 0; i < sizeof numbers / sizeof *numbers; i++)
        json_get(doc, numbers[i], J_NUMBER, 0);
    for (size_t i = 0; i < sizeof arrays / sizeof *arrays; i++)
        json_get(doc, arrays[i].key, J_ARRAY, arrays[i].len);
    json_get(doc, "cart.rear_wheels_slip", J_BOOL, 0);
}

/* ======================================================================================
 * Problem 1: pendulum, m = 2 kg, l = 9.81 m, g = 9.81 m/s^2, phi(0) = 0, dphi(0) = pi/2.
 * ====================================================================================== */

typedef struct pendulum_par {
    double g, l;
} pendulum_par;

/* x = (phi, dphi): ddphi = -(g/l) sin(phi). */
static void pendulum_equationsofmotion(double t, const double *x, double *dx, const void *p)
{
    const pendulum_par *par = p;
    (void)t;
    dx[0] = x[1];
    dx[1] = -par->g / par->l * sin(x[0]);
}

static void test_pendulum(void **state)
{
    const json_doc *doc = *state;
    tally t = {0};
    const pendulum_par par = {9.81, 9.81};
    const double phi0 = 0.0, dphi0 = PI / 2, te = 0.2;

    /* 1a: 1/2 m (l dphi0)^2 = m g h, unless the mass goes over the top (h = 2 l). */
    double h = (par.l * dphi0) * (par.l * dphi0) / (2 * par.g);
    if (h > 2 * par.l)
        h = 2 * par.l;
    /* 1c: phi(t) = phi0 cos(w t) + dphi0/w sin(w t), w = sqrt(g/l). */
    double w = sqrt(par.g / par.l);
    double phi_small = phi0 * cos(w * te) + dphi0 / w * sin(w * te);
    /* 1e: one Euler step of h = te. */
    double x0[2] = {phi0, dphi0}, dx0[2];
    pendulum_equationsofmotion(0.0, x0, dx0, &par);
    double phi_euler = x0[0] + te * dx0[0];
    /* the nonlinear solution: RK4 with a tiny step */
    double xe[2];
    final_state(Integrate_RungeKutta4, pendulum_equationsofmotion, 0.0, te, 1e-5, x0, 2, &par, xe);

    printf("problem 1 (pendulum)\n");
    compare(&t, "pendulum.max_height_m", json_number(doc, "pendulum.max_height_m"), h, 1e-12, 0);
    compare(&t, "pendulum.phi_small_angle_rad", json_number(doc, "pendulum.phi_small_angle_rad"),
            phi_small, 1e-12, 0);
    compare(&t, "pendulum.phi_euler_rad", json_number(doc, "pendulum.phi_euler_rad"), phi_euler,
            1e-12, 0);
    compare(&t, "pendulum.phi_nonlinear_rad", json_number(doc, "pendulum.phi_nonlinear_rad"), xe[0],
            1e-10, 0);
    tally_done(&t);
}

/* ======================================================================================
 * Problem 2: van der Pol, mu = 1, y0 = (2, 0), [0 15] at Ts = 0.01 (1500 steps).
 * ====================================================================================== */

/* vanderpoldemo: dy = [y2; mu (1 - y1^2) y2 - y1]. */
static void vanderpoldemo(double t, const double *y, double *dy, const void *p)
{
    const double Mu = *(const double *)p;
    (void)t;
    dy[0] = y[1];
    dy[1] = Mu * (1 - y[0] * y[0]) * y[1] - y[0];
}

static void test_vanderpol(void **state)
{
    const json_doc *doc = *state;
    tally t = {0};
    const double mu = 1.0, y0[2] = {2, 0};
    double ye[2], yme[2], yrk[2];
    final_state(Integrate_Euler, vanderpoldemo, 0, 15, 0.01, y0, 2, &mu, ye);
    final_state(Integrate_ModifiedEuler, vanderpoldemo, 0, 15, 0.01, y0, 2, &mu, yme);
    final_state(Integrate_RungeKutta4, vanderpoldemo, 0, 15, 0.01, y0, 2, &mu, yrk);
    assert_int_equal(num_samples(0, 15, 0.01), 1501);

    printf("problem 2 (van der Pol)\n");
    compare_vec(&t, "vanderpol.euler", json_array(doc, "vanderpol.euler", 2), ye, 2, 1e-15, 0);
    compare_vec(&t, "vanderpol.modified_euler", json_array(doc, "vanderpol.modified_euler", 2), yme,
                2, 1e-15, 0);
    compare_vec(&t, "vanderpol.rk4", json_array(doc, "vanderpol.rk4", 2), yrk, 2, 1e-12, 0);
    tally_done(&t);
}

/* ======================================================================================
 * Problem 3: the model plane on a spring (plane_equationsofmotion and simulate_plane.m).
 * ====================================================================================== */

typedef struct plane_par {
    double g, l0, k, m, Ixx, Iyy, Izz;
    double rp_B[3];
} plane_par;

static plane_par plane_parameters(void)
{
    plane_par par;
    double Ip = 1 * .1 * .1; /* kg m^2 */
    par.g = 9.81;
    par.Ixx = .5 * Ip;
    par.Iyy = .5 * Ip;
    par.Izz = Ip;
    par.m = 1;
    par.rp_B[0] = .1; /* px */
    par.rp_B[1] = 0;
    par.rp_B[2] = -.1; /* pz */
    par.l0 = 1;
    par.k = 20;
    return par;
}

/* x0 of simulate_plane.m. */
static void plane_initial_state(const plane_par *par, double x0[12])
{
    memset(x0, 0, 12 * sizeof *x0);
    x0[0] = -par->rp_B[0];                      /* sX = -px */
    x0[1] = .2;                                 /* sY */
    x0[2] = par->l0 + par->m * par->g / par->k; /* sZ */
    x0[6] = 2;                                  /* dsX */
    x0[11] = PI / 4 / 10;                       /* omegaz */
}

static void matmul3(double A[3][3], double B[3][3], double C[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            C[i][j] = 0;
            for (int k = 0; k < 3; k++)
                C[i][j] += A[i][k] * B[k][j];
        }
}

/* R_total = R_phi R_theta R_psi: maps N-frame coordinates to B-frame coordinates. */
static void rotation_matrix(double psi, double theta, double phi, double R[3][3])
{
    double R_psi[3][3] = {{cos(psi), sin(psi), 0}, {-sin(psi), cos(psi), 0}, {0, 0, 1}};
    double R_theta[3][3] = {{cos(theta), 0, -sin(theta)}, {0, 1, 0}, {sin(theta), 0, cos(theta)}};
    double R_phi[3][3] = {{1, 0, 0}, {0, cos(phi), sin(phi)}, {0, -sin(phi), cos(phi)}};
    double tmp[3][3];
    matmul3(R_phi, R_theta, tmp);
    matmul3(tmp, R_psi, R);
}

static void plane_equationsofmotion(double t, const double *x, double *dx, const void *p)
{
    const plane_par *par = p;
    (void)t;
    double sX = x[0], sY = x[1], sZ = x[2];
    double psi = x[3], theta = x[4], phi = x[5];
    double dsX = x[6], dsY = x[7], dsZ = x[8];
    double omegax = x[9], omegay = x[10], omegaz = x[11];
    double rs_N[3] = {sX, sY, sZ};

    double R_total[3][3];
    rotation_matrix(psi, theta, phi, R_total);

    /* position vector of P in the N frame: rs_N + R_total' rp_B */
    double rp_N[3];
    for (int i = 0; i < 3; i++) {
        rp_N[i] = rs_N[i];
        for (int j = 0; j < 3; j++)
            rp_N[i] += R_total[j][i] * par->rp_B[j];
    }
    /* spring from the ceiling origin A to P */
    double len = sqrt(rp_N[0] * rp_N[0] + rp_N[1] * rp_N[1] + rp_N[2] * rp_N[2]);
    double Fspring_N[3], Ftot_N[3];
    double Fg_N[3] = {0, 0, par->m * par->g};
    for (int i = 0; i < 3; i++) {
        Fspring_N[i] = -par->k * (len - par->l0) * rp_N[i] / len;
        Ftot_N[i] = Fspring_N[i] + Fg_N[i];
    }
    double Fspring_B[3];
    for (int i = 0; i < 3; i++) {
        Fspring_B[i] = 0;
        for (int j = 0; j < 3; j++)
            Fspring_B[i] += R_total[i][j] * Fspring_N[j];
    }
    /* moment of the spring about S, in the body frame: rp_B x Fspring_B */
    const double *r = par->rp_B;
    double Mx = r[1] * Fspring_B[2] - r[2] * Fspring_B[1];
    double My = r[2] * Fspring_B[0] - r[0] * Fspring_B[2];
    double Mz = r[0] * Fspring_B[1] - r[1] * Fspring_B[0];

    /* Newton (space-fixed frame) */
    double ddsX = Ftot_N[0] / par->m;
    double ddsY = Ftot_N[1] / par->m;
    double ddsZ = Ftot_N[2] / par->m;
    /* Euler (body-fixed principal axes) */
    double domegax = (Mx - (par->Izz - par->Iyy) * omegay * omegaz) / par->Ixx;
    double domegay = (My - (par->Ixx - par->Izz) * omegaz * omegax) / par->Iyy;
    double domegaz = (Mz - (par->Iyy - par->Ixx) * omegax * omegay) / par->Izz;
    /* Euler angle derivatives, Greenwood (3.16) */
    double dpsi = 1 / cos(theta) * (omegay * sin(phi) + omegaz * cos(phi));
    double dtheta = omegay * cos(phi) - omegaz * sin(phi);
    double dphi = omegax + dpsi * sin(theta);

    double out[12] = {dsX,  dsY,  dsZ,  dpsi,    dtheta,  dphi,
                      ddsX, ddsY, ddsZ, domegax, domegay, domegaz};
    memcpy(dx, out, sizeof out);
}

/* Principal angle of the rotation R(e1) R(e2)^T, from its trace. */
static double principal_angle(const double *e1, const double *e2)
{
    double R1[3][3], R2[3][3];
    rotation_matrix(e1[0], e1[1], e1[2], R1);
    rotation_matrix(e2[0], e2[1], e2[2], R2);
    double trace = 0;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            trace += R1[i][k] * R2[i][k]; /* (R1 R2')_ii */
    double c = (trace - 1) / 2;
    c = c > 1 ? 1 : (c < -1 ? -1 : c);
    return acos(c);
}

static double distance3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static void test_plane_rk4(void **state)
{
    const json_doc *doc = *state;
    tally t = {0};
    const double Ts = .01, endtime = 5;
    plane_par par = plane_parameters();
    double x0[12], xrk[12];
    plane_initial_state(&par, x0);
    final_state(Integrate_RungeKutta4, plane_equationsofmotion, 0, endtime, Ts, x0, 12, &par, xrk);
    assert_int_equal(num_samples(0, endtime, Ts), 501);

    printf("problem 3 (plane), RK4\n");
    compare(&t, "plane.step_s", json_number(doc, "plane.step_s"), Ts, 0, 0);
    compare(&t, "plane.end_time_s", json_number(doc, "plane.end_time_s"), endtime, 0, 0);
    compare_vec(&t, "plane.final_rk4", json_array(doc, "plane.final_rk4", 12), xrk, 12, 1e-8, 1e-8);
    tally_done(&t);
}

static void test_plane_euler(void **state)
{
    const json_doc *doc = *state;
    tally t = {0};
    plane_par par = plane_parameters();
    double x0[12], xeu[12];
    plane_initial_state(&par, x0);
    final_state(Integrate_Euler, plane_equationsofmotion, 0, 5, .01, x0, 12, &par, xeu);

    const double *rep_eu = json_array(doc, "plane.final_euler", 12);
    const double *rep_rk = json_array(doc, "plane.final_rk4", 12);
    const double *dspread = json_array(doc, "plane.distance_spread_m", 2);
    const double *aspread = json_array(doc, "plane.principal_angle_spread_rad", 2);
    double rep_dist = json_number(doc, "plane.distance_m");
    double rep_angle = json_number(doc, "plane.principal_angle_rad");

    printf("problem 3 (plane), Euler (chaotic with respect to rounding: consistency only)\n");
    /* the report's two answers follow from its own final states */
    compare(&t, "plane.distance_m vs its arrays", rep_dist, distance3(rep_eu, rep_rk), 1e-12, 0);
    compare(&t, "plane.principal_angle_rad vs arrays", rep_angle,
            principal_angle(&rep_eu[3], &rep_rk[3]), 1e-6, 0);

    /* this file's Euler run against the report's RK4 final state, within the spread */
    double my_dist = distance3(xeu, rep_rk);
    double my_angle = principal_angle(&xeu[3], &rep_rk[3]);
    double dslack = 0.2 * (dspread[1] - dspread[0]);
    double aslack = 0.2 * (aspread[1] - aspread[0]);
    printf("  independent Euler final state:");
    for (int i = 0; i < 12; i++)
        printf(" %.6g", xeu[i]);
    printf("\n");
    expect(&t, dspread[0] <= dspread[1] && dspread[0] >= 0,
           "distance spread [%.6g, %.6g] m is an interval", dspread[0], dspread[1]);
    expect(&t, aspread[0] <= aspread[1] && aspread[0] >= 0 && aspread[1] <= PI + 1e-12,
           "angle spread [%.6g, %.6g] rad is an interval in [0, pi]", aspread[0], aspread[1]);
    expect(&t, rep_dist >= dspread[0] - dslack && rep_dist <= dspread[1] + dslack,
           "report distance %.6g m near its spread", rep_dist);
    expect(&t, rep_angle >= aspread[0] - aslack && rep_angle <= aspread[1] + aslack,
           "report angle %.6g rad near its spread", rep_angle);
    expect(&t, my_dist >= dspread[0] - dslack && my_dist <= dspread[1] + dslack,
           "independent Euler distance %.6g m in [%.6g, %.6g] (spread +- 20%%)", my_dist,
           dspread[0] - dslack, dspread[1] + dslack);
    expect(&t, my_angle >= aspread[0] - aslack && my_angle <= aspread[1] + aslack,
           "independent Euler principal angle %.6g rad in [%.6g, %.6g] (spread +- 20%%)", my_angle,
           aspread[0] - aslack, aspread[1] + aslack);
    tally_done(&t);
}

/* ======================================================================================
 * Problem 4: the three-wheeled cart (simulate_cart.m, cart_equationsofmotion.m with the
 * third row of A read as [sin(theta) -cos(theta) l/2], inversedynamics_cart.m).
 * ====================================================================================== */

#define CART_N 500

typedef struct cart_par {
    double m, Is, length_cart, width_cart;
    double Ts;
    double F[CART_N][2]; /* the force table (Fx, Fy) at t = (row) Ts */
} cart_par;

static double det3(double A[3][3])
{
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
           A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

/* ddq = A \ b by Cramer's rule. */
static void solve3(double A[3][3], const double b[3], double ddq[3])
{
    double D = det3(A);
    for (int c = 0; c < 3; c++) {
        double Ac[3][3];
        memcpy(Ac, A, sizeof Ac);
        for (int r = 0; r < 3; r++)
            Ac[r][c] = b[r];
        ddq[c] = det3(Ac) / D;
    }
}

/* The forces of the table at time t, held at the nearest sample (index = round(t/Ts)). */
static void cart_forces(const cart_par *par, double t, double *Fx, double *Fy)
{
    long index = lround(t / par->Ts);
    assert_true(index >= 0 && index < CART_N);
    *Fx = par->F[index][0];
    *Fy = par->F[index][1];
}

static void cart_equationsofmotion(double t, const double *x, double *dx, const void *p)
{
    const cart_par *par = p;
    double m = par->m, Is = par->Is, l = par->length_cart;
    double theta = x[2], dsX = x[3], dsY = x[4], omega = x[5];
    double Fx, Fy;
    cart_forces(par, t, &Fx, &Fy);
    double A[3][3] = {{m, 0, -2 * Is / l * sin(theta)},
                      {0, m, 2 * Is / l * cos(theta)},
                      {sin(theta), -cos(theta), l / 2}};
    double b[3] = {Fx * cos(theta) - 2 * Fy * sin(theta), Fx * sin(theta) + 2 * Fy * cos(theta),
                   -dsX * omega * cos(theta) - dsY * omega * sin(theta)};
    double ddq[3];
    solve3(A, b, ddq);
    dx[0] = dsX;
    dx[1] = dsY;
    dx[2] = omega;
    dx[3] = ddq[0];
    dx[4] = ddq[1];
    dx[5] = ddq[2];
}

/* Rows 1 and 2 of A ddq = b solved for Fx, Fy: (row 1) cos + (row 2) sin gives
 * m (ddsX cos + ddsY sin) = Fx; -(row 1) sin + (row 2) cos gives
 * m (-ddsX sin + ddsY cos) + 2 Is/l domega = 2 Fy. */
static void inversedynamics_cart(double theta, double ddsX, double ddsY, double domega,
                                 const cart_par *par, double *Fx, double *Fy)
{
    double m = par->m, Is = par->Is, l = par->length_cart;
    *Fx = m * (ddsX * cos(theta) + ddsY * sin(theta));
    *Fy = (m * (-ddsX * sin(theta) + ddsY * cos(theta)) + 2 * Is / l * domega) / 2;
}

/* The prescribed motion sX = -v0 t, theta = pi/8 sin(2 pi f t), with sY following from
 * the constraint dsY cos(theta) - dsX sin(theta) = (l/2) omega. */
typedef struct cart_motion {
    double theta, omega, domega, dsX, ddsX, dsY, ddsY;
} cart_motion;

static cart_motion prescribed_motion(double t, double v0, double f, double l)
{
    cart_motion s;
    double a = PI / 8, w = 2 * PI * f;
    s.theta = a * sin(w * t);
    s.omega = a * w * cos(w * t);
    s.domega = -a * w * w * sin(w * t);
    s.dsX = -v0;
    s.ddsX = 0;
    /* dsY = num / cos(theta), num = (l/2) omega + dsX sin(theta); quotient rule */
    double num = l / 2 * s.omega + s.dsX * sin(s.theta);
    double dnum = l / 2 * s.domega + s.ddsX * sin(s.theta) + s.dsX * cos(s.theta) * s.omega;
    double c = cos(s.theta);
    s.dsY = num / c;
    s.ddsY = (dnum * c + num * sin(s.theta) * s.omega) / (c * c);
    return s;
}

static void test_cart(void **state)
{
    const json_doc *doc = *state;
    tally t = {0};
    static cart_par par; /* the force table is large-ish */
    par.length_cart = 2;
    par.width_cart = 1;
    par.m = 20;
    par.Is = par.m * 1 / 12 * (par.length_cart * par.length_cart + par.width_cart * par.width_cart);
    par.Ts = .01;
    const double v0 = 20, f = 2, Ts = par.Ts, l = par.length_cart;
    const int N = CART_N;
    const double te = (N - 1) * Ts;

    /* 4a: initial conditions; dsY(0) from the constraint */
    cart_motion s0 = prescribed_motion(0, v0, f, l);
    double x0[6] = {0, 0, s0.theta, s0.dsX, 0, s0.omega};
    x0[4] = (l / 2 * x0[5] + x0[3] * sin(x0[2])) / cos(x0[2]);

    /* 4b: the force table from the inverse dynamics at N samples */
    for (int k = 0; k < N; k++) {
        cart_motion s = prescribed_motion(k * Ts, v0, f, l);
        inversedynamics_cart(s.theta, s.ddsX, s.ddsY, s.domega, &par, &par.F[k][0], &par.F[k][1]);
    }

    /* 4c: forward run with modified Euler over the N samples */
    double(*y)[6] = malloc(sizeof(double[CART_N][6]));
    assert_non_null(y);
    assert_int_equal(num_samples(0, te, Ts), N);
    Integrate_ModifiedEuler(cart_equationsofmotion, 0, te, Ts, x0, 6, &par, &y[0][0]);
    double error_sX = fabs(y[N - 1][0] - (-v0 * te));

    /* 4d: lambda = Fy - 2 Is domega / l at each sample of the forward run */
    double max_lambda = 0;
    for (int k = 0; k < N; k++) {
        double dx[6], tk = k * Ts;
        cart_equationsofmotion(tk, y[k], dx, &par);
        double lambda = par.F[k][1] - 2 * par.Is * dx[5] / l;
        if (fabs(lambda) > max_lambda)
            max_lambda = fabs(lambda);
    }
    double mu = 0.7, g = 9.81;
    double friction_limit = mu * (2.0 / 3.0) * par.m * g;

    printf("problem 4 (cart)\n");
    compare(&t, "cart.initial_dsY_mps", json_number(doc, "cart.initial_dsY_mps"), x0[4], 1e-12, 0);
    compare(&t, "  (= pi^2/2)", json_number(doc, "cart.initial_dsY_mps"), PI * PI / 2, 1e-12, 0);
    compare(&t, "cart.final_Fx_N", json_number(doc, "cart.final_Fx_N"), par.F[N - 1][0], 1e-9, 0);
    compare(&t, "cart.final_Fy_N", json_number(doc, "cart.final_Fy_N"), par.F[N - 1][1], 1e-9, 0);
    compare(&t, "cart.forward_error_sX_m", json_number(doc, "cart.forward_error_sX_m"), error_sX,
            1e-6, 0);
    compare(&t, "cart.max_constraint_force_N", json_number(doc, "cart.max_constraint_force_N"),
            max_lambda, 1e-6, 0);
    compare(&t, "cart.friction_limit_N", json_number(doc, "cart.friction_limit_N"), friction_limit,
            1e-12, 0);
    int slip = json_get(doc, "cart.rear_wheels_slip", J_BOOL, 0)->boolean;
    expect(&t,
           slip == (json_number(doc, "cart.max_constraint_force_N") >
                    json_number(doc, "cart.friction_limit_N")),
           "cart.rear_wheels_slip = %s, consistent with max |lambda| vs the friction limit",
           slip ? "true" : "false");
    expect(&t, slip == (max_lambda > friction_limit),
           "cart.rear_wheels_slip = %s, as independently (%.6g N vs %.6g N)",
           slip ? "true" : "false", max_lambda, friction_limit);
    free(y);
    tally_done(&t);
}

/* ======================================================================================
 * The text report and the usage error.
 * ====================================================================================== */

/* 1 if some line of text starts (after blanks) with label followed by a non-alphanumeric
 * character, or text has "Problem <label>" with nothing alphanumeric after the label. */
static int mentions(const char *text, const char *label)
{
    size_t n = strlen(label);
    const char *line = text;
    while (*line) {
        const char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncmp(p, label, n) == 0 && !isalnum((unsigned char)p[n]))
            return 1;
        if (strncmp(p, "Problem ", 8) == 0 && strncmp(p + 8, label, n) == 0 &&
            !isalnum((unsigned char)p[8 + n]))
            return 1;
        const char *nl = strchr(line, '\n');
        if (!nl)
            break;
        line = nl + 1;
    }
    return 0;
}

static void test_text_report(void **state)
{
    (void)state;
    int status;
    char *text = cli_capture("'" DYNKIT_CLI "' report 2>/dev/null", &status);
    assert_int_equal(status, 0);
    static const char *const labels[] = {"1a", "1b", "1c", "1d", "1e", "1f",
                                         "2",  "3",  "4a", "4b", "4c", "4d"};
    for (size_t i = 0; i < sizeof labels / sizeof *labels; i++) {
        if (!mentions(text, labels[i])) {
            print_error("the text report does not mention problem %s\n", labels[i]);
            free(text);
            fail();
        }
    }
    free(text);
}

static void test_bogus_option(void **state)
{
    (void)state;
    int status;
    char *out = cli_capture("'" DYNKIT_CLI "' report --bogus 2>/dev/null", &status);
    assert_int_equal(status, 2);
    assert_string_equal(out, ""); /* nothing on stdout: the message goes to stderr */
    free(out);
    out = cli_capture("'" DYNKIT_CLI "' report --bogus 2>&1 >/dev/null", &status);
    assert_int_equal(status, 2);
    assert_non_null(strstr(out, "--bogus"));
    free(out);
}

/* The studies of many runs: --no-studies leaves them out (the help's example), --threads
 * changes no number (only the line with the studies' time), a bad --threads is refused. */
static void test_studies_options(void **state)
{
    (void)state;
    int status;
    char *alone = cli_capture("'" DYNKIT_CLI "' report --threads 1 --no-studies 2>/dev/null", &status);
    assert_int_equal(status, 0);
    assert_non_null(strstr(alone, " 4d "));
    assert_null(strstr(alone, "Many runs"));
    char *one = cli_capture("'" DYNKIT_CLI "' report --threads 1 | grep -v -e '^(computed in' "
                            "-e '^(the studies of many runs'", &status);
    char *two = cli_capture("'" DYNKIT_CLI "' report --threads 2 | grep -v -e '^(computed in' "
                            "-e '^(the studies of many runs'", &status);
    assert_non_null(strstr(one, "Many runs: the period against the amplitude"));
    assert_non_null(strstr(one, "Many runs: max |lambda|"));
    assert_string_equal(one, two);
    free(alone);
    free(one);
    free(two);
    char *out = cli_capture("'" DYNKIT_CLI "' report --threads 0 2>&1 >/dev/null", &status);
    assert_int_equal(status, 2);
    assert_non_null(strstr(out, "--threads '0'"));
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_keys_and_types), cmocka_unit_test(test_pendulum),
        cmocka_unit_test(test_vanderpol),      cmocka_unit_test(test_plane_rk4),
        cmocka_unit_test(test_plane_euler),    cmocka_unit_test(test_cart),
        cmocka_unit_test(test_text_report),    cmocka_unit_test(test_bogus_option),
        cmocka_unit_test(test_studies_options),
    };
    return cmocka_run_group_tests(tests, setup_report, teardown_report);
}
