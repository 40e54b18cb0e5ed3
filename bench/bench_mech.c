/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_mech: the right-hand sides that dynkit derives from mechanism files (src/mbs,
 * docs/mechanisms.md) against hand-written ones, and what deriving and compiling one costs
 * (docs/performance.md, "Mechanisms").
 *
 * 1. Right-hand side: examples/mechanisms/plane.mech and cart.mech, derived and compiled by
 *    the system compiler (the default flags), against the built-in `plane` and `cart`
 *    (hand-written C, compiled into the library): ns of CPU time per evaluation at each
 *    model's default state, the samples interleaved (each about 2 ms of calls, the variant that goes first
 *    rotating), medians; the ratio derived / built-in (target: at most 1.5).
 * 2. With --file F.mech ... (or after section 1 for examples/mechanisms/bicycle.mech): the
 *    CPU time of deriving (text to C), of compiling with the system compiler and with
 *    libtcc (each into an empty cache), the size of the C, and ns per evaluation of the
 *    right-hand side of each compiled model. bench/bench_mech_sympy.py reads these lines.
 *
 * Usage: bench_mech [--quick] [--reps N] [--file F.mech ...]
 *   --quick   one repetition, few calls: checks that everything derives, compiles and
 *             gives finite numbers (CI; the times mean nothing)
 *   --reps N  repetitions of section 1 (default 15)
 *   --file    only section 2, for these files (one line each: "derive S compile_cc S
 *             compile_tcc S bytes B rhs_cc NS rhs_tcc NS")
 * The examples are read from the source tree it was built from (or $DYNKIT_SOURCE_DIR). Exit status 0 when every check
 * passes, 1 otherwise, 2 for a usage error. */
#define _XOPEN_SOURCE 700 /* nftw */
#define _DEFAULT_SOURCE   /* mkdtemp */
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include <dynkit/jit.h>
#include <dynkit/lang.h>
#include <dynkit/mbs.h>
#include <dynkit/model.h>
#include "bench_clock.h"
#include "bench_util.h"

#define MAX_REPS 101

/* CPU time of this process and of its finished children (the compiler) */
static double cpu_now(void)
{
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return bench_process_cpu_seconds() + (double)ru.ru_utime.tv_sec +
           1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static char cache_root[256];

static int remove_one(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

/* a model and its parameters and default state */
typedef struct subject {
    const char *name;
    const dyn_model *m;
    dyn_jit_model jm;
    void *par;
    double *y, *dy;
    double ns[MAX_REPS];
} subject;

static int prepare(subject *s)
{
    char err[512];
    s->par = calloc(1, s->m->par_size + 16);
    s->y = calloc((size_t)s->m->n_states, sizeof *s->y);
    s->dy = calloc((size_t)s->m->n_states, sizeof *s->dy);
    if (!s->par || !s->y || !s->dy ||
        dyn_model_default_params(s->m, s->par, err, sizeof err) != 0) {
        fprintf(stderr, "bench_mech: %s: parameters: %s\n", s->name, err);
        return 1;
    }
    dyn_model_initial_state(s->m, s->par, s->y);
    if (s->m->rhs(s->m->t0, s->y, s->dy, s->par) != 0) {
        fprintf(stderr, "bench_mech: %s: the right-hand side failed\n", s->name);
        return 1;
    }
    for (int i = 0; i < s->m->n_states; i++)
        if (!isfinite(s->dy[i])) {
            fprintf(stderr, "bench_mech: %s: state %d's rate is not finite\n", s->name, i);
            return 1;
        }
    return 0;
}

/* what prepare allocated, and the compiled model when there is one */
static void release(subject *s)
{
    free(s->par);
    free(s->y);
    free(s->dy);
    s->par = s->y = s->dy = NULL;
    if (s->jm.model)
        dyn_jit_unload(&s->jm);
}

/* ns of CPU time per evaluation, of calls evaluations (CPU time: a busy machine's waits
 * for a core are not counted) */
static double time_rhs(subject *s, long calls)
{
    const double t0 = bench_process_cpu_seconds();
    for (long k = 0; k < calls; k++)
        s->m->rhs(s->m->t0, s->y, s->dy, s->par);
    return 1e9 * (bench_process_cpu_seconds() - t0) / (double)calls;
}

/* calls that take about 2 ms */
static long calibrate(subject *s)
{
    long calls = 16;
    while (calls < (1L << 26) && time_rhs(s, calls) * (double)calls < 2e6)
        calls *= 2;
    return calls;
}

/* derive the file into C (CPU seconds in *t), malloc'd, or NULL */
static char *derive(const char *path, double *t, size_t *bytes)
{
    size_t len;
    char *text = bench_read_text(path, &len);
    if (!text) {
        fprintf(stderr, "bench_mech: cannot read %s\n", path);
        return NULL;
    }
    char *c_src = NULL;
    dyn_lang_diag d;
    char buf[4096];
    const double t0 = cpu_now();
    const int rc = dyn_mech_to_c(path, text, len, NULL, 0, &c_src, &d, NULL, NULL);
    *t = cpu_now() - t0;
    free(text);
    if (rc != 0) {
        fprintf(stderr, "bench_mech: %s\n", dyn_lang_diag_format(&d, buf, sizeof buf));
        return NULL;
    }
    *bytes = strlen(c_src);
    return c_src;
}

/* compile into a new empty cache (CPU seconds with the compiler in *t) */
static int compile(const char *path, const char *c_src, dyn_jit_backend b, subject *s,
                   double *t)
{
    static int count;
    char dir[300];
    snprintf(dir, sizeof dir, "%s/c%d", cache_root, count++);
    dyn_jit_opts opts = {0};
    opts.backend = b;
    opts.cache_dir = dir;
    opts.cc_timeout = 600;
    char err[4096];
    const double t0 = cpu_now();
    const int rc = dyn_jit_load_source(c_src, strlen(c_src), path, &opts, &s->jm, err,
                                       sizeof err);
    *t = cpu_now() - t0;
    if (rc != 0) {
        fprintf(stderr, "bench_mech: %s: %s\n", path, err);
        return 1;
    }
    s->m = s->jm.model;
    s->name = path;
    return prepare(s);
}

/* section 2 for one file */
static int derive_and_compile(const char *path, int quick)
{
    double td, tc, tt;
    size_t bytes;
    char *c_src = derive(path, &td, &bytes);
    if (!c_src)
        return 1;
    subject cc = {0}, tcc = {0};
    int fail = compile(path, c_src, DYN_JIT_CC, &cc, &tc);
    fail |= compile(path, c_src, DYN_JIT_TCC, &tcc, &tt);
    free(c_src);
    if (fail) {
        release(&cc);
        release(&tcc);
        return 1;
    }
    double best_cc = 1e300, best_tcc = 1e300;
    const int reps = quick ? 1 : 7;
    const long calls_cc = quick ? 10 : calibrate(&cc), calls_tcc = quick ? 10 : calibrate(&tcc);
    for (int r = 0; r < reps; r++) {
        best_cc = fmin(best_cc, time_rhs(&cc, calls_cc));
        best_tcc = fmin(best_tcc, time_rhs(&tcc, calls_tcc));
    }
    int same = 1;
    for (int i = 0; i < cc.m->n_states; i++)
        same &= fabs(cc.dy[i] - tcc.dy[i]) <= 1e-9 * (1.0 + fabs(cc.dy[i]));
    printf("%s derive %.4f compile_cc %.4f compile_tcc %.4f bytes %zu rhs_cc %.1f rhs_tcc %.1f\n",
           path, td, tc, tt, bytes, best_cc, best_tcc);
    if (!same)
        fprintf(stderr, "bench_mech: %s: the two compilers' right-hand sides differ\n", path);
    release(&cc);
    release(&tcc);
    return !same;
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 15, first_file = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--file") && i + 1 < argc) {
            first_file = i + 1;
            break;
        } else {
            fprintf(stderr, "usage: bench_mech [--quick] [--reps N] [--file F.mech ...]\n");
            return 2;
        }
    }
    if (reps < 1 || reps > MAX_REPS) {
        fprintf(stderr, "bench_mech: --reps takes 1 to %d\n", MAX_REPS);
        return 2;
    }
    if (quick)
        reps = 1;
    const char *tmp = getenv("TMPDIR");
    snprintf(cache_root, sizeof cache_root, "%s/bench_mech_XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(cache_root)) {
        perror("bench_mech: mkdtemp");
        return 1;
    }
    int fail = 0;
    if (first_file) {
        for (int i = first_file; i < argc; i++)
            fail |= derive_and_compile(argv[i], quick);
        nftw(cache_root, remove_one, 16, FTW_DEPTH | FTW_PHYS);
        return fail;
    }
    const char *src = getenv("DYNKIT_SOURCE_DIR");
    if (!src || !*src)
        src = BENCH_SOURCE_DIR;
    static const char *const pairs[2][2] = {{"plane", "plane.mech"}, {"cart", "cart.mech"}};
    subject S[4] = {{0}};
    for (int k = 0; k < 2; k++) {
        subject *b = &S[2 * k], *d = &S[2 * k + 1];
        b->name = pairs[k][0];
        b->m = dyn_model_find(pairs[k][0]);
        if (!b->m || prepare(b))
            return 1;
        char path[1024];
        snprintf(path, sizeof path, "%s/examples/mechanisms/%s", src, pairs[k][1]);
        double td, tc;
        size_t bytes;
        char *c_src = derive(path, &td, &bytes);
        if (!c_src || compile(path, c_src, DYN_JIT_AUTO, d, &tc))
            return 1;
        free(c_src);
    }
    long calls[4];
    for (int k = 0; k < 4; k++)
        calls[k] = quick ? 10 : calibrate(&S[k]);
    for (int r = 0; r < reps; r++)
        for (int j = 0; j < 4; j++) {
            const int k = (j + r) % 4;
            S[k].ns[r] = time_rhs(&S[k], calls[k]);
        }
    printf("| model | hand-written built-in [ns] | derived from .mech [ns] | ratio |\n"
           "|---|---|---|---|\n");
    for (int k = 0; k < 2; k++) {
        const double b = bench_median(S[2 * k].ns, reps), d = bench_median(S[2 * k + 1].ns, reps);
        printf("| %s | %.1f | %.1f | %.2f |\n", pairs[k][0], b, d, d / b);
    }
    for (int k = 0; k < 4; k++)
        release(&S[k]);
    char bicycle[1024];
    snprintf(bicycle, sizeof bicycle, "%s/examples/mechanisms/bicycle.mech", src);
    printf("\n");
    fail |= derive_and_compile(bicycle, quick);
    nftw(cache_root, remove_one, 16, FTW_DEPTH | FTW_PHYS);
    return fail;
}
