/* SPDX-License-Identifier: BSD-3-Clause */
/* family.c — section 2b of the benchmark suite (family.h): right-hand-side calls at equal
 * error over families of problems.
 *
 * The problems: van der Pol with mu = 0.5, 1, 1.5, 2, 3, 4, each from four starts to four
 * ends (24 orbits, no two sharing the beginning of their steps; references in long double
 * by classical RK4 with steps of at most 2e-5, whose error is estimated from the same solve
 * with twice the step, and for mu = 1 from (2, 0) to 15 checked against the library's
 * reference vanderpol-mu1-15); Kepler's problem with e = 0.3, 0.5, 0.7, 0.8, 0.9 over one
 * period (exact: the initial state); the Arenstorf orbit (arenstorf-period). The peers run
 * the van der Pol orbits, dynkit's pairs and their controller settings every problem.
 * Every solver runs each problem at rtol = atol = 1e-1 ... 1e-12, four tolerances per decade;
 * its calls at an error level are read off its front (wp_front.h) on each problem, and a
 * comparison is the geometric mean over the problems of the ratio of calls.
 */
#include "family.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dynkit/problems.h>

#include "wp_front.h"

#define FAM_MAX_PROBLEMS 32
#define FAM_MAX_SOLVERS 40
#define FAM_MAX_TOLS 48
/* the error levels of the targets (issue 12's range); a level enters a target when at least
 * half the orbits reach it on both sides */
#define FAM_TARGET_LO 3
#define FAM_TARGET_HI 12

enum { FAM_VDP, FAM_KEPLER, FAM_ARENSTORF, FAM_NFAMILY };
static const char *const family_names[FAM_NFAMILY] = {"van der Pol", "Kepler", "Arenstorf"};

typedef struct problem {
    bench_sys sys;
    char name[96];
    int family;
    bench_vdp_par vdp;
    bench_arenstorf_par aren;
    double y0[4], ref[4];
} problem;

typedef struct solver_data {
    char label[80];
    int order, is_dynkit, flags;
    int variant_of;   /* index of the default pair it varies, or -1 */
    const char *what; /* the variant's settings */
    int has[FAM_MAX_PROBLEMS];
    double err[FAM_MAX_PROBLEMS][FAM_MAX_TOLS], calls[FAM_MAX_PROBLEMS][FAM_MAX_TOLS];
    int ok[FAM_MAX_PROBLEMS][FAM_MAX_TOLS];
} solver_data;

static problem problems[FAM_MAX_PROBLEMS];
static int n_problems;
static solver_data solvers[FAM_MAX_SOLVERS];
static int n_solvers;
static double tols[FAM_MAX_TOLS];
static int n_tols;
static int n_failed; /* runs that failed, left out of the comparisons */
static char failed_runs[8][200];

/* the controller settings measured against each pair's default */
static const struct {
    const char *method;
    dyn_solve_opts ctl;
    const char *what;
} variants[] = {
    {"bs23", {.safety = 0.9}, "safety 0.9 (SciPy's RK23)"},
    {"dp45", {.safety = 0.9}, "safety 0.9 (dopri5.f)"},
    {"dp45", {.safety = 0.85}, "safety 0.85"},
    {"dp45", {.safety = 0.75}, "safety 0.75"},
    {"dop853", {.safety = 0.9}, "safety 0.9 (dop853.f)"},
    {"dop853", {.safety = 0.8}, "safety 0.8"},
    {"dop853",
     {.safety = 0.9, .beta = -1.0, .fac_min = 0.333, .fac_max = 6.0},
     "dop853.f's I controller (beta 0, safety 0.9, 0.333 .. 6)"},
};

/* ---- the reference solutions of van der Pol ---- */

static void vdp_rhs_ld(long double mu, const long double *y, long double *d)
{
    d[0] = y[1];
    d[1] = mu * (1.0L - y[0] * y[0]) * y[1] - y[0];
}

/* y(t1) by classical RK4 with `steps` equal steps, in long double */
static void vdp_rk4_ld(double mu, const double *y0, double t1, long steps, long double *y)
{
    const long double h = (long double)t1 / (long double)steps, m = mu;
    long double k1[2], k2[2], k3[2], k4[2], z[2];
    y[0] = y0[0];
    y[1] = y0[1];
    for (long s = 0; s < steps; s++) {
        vdp_rhs_ld(m, y, k1);
        for (int i = 0; i < 2; i++)
            z[i] = y[i] + 0.5L * h * k1[i];
        vdp_rhs_ld(m, z, k2);
        for (int i = 0; i < 2; i++)
            z[i] = y[i] + 0.5L * h * k2[i];
        vdp_rhs_ld(m, z, k3);
        for (int i = 0; i < 2; i++)
            z[i] = y[i] + h * k3[i];
        vdp_rhs_ld(m, z, k4);
        for (int i = 0; i < 2; i++)
            y[i] += h / 6.0L * (k1[i] + 2.0L * k2[i] + 2.0L * k3[i] + k4[i]);
    }
}

