/* SPDX-License-Identifier: BSD-3-Clause */
/* bench_jit: what compiling a model costs and how fast the compiled model runs (the jit
 * layer, dynkit/jit.h), for the choice of its default backend (docs/model-files.md,
 * "Compiling models").
 *
 * 1. Right-hand side: van der Pol, classical RK4 through dyn_fixed_solve, the built-in
 *    dyn_model_vanderpol against the same equations written as C source (below, as the .ode
 *    translator writes them) compiled by the system compiler with the default flags (-O2),
 *    with -O3 -march=native, and by libtcc. ns per step, the ratio to the built-in model
 *    (target: at most 1.3), and whether the final states are the same bits.
 *    The same for a heavier right-hand side, arithmetic in a loop (Lorenz-96, 40 states),
 *    against the same code compiled into this program: where libtcc's code generation shows.
 * 2. First run of a new model: a 4-state model (an elastic pendulum, libm calls) whose source
 *    changes every repetition, so each one compiles: compile + load + 1000 RK4 steps, per
 *    backend (target: under 0.3 s in all); once also into an empty cache (the headers
 *    written first).
 *    Also the CPU time of this process and the compiler: close to the wall time of a first run
 *    on an idle machine, and much less sensitive to other work on the machine.
 * 3. Cached run: a source compiled in 2 loaded again (hash, stat, dlopen, checks) and run
 *    for 1000 steps (target: under 20 ms).
 * The variants' samples are interleaved, rotating which goes first; medians (and minima)
 * over the repetitions. The cache is a fresh directory under /tmp, removed at the end.
 *
 * Usage: bench_jit [--quick] [--reps N] [--steps N]
 *   --quick    1e5 steps, 1 repetition: checks that everything compiles, loads and gives
 *              the built-in model's numbers bit for bit (CI; the times mean nothing)
 *   --reps N   repetitions (default 7)
 *   --steps N  RK4 steps of van der Pol (default 1e7)
 * The system compiler is $DYNKIT_CC, else $CC, else cc, as for dynkit itself.
 * Exit status 0 when every check passes, 1 otherwise, 2 for a usage error.
 */
#define _XOPEN_SOURCE 700 /* nftw */
#define _DEFAULT_SOURCE   /* mkdtemp */
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#include <dynkit/jit.h>
#include <dynkit/models.h>
#include <dynkit/ode.h>
#include "bench_clock.h"
#include "bench_util.h"

#define MAX_REPS 101

/* CPU time of this thread and of the finished child processes (the compiler): what a first
 * run costs on an idle machine, much less sensitive to the machine's load than wall time */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec + (double)ru.ru_utime.tv_sec +
           1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

/* the median of v, left in its order */
static double median(const double *v, int n)
{
    double s[MAX_REPS];
    memcpy(s, v, (size_t)n * sizeof *s);
    return bench_median(s, n);
}

static double minimum(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++)
        m = fmin(m, v[i]);
    return m;
}

/* van der Pol with the built-in model's equations (src/models/vanderpol.c) */
static const char vdp_source[] =
    "#include <math.h>\n"
    "#include <stddef.h>\n"
    "#include <dynkit/model.h>\n"
    "typedef struct par { double mu; } par;\n"
    "static int rhs(double t, const double *y, double *dydt, void *p_)\n"
    "{\n"
    "    const par *p = p_;\n"
    "    (void)t;\n"
    "    dydt[0] = y[1];\n"
    "    dydt[1] = p->mu * (1.0 - y[0] * y[0]) * y[1] - y[0];\n"
    "    return 0;\n"
    "}\n"
    "static const dyn_var states[] = {{\"y1\", \"1\", \"\"}, {\"y2\", \"1/s\", \"\"}};\n"
    "static const double init[] = {2.0, 0.0};\n"
    "static const dyn_param params[] = {{\"mu\", \"1\", \"\", offsetof(par, mu), 1.0}};\n"
    "static const dyn_model model = {.name = \"vanderpol\", .n_states = 2, .states = states,\n"
    "    .y0 = init, .n_params = 1, .params = params, .par_size = sizeof(par), .rhs = rhs,\n"
    "    .t1 = 15.0, .step = 0.01, .method = \"rk4\"};\n"
    "const dyn_model *dynkit_model(void) { return &model; }\n";

/* a 4-state model (elastic pendulum); %d makes each repetition a new source */
static const char four_source_fmt[] =
    "/* elastic pendulum, variant %d */\n"
    "#include <math.h>\n"
    "#include <stddef.h>\n"
    "#include <dynkit/model.h>\n"
    "typedef struct par { double m, k, l0, g; } par;\n"
    "static int rhs(double t, const double *y, double *dydt, void *p_)\n"
    "{\n"
    "    const par *p = p_;\n"
    "    (void)t;\n"
    "    double r = y[0], th = y[1], dr = y[2], dth = y[3];\n"
    "    dydt[0] = dr;\n"
    "    dydt[1] = dth;\n"
    "    dydt[2] = r * dth * dth + p->g * cos(th) - p->k / p->m * (r - p->l0);\n"
    "    dydt[3] = -(p->g * sin(th) + 2.0 * dr * dth) / r;\n"
    "    return 0;\n"
    "}\n"
    "static int outputs(double t, const double *y, const void *p_, double *out)\n"
    "{\n"
    "    const par *p = p_;\n"
    "    (void)t;\n"
    "    out[0] = 0.5 * p->m * (y[2] * y[2] + y[0] * y[0] * y[3] * y[3])\n"
    "             - p->m * p->g * y[0] * cos(y[1]) + 0.5 * p->k * pow(y[0] - p->l0, 2);\n"
    "    return 0;\n"
    "}\n"
    "static const dyn_var states[] = {{\"r\", \"m\", \"length\"}, {\"theta\", \"rad\", "
    "\"angle\"},\n"
    "    {\"dr\", \"m/s\", \"\"}, {\"dtheta\", \"rad/s\", \"\"}};\n"
    "static const dyn_var outs[] = {{\"energy\", \"J\", \"total energy\"}};\n"
    "static const double init[] = {1.2, 0.5, 0.0, 0.0};\n"
    "static const dyn_param params[] = {\n"
    "    {\"m\", \"kg\", \"mass\", offsetof(par, m), 1.0},\n"
    "    {\"k\", \"N/m\", \"stiffness\", offsetof(par, k), 40.0},\n"
    "    {\"l0\", \"m\", \"rest length\", offsetof(par, l0), 1.0},\n"
    "    {\"g\", \"m/s^2\", \"gravity\", offsetof(par, g), 9.81}};\n"
    "static const dyn_model model = {.name = \"elastic\", .n_states = 4, .states = states,\n"
    "    .y0 = init, .n_params = 4, .params = params, .par_size = sizeof(par), .rhs = rhs,\n"
    "    .n_outputs = 1, .outputs = outs, .compute_outputs = outputs,\n"
    "    .t1 = 10.0, .step = 0.01, .method = \"rk4\"};\n"
    "const dyn_model *dynkit_model(void) { return &model; }\n";

/* a heavier right-hand side, arithmetic in a loop (XPPAUT's x[1..n] arrays look alike):
 * Lorenz-96 with 40 states, x_i' = (x_{i+1} - x_{i-2}) x_{i-1} - x_i + F; the same text is
 * compiled into this program (L96_BODY) as the reference */
#define L96_N 40
#define L96_BODY                                                                                   \
    for (int i = 0; i < L96_N; i++)                                                                \
        dydt[i] = (y[(i + 1) % L96_N] - y[(i + L96_N - 2) % L96_N]) * y[(i + L96_N - 1) % L96_N] - \
                  y[i] + 8.0;