/* The reference of van der Pol problem p; returns the estimated error of the double result:
 * RK4's error with twice the step is 16 times its own (Richardson), so it is the difference
 * of the two over 15, plus the rounding to double. */
static double vdp_reference(problem *p)
{
    const long steps = 2 * (long)ceil(p->sys.t1 / 4e-5);
    long double fine[2], coarse[2];
    vdp_rk4_ld(p->vdp.mu, p->y0, p->sys.t1, steps, fine);
    vdp_rk4_ld(p->vdp.mu, p->y0, p->sys.t1, steps / 2, coarse);
    double est = 0.0;
    for (int i = 0; i < 2; i++) {
        p->ref[i] = (double)fine[i];
        est = fmax(est, (double)fabsl(fine[i] - coarse[i]) / 15.0 + fabs(p->ref[i]) * 1.2e-16);
    }
    return est;
}

/* ---- the problems ---- */

static problem *add_problem(int family)
{
    problem *p = &problems[n_problems++];
    memset(p, 0, sizeof *p);
    p->family = family;
    return p;
}

static void make_problems(const family_env *env)
{
    /* van der Pol: each mu with four starts and ends, so that no two orbits share the
     * beginning of their steps */
    static const double mus[] = {0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
    static const struct {
        double y0[2], t1;
    } runs[] = {{{2.0, 0.0}, 15.0}, {{0.0, 1.0}, 11.0}, {{-1.0, -2.0}, 19.0}, {{0.5, 0.0}, 7.0}};
    static const double es[] = {0.3, 0.5, 0.7, 0.8, 0.9};
    const int quick = env->quick;
    n_problems = 0;
    double worst_ref = 0.0;
    for (int a = 0; a < 6; a++)
        for (int b = 0; b < 4; b++) {
            if (quick && !((a == 1 && b == 0) || (a == 3 && b == 1)))
                continue;
            problem *p = add_problem(FAM_VDP);
            p->vdp.mu = mus[a];
            memcpy(p->y0, runs[b].y0, sizeof runs[b].y0);
            snprintf(p->name, sizeof p->name, "van der Pol mu = %g, y0 = (%g, %g), t1 = %g", mus[a],
                     runs[b].y0[0], runs[b].y0[1], runs[b].t1);
            p->sys = (bench_sys){BENCH_VDP, p->name, 2, &p->vdp, p->y0, 0.0, runs[b].t1};
            worst_ref = fmax(worst_ref, vdp_reference(p));
            if (a == 1 && b == 0) { /* mu = 1 from (2, 0) to 15: the library's reference */
                const dyn_reference *r = dyn_reference_find("vanderpol-mu1-15");
                const double d =
                    r ? fmax(fabs(r->y[0] - p->ref[0]), fabs(r->y[1] - p->ref[1])) : INFINITY;
                char msg[160];
                snprintf(msg, sizeof msg,
                         "family: the van der Pol reference differs from vanderpol-mu1-15 by "
                         "%.1e",
                         d);
                env->check(d < 1e-14, msg);
            }
        }
    char msg[160];
    snprintf(msg, sizeof msg, "family: a van der Pol reference is only good to %.1e", worst_ref);
    env->check(worst_ref < 1e-14, msg);
    for (int a = 0; a < 5; a++) {
        if (quick && a != 4)
            continue;
        problem *p = add_problem(FAM_KEPLER);
        const double e = es[a];
        p->y0[0] = 1.0 - e;
        p->y0[3] = sqrt((1.0 + e) / (1.0 - e));
        memcpy(p->ref, p->y0, sizeof p->ref);
        snprintf(p->name, sizeof p->name, "Kepler e = %g", e);
        p->sys =
            (bench_sys){BENCH_KEPLER, p->name, 4, NULL, p->y0, 0.0, 2.0 * 3.14159265358979323846};
    }
    if (!quick) {
        const dyn_reference *r = dyn_reference_find("arenstorf-period");
        problem *p = add_problem(FAM_ARENSTORF);
        p->aren.mu = DYN_ARENSTORF_MU;
        p->y0[0] = 0.994;
        p->y0[3] = DYN_ARENSTORF_Y2DOT0;
        if (r)
            memcpy(p->ref, r->y, 4 * sizeof(double));
        env->check(r != NULL, "family: the reference arenstorf-period is missing");
        snprintf(p->name, sizeof p->name, "Arenstorf");
        p->sys =
            (bench_sys){BENCH_ARENSTORF, p->name, 4, &p->aren, p->y0, 0.0, DYN_ARENSTORF_PERIOD};
    }
}

/* ---- the runs ---- */

static int solver_index(const bench_solver *s, int variant_of, const char *what)
{
    for (int i = 0; i < n_solvers; i++)
        if (strcmp(solvers[i].label, s->label) == 0)
            return i;
    if (n_solvers >= FAM_MAX_SOLVERS)
        return -1;
    solver_data *d = &solvers[n_solvers];
    memset(d, 0, sizeof *d);
    memcpy(d->label, s->label, sizeof d->label);
    d->label[sizeof d->label - 1] = '\0';
    d->order = s->order;
    d->is_dynkit = s->is_dynkit;
    d->flags = s->flags;
    d->variant_of = variant_of;
    d->what = what;
    return n_solvers++;
}

static void run_solver(const family_env *env, int p, bench_solver *s, int variant_of,
                       const char *what)
{
    const int id = solver_index(s, variant_of, what);
    const problem *pr = &problems[p];
    if (id < 0)
        return;
    solver_data *d = &solvers[id];
    d->has[p] = 1;
    for (int t = 0; t < n_tols; t++) {
        double y[4];
        bench_counts counts = {0, 0, 0};
        const int failed = s->run(s->ctx, tols[t], 0, y, &counts);
        double err = 0.0;
        for (int i = 0; i < pr->sys.n; i++)
            err = fmax(err, fabs(y[i] - pr->ref[i]));
        d->ok[p][t] = !failed && isfinite(err);
        d->err[p][t] = err;
        d->calls[p][t] = (double)counts.rhs;
        if (!d->ok[p][t]) {
            /* a loose tolerance may send the Arenstorf orbit into the moon's singularity:
             * such a run is left out; a dynkit pair must not fail at tighter ones */
            char msg[200];
            snprintf(msg, sizeof msg, "%.80s on %.90s at tol %.1e", s->label, pr->name, tols[t]);
            if (n_failed < 8)
                memcpy(failed_runs[n_failed], msg, sizeof msg);
            n_failed++;
            char check_msg[220];
            snprintf(check_msg, sizeof check_msg, "family: %s failed", msg);
            env->check(!d->is_dynkit || d->variant_of >= 0 || tols[t] > 1.001e-3, check_msg);
        }
    }
}

static void run_problem(const family_env *env, int p)
{
    bench_solver s[FAM_MAX_SOLVERS];
    int variant[FAM_MAX_SOLVERS]; /* index into variants, or -1 */
    int count = env->collect(&problems[p].sys, s, FAM_MAX_SOLVERS);
    for (int i = 0; i < count; i++)
        variant[i] = -1;
    for (int v = 0; v < (int)(sizeof variants / sizeof variants[0]); v++) {
        char label[80];
        snprintf(label, sizeof label, "dynkit %s, %s", variants[v].method, variants[v].what);
        if (env->variant(&problems[p].sys, variants[v].method, &variants[v].ctl, label, s + count,
                         FAM_MAX_SOLVERS - count))
            variant[count++] = v;
    }
    for (int i = 0; i < count; i++) {
        const int v = variant[i];
        if (problems[p].family != FAM_VDP && !s[i].is_dynkit && v < 0)
            continue; /* the peers only where they are compared */
        int base = -1;
        for (int k = 0; v >= 0 && k < n_solvers; k++)
            if (strncmp(solvers[k].label, "dynkit ", 7) == 0 &&
                strcmp(solvers[k].label + 7, variants[v].method) == 0)
                base = k;
        run_solver(env, p, &s[i], base, v >= 0 ? variants[v].what : NULL);
    }
    for (int i = 0; i < count; i++)
        if (s[i].destroy)
            s[i].destroy(s[i].ctx);
}

/* calls of solver d on problem p at error e, or NAN */
static double calls_at(const solver_data *d, int p, double e)
{
    if (!d->has[p])
        return NAN;
    return wp_front_cost_at(n_tols, d->err[p], d->calls[p], d->ok[p], e);
}

/* ---- the tables ---- */

static void write_csv(const family_env *env)
{
    if (!env->csv_dir)
        return;
    char path[512];
    snprintf(path, sizeof path, "%s/wp-family.csv", env->csv_dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "bench_suite: cannot write %s\n", path);
        return;
    }
    fprintf(f, "problem,solver,order,tol,error,rhs_calls\n");
    for (int i = 0; i < n_solvers; i++)
        for (int p = 0; p < n_problems; p++)
            for (int t = 0; solvers[i].has[p] && t < n_tols; t++)
                if (solvers[i].ok[p][t])
                    fprintf(f, "\"%s\",\"%s\",%d,%.3e,%.6e,%.0f\n", problems[p].name,
                            solvers[i].label, solvers[i].order, tols[t], solvers[i].err[p][t],
                            solvers[i].calls[p][t]);
    fclose(f);
}