#define STR_(x) #x
#define STR(x) STR_(x)
static const char l96_source[] =
    "#include <dynkit/model.h>\n"
    "#define L96_N 40\n"
    "static int rhs(double t, const double *y, double *dydt, void *p)\n"
    "{\n"
    "    (void)t, (void)p;\n"
    "    " STR(
        L96_BODY) "\n"
                  "    return 0;\n"
                  "}\n"
                  "static double init[L96_N];\n"
                  "static dyn_var states[L96_N];\n"
                  "static char names[L96_N][8];\n"
                  "static dyn_model model = {.name = \"lorenz96\", .n_states = L96_N, .states = "
                  "states,\n"
                  "    .y0 = init, .rhs = rhs, .t1 = 10.0, .step = 0.01, .method = \"rk4\"};\n"
                  "const dyn_model *dynkit_model(void)\n"
                  "{\n"
                  "    for (int i = 0; i < L96_N; i++) {\n"
                  "        init[i] = 8.0 + (i == 0 ? 0.01 : 0.0);\n"
                  "        names[i][0] = 'x'; names[i][1] = (char)('0' + i / 10);\n"
                  "        names[i][2] = (char)('0' + i % 10); names[i][3] = 0;\n"
                  "        states[i] = (dyn_var){names[i], \"1\", \"\"};\n"
                  "    }\n"
                  "    return &model;\n"
                  "}\n";

static int l96_rhs(double t, const double *y, double *dydt, void *p)
{
    (void)t, (void)p;
    L96_BODY
    return 0;
}

/* the compiled variants */
enum { V_BUILTIN, V_CC, V_NATIVE, V_TCC, N_VARIANTS };
static const char *variant_name[N_VARIANTS] = {
    "built in (dyn_model_vanderpol)", "cc -O2 (default flags)", "cc -O3 -march=native", "libtcc"};

static int rk4_final(const dyn_model *m, long steps, double h, double *y)
{
    static double work[8 * L96_N];
    double par[16] = {0};
    char err[256];
    if (dyn_model_default_params(m, par, err, sizeof err) != 0)
        return 1;
    double y0[L96_N];
    dyn_model_initial_state(m, par, y0);
    dyn_system sys = {m->rhs, m->n_states, par};
    dyn_result res;
    return dyn_fixed_solve(dyn_method_find("rk4"), &sys, 0.0, (double)steps * h, h, y0, y, work,
                           NULL, &res) != DYN_OK;
}