/* dynkit's pairs against the peers' methods of the same order, on the van der Pol orbits:
 * per decade the geometric mean of the ratio of calls, and a target row for each pair */
static void pairs_against_peers(const family_env *env, int n_vdp)
{
    int rows = 0;
    for (int i = 0; i < n_solvers; i++)
        for (int j = 0; j < n_solvers; j++)
            rows += solvers[i].is_dynkit && !solvers[i].flags && solvers[i].variant_of < 0 &&
                    !solvers[j].is_dynkit && !solvers[j].flags &&
                    solvers[j].order == solvers[i].order;
    if (!rows) {
        printf("\nNo peer of the same order as a dynkit pair is built into this program: no "
               "comparison over the van der Pol orbits.\n");
        return;
    }
    printf("\n### Calls at equal error over %d van der Pol orbits: dynkit's pairs against the "
           "peers' methods of the same order\n\n"
           "mu = 0.5, 1, 1.5, 2, 3, 4, each from (2, 0) to t1 = 15, (0, 1) to 11, (-1, -2) to "
           "19 and (0.5, 0) to 7%s. Cells: the geometric mean over the orbits of (the dynkit "
           "pair's calls / the peer's) at equal error, times or divided by its uncertainty "
           "(two standard errors of the mean of the logarithms), and the number of orbits "
           "whose runs reach that error on both sides. The target rows take the levels 1e-%d "
           "... 1e-%d that at least half the orbits reach.\n\n"
           "| dynkit pair | peer | order |",
           n_vdp, env->quick ? " (with --quick two of them)" : "", FAM_TARGET_LO, FAM_TARGET_HI);
    for (int k = 2; k <= 12; k++)
        printf(" err 1e-%02d |", k);
    printf("\n|---|---|---:|");
    for (int k = 2; k <= 12; k++)
        printf("---:|");
    printf("\n");
    for (int i = 0; i < n_solvers; i++) {
        const solver_data *a = &solvers[i];
        if (!a->is_dynkit || a->flags || a->variant_of >= 0)
            continue;
        int cmp = 0, met = 0;
        double worst = 0.0;
        char worst_at[96] = "";
        for (int j = 0; j < n_solvers; j++) {
            const solver_data *b = &solvers[j];
            if (b->is_dynkit || b->flags || b->order != a->order)
                continue;
            printf("| %s | %s | %d |", a->label + 7, b->label, a->order);
            for (int k = 2; k <= 12; k++) {
                const double e = pow(10.0, -k);
                double sum = 0.0, sum2 = 0.0;
                int n = 0;
                for (int p = 0; p < n_problems; p++) {
                    const double ca = calls_at(a, p, e), cb = calls_at(b, p, e);
                    if (problems[p].family != FAM_VDP || !isfinite(ca) || !isfinite(cb))
                        continue;
                    sum += log(ca / cb);
                    sum2 += log(ca / cb) * log(ca / cb);
                    n++;
                }
                if (!n) {
                    printf(" - |");
                    continue;
                }
                const double mean = sum / n;
                const double sd = n > 1 ? sqrt(fmax(0.0, (sum2 - n * mean * mean) / (n - 1))) : 0;
                const double g = exp(mean);
                if (n > 1)
                    printf(" %.2f x/ %.2f (%d) |", g, exp(2.0 * sd / sqrt((double)n)), n);
                else
                    printf(" %.2f (1) |", g);
                if (k < FAM_TARGET_LO || k > FAM_TARGET_HI || 2 * n < n_vdp)
                    continue;
                cmp++;
                met += g <= 1.0;
                if (g > worst) {
                    worst = g;
                    snprintf(worst_at, sizeof worst_at, "%.72s at %.0e", b->label, e);
                }
            }
            printf("\n");
        }
        if (cmp && !env->quick) {
            char task[64], what[96], value[200];
            snprintf(task, sizeof task, "adaptive, %d van der Pol orbits", n_vdp);
            snprintf(what, sizeof what, "%s: calls vs same-order peers (geometric mean)",
                     a->label + 7);
            snprintf(value, sizeof value, "%d/%d; worst %.2f (%s)", met, cmp, worst, worst_at);
            env->target(met == cmp, task, what, "<= 1 at every level", value);
        }
    }
}

/* each pair's controller settings against its default, on every problem: the geometric mean
 * of the ratio of calls at errors 1e-3 ... 1e-11 (four levels per decade), by range of
 * error and by family, and the share of (problem, level) where the setting needs more
 * (by more than 0.5%) */
static void controllers(void)
{
    printf("\n### Each pair's controller against other settings, %d problems\n\n"
           "Geometric mean over the problems and the error levels 1e-3 ... 1e-11 (four per "
           "decade) of (calls with the setting / calls with the pair's default) at equal "
           "error; below 1: the setting needs fewer. Last column: the share of (problem, "
           "level) where it needs more than 0.5%% more.\n\n"
           "| pair | setting | all | errors >= 1e-6 | errors < 1e-6 |",
           n_problems);
    for (int f = 0; f < FAM_NFAMILY; f++)
        printf(" %s |", family_names[f]);
    printf(" more calls in |\n|---|---|---:|---:|---:|");
    for (int f = 0; f < FAM_NFAMILY; f++)
        printf("---:|");
    printf("---:|\n");
    for (int i = 0; i < n_solvers; i++) {
        const solver_data *v = &solvers[i];
        if (v->variant_of < 0)
            continue;
        const solver_data *b = &solvers[v->variant_of];
        double sum[3 + FAM_NFAMILY] = {0};
        int n[3 + FAM_NFAMILY] = {0}, worse = 0;
        for (int p = 0; p < n_problems; p++)
            for (int k = 12; k <= 44; k++) {
                const double e = pow(10.0, -k / 4.0);
                const double cv = calls_at(v, p, e), cb = calls_at(b, p, e);
                if (!isfinite(cv) || !isfinite(cb))
                    continue;
                const double l = log(cv / cb);
                const int groups[3] = {0, e >= 1e-6 ? 1 : 2, 3 + problems[p].family};
                for (int g = 0; g < 3; g++) {
                    sum[groups[g]] += l;
                    n[groups[g]]++;
                }
                worse += l > log(1.005);
            }
        printf("| %s | %s |", b->label + 7, v->what);
        for (int g = 0; g < 3 + FAM_NFAMILY; g++) {
            if (n[g])
                printf(" %.3f |", exp(sum[g] / n[g]));
            else
                printf(" - |");
        }
        printf(" %.0f%% |\n", n[0] ? 100.0 * worse / n[0] : 0.0);
    }
}