static int load(const char *src, const dyn_jit_opts *o, dyn_jit_model *jm)
{
    char err[4096];
    if (dyn_jit_load_source(src, strlen(src), "bench.c", o, jm, err, sizeof err) != 0) {
        fprintf(stderr, "bench_jit: %s\n", err);
        return 1;
    }
    return 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void first_line_of(const char *cmd, char *out, size_t size)
{
    snprintf(out, size, "?");
    FILE *p = popen(cmd, "r");
    if (!p)
        return;
    if (fgets(out, (int)size, p))
        out[strcspn(out, "\n")] = '\0';
    pclose(p);
}

static void cpu_name(char *out, size_t size)
{
    snprintf(out, size, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, "model name", 10) == 0) {
            const char *c = strchr(line, ':');
            snprintf(out, size, "%.200s", c ? c + 2 : line);
            out[strcspn(out, "\n")] = '\0';
            break;
        }
    if (f)
        fclose(f);
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 7;
    long steps = 10000000;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc)
            steps = atol(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_jit [--quick] [--reps N] [--steps N]\n");
            return 2;
        }
    }
    if (quick) {
        reps = 1;
        steps = 100000;
    }
    if (reps < 1 || reps > MAX_REPS || steps < 1) {
        fprintf(stderr, "bench_jit: --reps 1..%d, --steps >= 1\n", MAX_REPS);
        return 2;
    }
    char cache[] = "/tmp/dynkit-bench-jit-XXXXXX";
    if (!mkdtemp(cache)) {
        perror("bench_jit: mkdtemp");
        return 1;
    }
    int have_tcc = dyn_jit_backend_available(DYN_JIT_TCC);
    dyn_jit_opts opts[N_VARIANTS] = {
        [V_CC] = {.backend = DYN_JIT_CC, .cache_dir = cache},
        [V_NATIVE] = {.backend = DYN_JIT_CC, .cache_dir = cache, .cflags = "-O3 -march=native"},
        [V_TCC] = {.backend = DYN_JIT_TCC, .cache_dir = cache},
    };
    int failed = 0;

    /* ---- 3 (prepared first): a first load into an empty cache, headers written ---- */
    char src[8192];
    int variant_id = 0;
    snprintf(src, sizeof src, four_source_fmt, variant_id++);
    dyn_jit_model jm;
    double t = bench_wall_seconds();
    if (load(src, &opts[V_CC], &jm) != 0) {
        nftw(cache, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
        return 1;
    }
    double y4[4];
    failed |= rk4_final(jm.model, 1000, 0.01, y4);
    double empty_cache_ms = 1e3 * (bench_wall_seconds() - t);
    dyn_jit_unload(&jm);

    /* ---- 1. the right-hand side ---- */
    dyn_jit_model vm[N_VARIANTS];
    const dyn_model *models[N_VARIANTS] = {&dyn_model_vanderpol};
    for (int v = V_CC; v < N_VARIANTS; v++) {
        if (v == V_TCC && !have_tcc)
            continue;
        if (load(vdp_source, &opts[v], &vm[v]) != 0) {
            nftw(cache, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
            return 1;
        }
        models[v] = vm[v].model;
    }
    double ns[N_VARIANTS][MAX_REPS], yv[N_VARIANTS][2];
    const double h = 0.01;
    for (int r = 0; r < reps; r++)
        for (int j = 0; j < N_VARIANTS; j++) {
            int v = (j + r) % N_VARIANTS;
            if (!models[v])
                continue;
            t = bench_wall_seconds();
            failed |= rk4_final(models[v], steps, h, yv[v]);
            ns[v][r] = 1e9 * (bench_wall_seconds() - t) / (double)steps;
        }
    int same[N_VARIANTS];
    for (int v = 0; v < N_VARIANTS; v++) {
        same[v] = models[v] && memcmp(yv[v], yv[V_BUILTIN], sizeof yv[v]) == 0;
        /* the default flags and libtcc must give the built-in model's numbers exactly */
        if (models[v] && !same[v] && v != V_NATIVE) {
            fprintf(stderr,
                    "bench_jit: %s: final state (%.17g, %.17g) differs from the "
                    "built-in (%.17g, %.17g)\n",
                    variant_name[v], yv[v][0], yv[v][1], yv[V_BUILTIN][0], yv[V_BUILTIN][1]);
            failed = 1;
        }
    }

    for (int v = V_CC; v < N_VARIANTS; v++)
        if (models[v])
            dyn_jit_unload(&vm[v]);

    /* ---- 1b. the heavier right-hand side: Lorenz-96 ---- */
    double l96_init[L96_N];
    for (int i = 0; i < L96_N; i++)
        l96_init[i] = 8.0 + (i == 0 ? 0.01 : 0.0);
    const dyn_model l96_here = {
        .name = "lorenz96", .n_states = L96_N, .y0 = l96_init, .rhs = l96_rhs};
    const dyn_model *lm[N_VARIANTS] = {&l96_here};
    for (int v = V_CC; v < N_VARIANTS; v++) {
        if (v == V_TCC && !have_tcc)
            continue;
        if (load(l96_source, &opts[v], &vm[v]) != 0) {
            nftw(cache, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
            return 1;
        }
        lm[v] = vm[v].model;
    }
    long l96_steps = steps / 20;
    double l96_ns[N_VARIANTS][MAX_REPS], l96_y[N_VARIANTS][L96_N];
    for (int r = 0; r < reps; r++)
        for (int j = 0; j < N_VARIANTS; j++) {
            int v = (j + r) % N_VARIANTS;
            if (!lm[v])
                continue;
            t = bench_wall_seconds();
            failed |= rk4_final(lm[v], l96_steps, 0.001, l96_y[v]);
            l96_ns[v][r] = 1e9 * (bench_wall_seconds() - t) / (double)l96_steps;
        }
    int l96_same[N_VARIANTS];
    for (int v = 0; v < N_VARIANTS; v++) {
        l96_same[v] = lm[v] && memcmp(l96_y[v], l96_y[V_BUILTIN], sizeof l96_y[v]) == 0;
        if (lm[v] && !l96_same[v] && v != V_NATIVE) {
            fprintf(stderr, "bench_jit: %s: Lorenz-96 differs from the program's own\n",
                    variant_name[v]);
            failed = 1;
        }
    }
    for (int v = V_CC; v < N_VARIANTS; v++)
        if (lm[v])
            dyn_jit_unload(&vm[v]);

    /* ---- 2. first runs of new 4-state models; 3. cached runs (of the last one cc compiled,
     * unloaded before, so that dlopen maps it anew) ---- */
    char src_cc[8192] = "";
    enum { F_CC, F_NATIVE, F_TCC, N_FIRST };
    const int first_variant[N_FIRST] = {V_CC, V_NATIVE, V_TCC};
    double first_ms[N_FIRST][MAX_REPS], compile_ms[N_FIRST][MAX_REPS], cpu_ms[N_FIRST][MAX_REPS];
    double cached_ms[MAX_REPS];
    double ref4[4];
    int have_ref4 = 0;
    for (int r = 0; r < reps; r++) {
        for (int j = 0; j < N_FIRST; j++) {
            int f = (j + r) % N_FIRST;
            if (first_variant[f] == V_TCC && !have_tcc)
                continue;
            snprintf(src, sizeof src, four_source_fmt, variant_id++);
            double c0 = cpu_now();
            t = bench_wall_seconds();
            if (load(src, &opts[first_variant[f]], &jm) != 0) {
                failed = 1;
                continue;
            }
            failed |= rk4_final(jm.model, 1000, 0.01, y4);
            first_ms[f][r] = 1e3 * (bench_wall_seconds() - t);
            cpu_ms[f][r] = 1e3 * (cpu_now() - c0);
            compile_ms[f][r] = 1e3 * jm.compile_seconds;
            if (jm.cached) {
                fprintf(stderr, "bench_jit: a new source came from the cache\n");
                failed = 1;
            }
            if (f == F_CC)
                memcpy(src_cc, src, sizeof src_cc);
            if (f != F_NATIVE) {
                if (have_ref4 && memcmp(ref4, y4, sizeof y4) != 0) {
                    fprintf(stderr, "bench_jit: the 4-state model differs between backends\n");
                    failed = 1;
                }
                memcpy(ref4, y4, sizeof y4);
                have_ref4 = 1;
            }
            dyn_jit_unload(&jm);
        }
        /* the last cc source again: from the cache */
        t = bench_wall_seconds();
        if (load(src_cc, &opts[V_CC], &jm) != 0 || !jm.cached) {
            fprintf(stderr, "bench_jit: the cached load did not come from the cache\n");
            failed = 1;
        }
        if (jm.model)
            failed |= rk4_final(jm.model, 1000, 0.01, y4);
        cached_ms[r] = 1e3 * (bench_wall_seconds() - t);
        dyn_jit_unload(&jm);
    }
    nftw(cache, remove_entry, 16, FTW_DEPTH | FTW_PHYS);

    /* ---- report ---- */
    char cpu[256], ccv[256];
    const char *cc = getenv("DYNKIT_CC") && getenv("DYNKIT_CC")[0] ? getenv("DYNKIT_CC")
                     : getenv("CC") && getenv("CC")[0]             ? getenv("CC")
                                                                   : "cc";
    char cmd[300];
    snprintf(cmd, sizeof cmd, "%s --version 2>/dev/null", cc);
    cpu_name(cpu, sizeof cpu);
    first_line_of(cmd, ccv, sizeof ccv);
    printf("## bench_jit%s\n\n", quick ? " --quick (checks only: the times mean nothing)" : "");
    printf("%s; system compiler `%s`: %s; %d repetitions, medians (min)\n\n", cpu, cc, ccv, reps);
    printf("| van der Pol, RK4, %ld steps | ns/step | ratio to built in | same bits |\n", steps);
    printf("|---|---:|---:|---|\n");
    for (int v = 0; v < N_VARIANTS; v++) {
        if (!models[v])
            continue;
        double m = median(ns[v], reps);
        printf("| %s | %.2f (%.2f) | %.3f | %s |\n", variant_name[v], m, minimum(ns[v], reps),
               m / median(ns[V_BUILTIN], reps),
               v == V_BUILTIN ? ""
               : same[v]      ? "yes"
                              : "no");
    }
    printf("\n| Lorenz-96 (40 states), RK4, %ld steps | ns/step | ratio to compiled in | same "
           "bits |\n|---|---:|---:|---|\n",
           l96_steps);
    for (int v = 0; v < N_VARIANTS; v++) {
        if (!lm[v])
            continue;
        double m = median(l96_ns[v], reps);
        printf("| %s | %.1f (%.1f) | %.3f | %s |\n",
               v == V_BUILTIN ? "compiled into this program" : variant_name[v], m,
               minimum(l96_ns[v], reps), m / median(l96_ns[V_BUILTIN], reps),
               v == V_BUILTIN ? ""
               : l96_same[v]  ? "yes"
                              : "no");
    }
    printf("\n| new 4-state model: compile + load + 1000 RK4 steps | ms in all | of which "
           "compiling | CPU ms (with the compiler's) |\n|---|---:|---:|---:|\n");
    printf("| cc -O2, into an empty cache (headers written first) | %.1f | | |\n", empty_cache_ms);
    for (int f = 0; f < N_FIRST; f++) {
        if (first_variant[f] == V_TCC && !have_tcc)
            continue;
        printf("| %s | %.1f (%.1f) | %.1f | %.1f |\n", variant_name[first_variant[f]],
               median(first_ms[f], reps), minimum(first_ms[f], reps), median(compile_ms[f], reps),
               median(cpu_ms[f], reps));
    }
    printf("\n| cached run: load from the cache (key, owner and mode, SHA-256 of the object, "
           "dlopen of a private copy, checks) + 1000 RK4 steps "
           "| ms |\n"
           "|---|---:|\n| cc | %.2f (%.2f) |\n",
           median(cached_ms, reps), minimum(cached_ms, reps));

    double ratio = median(ns[V_CC], reps) / median(ns[V_BUILTIN], reps);
    double first = median(first_ms[F_CC], reps), cached = median(cached_ms, reps);
    printf("\n| target (issue 9), default backend cc | measured | |\n|---|---:|---|\n");
    printf("| right-hand side within 1.3x of built in | %.3f | %s |\n", ratio,
           quick          ? "(quick)"
           : ratio <= 1.3 ? "met"
                          : "missed");
    printf("| first run of a new 4-state model under 300 ms | %.0f ms | %s |\n", first,
           quick         ? "(quick)"
           : first < 300 ? "met"
                         : "missed");
    printf("| cached run adding under 20 ms | %.2f ms | %s |\n", cached,
           quick         ? "(quick)"
           : cached < 20 ? "met"
                         : "missed");
    if (failed)
        fprintf(stderr, "bench_jit: FAILED\n");
    return failed ? 1 : 0;
}