void family_section(const family_env *env)
{
    n_solvers = 0;
    n_tols = 0;
    n_failed = 0;
    if (env->quick) {
        tols[n_tols++] = 1e-3;
        tols[n_tols++] = 1e-5;
        tols[n_tols++] = 1e-7;
    } else {
        for (int k = 4; k <= 48; k++)
            tols[n_tols++] = pow(10.0, -k / 4.0);
    }
    make_problems(env);
    int n_vdp = 0;
    for (int p = 0; p < n_problems; p++)
        n_vdp += problems[p].family == FAM_VDP;
    printf("\n## 2b. Calls at equal error over families of problems\n\n"
           "On one orbit the error at t1 does not fall smoothly with the tolerance: it swings up "
           "and down from one tolerance to the next (errors cancel along the orbit), so one "
           "orbit's ratio of calls at one error "
           "level is partly chance. Here dynkit's pairs run %d problems and the peers the "
           "%d van der Pol orbits among them, at rtol = atol = %.0e ... %.0e (%s), and ratios "
           "of calls at equal error are averaged over the problems. Calls are exact counts: "
           "this section times nothing.\n",
           n_problems, n_vdp, tols[0], tols[n_tols - 1],
           env->quick ? "a few tolerances" : "four per decade");
    for (int p = 0; p < n_problems; p++)
        run_problem(env, p);
    if (n_failed) {
        printf("\nRuns that failed, left out (at loose tolerances the Arenstorf orbit may run "
               "into the moon's singularity):\n\n");
        for (int i = 0; i < n_failed && i < 8; i++)
            printf("- %s\n", failed_runs[i]);
        if (n_failed > 8)
            printf("- and %d more\n", n_failed - 8);
    }
    pairs_against_peers(env, n_vdp);
    controllers();
    write_csv(env);
}
