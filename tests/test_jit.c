/* SPDX-License-Identifier: BSD-3-Clause */
/* test_jit.c — tests of the jit layer (dynkit/jit.h): C models compiled by the system
 * compiler and by libtcc, loaded and integrated to known answers (the example spring-mass
 * against cos/sin, van der Pol bit for bit against the built-in model, the translated .ode
 * files of examples/models the same from both backends), the cache (a second load runs no
 * compiler; concurrent first loads in several processes), compiler errors that
 * name the user's file and line, the model ABI check and the checks of the returned model, a
 * missing compiler (libtcc instead when none was named), a compiler stopped at its time limit
 * (libtcc instead, with a note), a compiler that cannot write (libtcc instead, with a note),
 * what is planted under an object's name (moved aside), and a model calling the library's
 * mech.h functions from this program.
 * Each test has a cache directory of its own under /tmp (with a blank in its name).
 */
#define _XOPEN_SOURCE 700 /* nftw */
#define _DEFAULT_SOURCE   /* mkdtemp, setenv */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "dynkit/delay.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/mech.h"
#include "dynkit/models.h"
#include "test_util.h"

#define ERRLEN 4096

typedef struct fixture {
    char dir[256];   /* the test's directory: sources, scripts */
    char cache[300]; /* its cache directory */
    dyn_jit_opts cc, tcc;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    snprintf(f->dir, sizeof f->dir, "/tmp/dynkit jit test XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    snprintf(f->cache, sizeof f->cache, "%s/cache", f->dir);
    f->cc = (dyn_jit_opts){.backend = DYN_JIT_CC, .cache_dir = f->cache};
    f->tcc = (dyn_jit_opts){.backend = DYN_JIT_TCC, .cache_dir = f->cache};
    unsetenv("DYNKIT_CC");
    unsetenv("DYNKIT_CFLAGS");
    unsetenv("DYNKIT_JIT");
    *state = f;
    return 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static int teardown(void **state)
{
    fixture *f = *state;
    nftw(f->dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    unsetenv("DYNKIT_CC");
    free(f);
    return 0;
}

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    assert_int_equal(fclose(fp), 0);
}

/* Integrate m with its default parameters (then set[i] = value) by RK4 from 0 to t1 with
 * step h (iterate it, for a discrete map); final state into y. */
static void rk4_run(const dyn_model *m, const char *set_name, double set_value, double t1, double h,
                    double *y)
{
    double par[64] = {0}, work[TEST_WORK], y0[TEST_MAX_N];
    char err[256];
    assert_true(m->par_size <= sizeof par);
    assert_true(m->n_states <= TEST_MAX_N);
    assert_int_equal(dyn_model_default_params(m, par, err, sizeof err), 0);
    if (set_name) {
        int i = dyn_model_param_index(m, set_name);
        assert_true(i >= 0);
        dyn_model_set_param(m, par, i, set_value);
        if (m->prepare)
            assert_int_equal(m->prepare(par, err, sizeof err), 0);
    }
    dyn_model_initial_state(m, par, y0);
    dyn_system sys = {m->rhs, m->n_states, par};
    dyn_result res;
    if (m->delay) { /* delay(x, tau): RK4 by dyn_solve, its steps kept in a history */
        const dyn_tableau *rk4 = dyn_method_find("rk4");
        const long steps = (long)ceil(t1 / h) + 2;
        double *store = malloc((size_t)steps * dyn_dense_record_block(m->n_states, 3) *
                               sizeof *store);
        assert_non_null(store);
        dyn_history hist = {0};
        dyn_history_init(&hist, m->n_states, dyn_method_dense_degree(rk4), 0.0, y0,
                         m->delay->history, par, m->delay->max_delay, store, steps);
        m->delay->attach(par, &hist);
        dyn_solve_opts o = {0};
        o.h = h;
        o.step = dyn_history_push;
        o.step_ctx = &hist;
        assert_true(dyn_solve_work_size(rk4, m->n_states, &o) <= TEST_WORK);
        assert_int_equal(dyn_solve(rk4, &sys, 0.0, t1, y0, y, work, &o, &res), DYN_OK);
        m->delay->attach(par, NULL);
        free(store);
        return;
    }
    const dyn_tableau *own = dyn_method_find(m->method);
    const dyn_tableau *method = dyn_method_is_map(own) ? own : dyn_method_find("rk4");
    assert_int_equal(dyn_fixed_solve(method, &sys, 0.0, t1, h, y0, y, work, NULL, &res), DYN_OK);
}

static void load_ok(const char *source, const char *name, const dyn_jit_opts *opts,
                    dyn_jit_model *jm)
{
    char err[ERRLEN];
    int rc = dyn_jit_load_source(source, strlen(source), name, opts, jm, err, sizeof err);
    if (rc != 0)
        print_error("%s\n", err);
    assert_int_equal(rc, 0);
    assert_non_null(jm->model);
}

/* ---- the models ---- */

/* van der Pol with the built-in model's equations, as the translator writes them */
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
    "static const dyn_model model = {.name = \"vdp\", .n_states = 2, .states = states,\n"
    "    .y0 = init, .n_params = 1, .params = params, .par_size = sizeof(par), .rhs = rhs,\n"
    "    .t1 = 15.0, .step = 0.01, .method = \"rk4\"};\n"
    "const dyn_model *dynkit_model(void) { return &model; }\n";

/* a rotating frame: calls the library (mech.h) from the right-hand side */
static const char mech_source[] =
    "#include <dynkit/model.h>\n"
    "#include <dynkit/mech.h>\n"
    "static int rhs(double t, const double *y, double *dydt, void *p)\n"
    "{\n"
    "    double R[9], v[3];\n"
    "    (void)p;\n"
    "    dyn_rot_z(t, R);\n"
    "    dyn_mat3_mul_vec(R, y, v);\n"
    "    double n = dyn_vec3_norm(y);\n"
    "    for (int i = 0; i < 3; i++) dydt[i] = v[i] - 0.1 * n * y[i];\n"
    "    return 0;\n"
    "}\n"
    "static const dyn_var states[] = {{\"a\", \"m\", \"\"}, {\"b\", \"m\", \"\"},\n"
    "                                 {\"c\", \"m\", \"\"}};\n"
    "static const double init[] = {1.0, 0.5, -0.25};\n"
    "static const dyn_model model = {.name = \"frame\", .n_states = 3, .states = states,\n"
    "    .y0 = init, .rhs = rhs, .t1 = 1.0, .step = 0.01, .method = \"rk4\"};\n"
    "const dyn_model *dynkit_model(void) { return &model; }\n";

static int mech_rhs(double t, const double *y, double *dydt, void *p)
{
    double R[9], v[3];
    (void)p;
    dyn_rot_z(t, R);
    dyn_mat3_mul_vec(R, y, v);
    double n = dyn_vec3_norm(y);
    for (int i = 0; i < 3; i++)
        dydt[i] = v[i] - 0.1 * n * y[i];
    return 0;
}

/* ---- tests ---- */

/* examples/models/spring_mass.c with k = 4: x = 0.1 cos(2t), v = -0.2 sin(2t); its prepare
 * calls the library's dyn_check_positive */
static void test_spring_mass_example(void **state)
{
    fixture *f = *state;
    char err[ERRLEN];
    dyn_jit_model jm;
    int rc = dyn_jit_load_c_file(DYNKIT_SOURCE_DIR "/examples/models/spring_mass.c", &f->cc, &jm,
                                 err, sizeof err);
    if (rc != 0)
        print_error("%s\n", err);
    assert_int_equal(rc, 0);
    assert_int_equal(jm.backend, DYN_JIT_CC);
    assert_int_equal(jm.cached, 0);
    assert_string_equal(jm.model->name, "spring_mass");
    assert_int_equal(dyn_model_param_index(jm.model, "k"), 1);
    double y[2], t1 = 2.5;
    rk4_run(jm.model, "k", 4.0, t1, 1e-3, y);
    assert_true(fabs(y[0] - 0.1 * cos(2.0 * t1)) < 1e-12);
    assert_true(fabs(y[1] + 0.2 * sin(2.0 * t1)) < 1e-12);
    /* its outputs: the energy k x^2/2 + m v^2/2 = 4 * 0.01 / 2 is conserved */
    double par[8] = {0}, out[2];
    assert_int_equal(dyn_model_default_params(jm.model, par, err, sizeof err), 0);
    dyn_model_set_param(jm.model, par, 1, 4.0);
    assert_int_equal(jm.model->compute_outputs(t1, y, par, out), 0);
    assert_true(fabs(out[0] - 0.02) < 1e-12);
    /* the library's message through the model's prepare */
    dyn_model_set_param(jm.model, par, 1, -1.0);
    assert_int_not_equal(jm.model->prepare(par, err, sizeof err), 0);
    assert_non_null(strstr(err, "k must be a finite number > 0"));
    /* the compiled file is a shared object that loads by itself too */
    dyn_jit_model again;
    assert_int_equal(dyn_jit_load_shared(jm.so_path, &again, err, sizeof err), 0);
    assert_string_equal(again.model->name, "spring_mass");
    dyn_jit_unload(&again);
    dyn_jit_unload(&jm);
    assert_null(jm.model);
}

/* the same equations as the built-in van der Pol give the same numbers bit for bit, from
 * both backends */
static void test_vanderpol_bit_for_bit(void **state)
{
    fixture *f = *state;
    double ref[2], y[2];
    rk4_run(&dyn_model_vanderpol, NULL, 0, 15.0, 0.01, ref);
    const dyn_jit_opts *opts[2] = {&f->cc, &f->tcc};
    for (int b = 0; b < 2; b++) {
        if (!dyn_jit_backend_available(opts[b]->backend))
            continue;
        dyn_jit_model jm;
        load_ok(vdp_source, "vdp.c", opts[b], &jm);
        rk4_run(jm.model, NULL, 0, 15.0, 0.01, y);
        if (!same_bits(y[0], ref[0]) || !same_bits(y[1], ref[1]))
            print_error("%s: (%.17g, %.17g) != built-in (%.17g, %.17g)\n",
                        dyn_jit_backend_name(opts[b]->backend), y[0], y[1], ref[0], ref[1]);
        assert_true(same_bits(y[0], ref[0]) && same_bits(y[1], ref[1]));
        dyn_jit_unload(&jm);
    }
}

/* libtcc and the system compiler agree on a model with library calls and libm */
static void test_tcc_and_cc_agree(void **state)
{
    fixture *f = *state;
    if (!dyn_jit_backend_available(DYN_JIT_TCC))
        skip();
    char err[ERRLEN];
    dyn_jit_model a, b;
    assert_int_equal(dyn_jit_load_c_file(DYNKIT_SOURCE_DIR "/examples/models/spring_mass.c",
                                         &f->tcc, &a, err, sizeof err),
                     0);
    assert_int_equal(a.backend, DYN_JIT_TCC);
    assert_string_equal(a.so_path, "");
    load_ok(mech_source, "frame.c", &f->tcc, &b);
    dyn_jit_model a2, b2;
    assert_int_equal(dyn_jit_load_c_file(DYNKIT_SOURCE_DIR "/examples/models/spring_mass.c", &f->cc,
                                         &a2, err, sizeof err),
                     0);
    load_ok(mech_source, "frame.c", &f->cc, &b2);
    double ya[2], ya2[2], yb[3], yb2[3];
    rk4_run(a.model, "c", 0.3, 5.0, 0.01, ya);
    rk4_run(a2.model, "c", 0.3, 5.0, 0.01, ya2);
    rk4_run(b.model, NULL, 0, 2.0, 0.01, yb);
    rk4_run(b2.model, NULL, 0, 2.0, 0.01, yb2);
    for (int i = 0; i < 2; i++)
        assert_true(same_bits(ya[i], ya2[i]));
    for (int i = 0; i < 3; i++)
        assert_true(same_bits(yb[i], yb2[i]));
    dyn_jit_unload(&a);
    dyn_jit_unload(&b);
    dyn_jit_unload(&a2);
    dyn_jit_unload(&b2);
}

/* the translator's output (every .ode file in examples/models): both backends compile it
 * and give the same numbers bit for bit */
static void test_translated_examples_agree(void **state)
{
    fixture *f = *state;
    if (!dyn_jit_backend_available(DYN_JIT_TCC))
        skip();
    DIR *d = opendir(DYNKIT_SOURCE_DIR "/examples/models");
    assert_non_null(d);
    struct dirent *e;
    int count = 0;
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".ode") != 0)
            continue;
        char path[1024], err[ERRLEN];
        snprintf(path, sizeof path, "%s/examples/models/%s", DYNKIT_SOURCE_DIR, e->d_name);
        FILE *fp = fopen(path, "rb");
        assert_non_null(fp);
        static char text[1 << 16];
        size_t len = fread(text, 1, sizeof text, fp);
        fclose(fp);
        char *c_source = NULL;
        dyn_lang_diag diag;
        if (dyn_ode_to_c(path, text, len, &c_source, &diag, NULL, NULL) != 0) {
            print_error("%s: %s\n", path, dyn_lang_diag_format(&diag, err, sizeof err));
            fail();
        }
        dyn_jit_model a, b;
        load_ok(c_source, path, &f->cc, &a);
        load_ok(c_source, path, &f->tcc, &b);
        free(c_source);
        const dyn_model *m = a.model;
        double ya[TEST_MAX_N], yb[TEST_MAX_N];
        double h = m->step > 0 ? m->step : 0.01, t1 = fmin(m->t1 - m->t0, 1000 * h);
        rk4_run(a.model, NULL, 0, t1, h, ya);
        rk4_run(b.model, NULL, 0, t1, h, yb);
        for (int i = 0; i < m->n_states; i++)
            if (!same_bits(ya[i], yb[i])) {
                print_error("%s: state %d: cc %.17g, tcc %.17g\n", path, i, ya[i], yb[i]);
                fail();
            }
        dyn_jit_unload(&a);
        dyn_jit_unload(&b);
        count++;
    }
    closedir(d);
    assert_true(count > 0);
}

/* a model calling mech.h functions, loaded into this program (linked with the library and
 * exporting its symbols), computes what the same code compiled here computes */
static void test_model_calls_library(void **state)
{
    fixture *f = *state;
    const dyn_model here = {
        .name = "frame", .n_states = 3, .y0 = (const double[]){1.0, 0.5, -0.25}, .rhs = mech_rhs};
    double ref[3], y[3];
    rk4_run(&here, NULL, 0, 2.0, 0.01, ref);
    const dyn_jit_opts *opts[2] = {&f->cc, &f->tcc};
    for (int b = 0; b < 2; b++) {
        if (!dyn_jit_backend_available(opts[b]->backend))
            continue;
        dyn_jit_model jm;
        load_ok(mech_source, "frame.c", opts[b], &jm);
        rk4_run(jm.model, NULL, 0, 2.0, 0.01, y);
        for (int i = 0; i < 3; i++)
            assert_true(same_bits(y[i], ref[i]));
        dyn_jit_unload(&jm);
    }
}

/* the second load comes from the cache and runs no compiler: DYNKIT_CC is a script (in a
 * directory with a blank in its name) that counts its runs; a compilation removes stale
 * temporary files */
static void test_second_load_is_cached(void **state)
{
    fixture *f = *state;
    char script[512], count[512], text[1400];
    snprintf(script, sizeof script, "%s/counting cc", f->dir);
    snprintf(count, sizeof count, "%s/count", f->dir);
    snprintf(text, sizeof text, "#!/bin/sh\necho run >> '%s'\nexec cc \"$@\"\n", count);
    write_text(script, text);
    assert_int_equal(chmod(script, 0755), 0);
    setenv("DYNKIT_CC", script, 1);
    dyn_jit_opts opts = {.backend = DYN_JIT_AUTO, .cache_dir = f->cache};
    /* what an interrupted compilation left: removed by the next compilation after an hour */
    char old_tmp[512], new_tmp[512];
    assert_int_equal(mkdir(f->cache, 0755), 0);
    snprintf(old_tmp, sizeof old_tmp, "%s/tmp-1-1-1.so", f->cache);
    snprintf(new_tmp, sizeof new_tmp, "%s/tmp-2-2-2.so", f->cache);
    write_text(old_tmp, "x");
    write_text(new_tmp, "x");
    struct timeval two_hours_ago[2] = {{time(NULL) - 7200, 0}, {time(NULL) - 7200, 0}};
    assert_int_equal(utimes(old_tmp, two_hours_ago), 0);

    dyn_jit_model a, b, c;
    load_ok(vdp_source, "vdp.c", &opts, &a);
    assert_int_equal(a.backend, DYN_JIT_CC);
    assert_int_equal(a.cached, 0);
    assert_true(a.compile_seconds > 0);
    load_ok(vdp_source, "vdp.c", &opts, &b);
    assert_int_equal(b.cached, 1);
    assert_true(b.compile_seconds == 0);
    assert_int_not_equal(access(old_tmp, F_OK), 0);
    assert_int_equal(access(new_tmp, F_OK), 0);
    unlink(new_tmp);
    assert_string_equal(a.so_path, b.so_path);
    struct stat st;
    assert_int_equal(stat(count, &st), 0);
    assert_int_equal(st.st_size, 4); /* one "run\n" */
    /* another source, or other flags, compile again */
    dyn_jit_opts o3 = opts;
    o3.cflags = "-O1";
    load_ok(vdp_source, "vdp.c", &o3, &c);
    assert_int_equal(c.cached, 0);
    assert_string_not_equal(c.so_path, a.so_path);
    assert_int_equal(stat(count, &st), 0);
    assert_int_equal(st.st_size, 8);
    dyn_jit_unload(&a);
    dyn_jit_unload(&b);
    dyn_jit_unload(&c);
}

/* several processes compiling the same new source at once all succeed */
static void test_concurrent_first_loads(void **state)
{
    fixture *f = *state;
    enum { N = 4 };
    int gate[2];
    assert_int_equal(pipe(gate), 0);
    pid_t pids[N];
    for (int i = 0; i < N; i++) {
        pids[i] = fork();
        assert_true(pids[i] >= 0);
        if (pids[i] == 0) {
            char c, err[ERRLEN];
            close(gate[1]);
            if (read(gate[0], &c, 1) != 0) /* wait until the parent closes the gate */
                _exit(3);
            dyn_jit_model jm;
            if (dyn_jit_load_source(mech_source, strlen(mech_source), "frame.c", &f->cc, &jm, err,
                                    sizeof err) != 0) {
                fprintf(stderr, "child %d: %s\n", i, err);
                _exit(1);
            }
            double y[3], dy[3] = {0};
            jm.model->rhs(0.0, jm.model->y0, dy, NULL);
            mech_rhs(0.0, jm.model->y0, y, NULL);
            int ok = memcmp(y, dy, sizeof y) == 0;
            dyn_jit_unload(&jm);
            _exit(ok ? 0 : 2);
        }
    }
    close(gate[0]);
    close(gate[1]);
    for (int i = 0; i < N; i++) {
        int status;
        assert_int_equal(waitpid(pids[i], &status, 0), pids[i]);
        assert_true(WIFEXITED(status));
        assert_int_equal(WEXITSTATUS(status), 0);
    }
    dyn_jit_model jm;
    load_ok(mech_source, "frame.c", &f->cc, &jm);
    assert_int_equal(jm.cached, 1);
    dyn_jit_unload(&jm);
    /* no temporary file left behind: the include directory and one shared object */
    char cmd[700];
    snprintf(cmd, sizeof cmd, "test $(ls '%s' | wc -l) -eq 2", f->cache);
    assert_int_equal(system(cmd), 0);
}

/* a syntax error in the user's file: the compiler's message names the file and the line */
static void test_syntax_error_names_the_file(void **state)
{
    fixture *f = *state;
    char path[512], err[ERRLEN];
    snprintf(path, sizeof path, "%s/bad model.c", f->dir);
    write_text(path, "#include <dynkit/model.h>\n"
                     "\n"
                     "static int rhs(double t, const double *y, double *dydt, void *p)\n"
                     "{\n"
                     "    (void)t, (void)p;\n"
                     "    dydt[0] = -y[0] * stiffness;\n"
                     "    return 0;\n"
                     "}\n");
    const dyn_jit_opts *opts[2] = {&f->cc, &f->tcc};
    for (int b = 0; b < 2; b++) {
        if (!dyn_jit_backend_available(opts[b]->backend))
            continue;
        dyn_jit_model jm;
        assert_int_not_equal(dyn_jit_load_c_file(path, opts[b], &jm, err, sizeof err), 0);
        assert_null(jm.model);
        char where[600];
        snprintf(where, sizeof where, "%s:6:", path);
        if (!strstr(err, where) || !strstr(err, "stiffness"))
            print_error("%s: no '%s' in:\n%s\n", dyn_jit_backend_name(opts[b]->backend), where,
                        err);
        assert_non_null(strstr(err, where));
        assert_non_null(strstr(err, "stiffness"));
        assert_null(strstr(err, "tmp-")); /* no temporary file named */
    }
    /* a short buffer gets whole lines and a note */
    dyn_jit_model jm;
    char small[120];
    assert_int_not_equal(dyn_jit_load_c_file(path, &f->cc, &jm, small, sizeof small), 0);
    assert_true(strlen(small) < sizeof small);
    assert_non_null(strstr(small, "more line"));
    assert_non_null(strstr(small, "bad model.c"));
    /* generated code: #line directives name the .ode file's lines */
    const char generated[] = "#include <dynkit/model.h>\n"
                             "#line 12 \"lorenz.ode\"\n"
                             "static double f(double x) { return x +* ; }\n";
    assert_int_not_equal(dyn_jit_load_source(generated, strlen(generated), "lorenz.ode", &f->cc,
                                             &jm, err, sizeof err),
                         0);
    assert_non_null(strstr(err, "lorenz.ode:12:"));
}

/* run argv (the system compiler), 0 on success */
static int run_cc(const char *const argv[])
{
    pid_t pid = fork();
    if (pid == 0) {
        execvp(argv[0], (char *const *)argv);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

/* shared objects built by hand: wrong ABI, no ABI stamp, no entry point */
static void test_abi_mismatch_refused(void **state)
{
    fixture *f = *state;
    char src[512], so[512], inc[600], err[ERRLEN];
    snprintf(src, sizeof src, "%s/old.c", f->dir);
    snprintf(so, sizeof so, "%s/model.so", f->dir);
    snprintf(inc, sizeof inc, "-I%s/include", DYNKIT_SOURCE_DIR);
    const char *argv[] = {"cc", "-shared", "-fPIC", inc, "-o", so, src, NULL};
    dyn_jit_model jm;

    char text[4096];
    /* the ABI before the last change of the layout (2 added the band of the Jacobian) */
    snprintf(text, sizeof text, "%s\nconst unsigned dynkit_model_abi = %d;\n", vdp_source,
             DYN_MODEL_ABI - 1);
    write_text(src, text);
    assert_int_equal(run_cc(argv), 0);
    assert_int_not_equal(dyn_jit_load_shared(so, &jm, err, sizeof err), 0);
    char expect[160];
    snprintf(expect, sizeof expect,
             "model.so was built for model ABI %d, this dynkit reads ABI %d: recompile it",
             DYN_MODEL_ABI - 1, DYN_MODEL_ABI);
    assert_string_equal(err, expect);
    assert_null(jm.model);

    write_text(src, vdp_source); /* no stamp */
    unlink(so);
    assert_int_equal(run_cc(argv), 0);
    assert_int_not_equal(dyn_jit_load_shared(so, &jm, err, sizeof err), 0);
    assert_non_null(strstr(err, "model.so does not record a model ABI"));

    snprintf(text, sizeof text, "const unsigned dynkit_model_abi = %d;\nint x(void) { return 1; }\n",
             DYN_MODEL_ABI);
    write_text(src, text);
    unlink(so);
    assert_int_equal(run_cc(argv), 0);
    assert_int_not_equal(dyn_jit_load_shared(so, &jm, err, sizeof err), 0);
    assert_non_null(strstr(err, "model.so does not define the entry point dynkit_model()"));

    assert_int_not_equal(dyn_jit_load_shared("no-such-model.so", &jm, err, sizeof err), 0);
    assert_non_null(strstr(err, "cannot load the model no-such-model.so"));
}

/* models that fail the checks of what dynkit_model() returns */
static void test_bad_models_refused(void **state)
{
    fixture *f = *state;
    static const struct {
        const char *body, *message;
    } cases[] = {
        {"const dyn_model *dynkit_model(void) { return NULL; }",
         "null.c: dynkit_model() returned NULL instead of a model"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 0, .rhs = rhs, .y0 = y0_};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "has n_states = 0"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 1, .y0 = y0_};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "has no right-hand side"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 1, .rhs = rhs, .y0 = y0_,\n"
         "  .states = st, .jac_banded = 1, .jac_lower = 1};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "declares a band of its Jacobian with jac_lower = 1"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 1, .rhs = rhs, .y0 = y0_,\n"
         "  .states = (const dyn_var[]){{NULL, \"m\", \"\"}}};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "states 0 of the model has no name"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 1, .rhs = rhs, .y0 = y0_,\n"
         "  .states = st, .n_params = 1, .par_size = 8,\n"
         "  .params = (const dyn_param[]){{\"k\", \"1\", \"\", 8, 1.0}}};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "parameter 'k' of the model 'z' lies outside its parameter struct"},
        {"static const dyn_model m = {.name = \"z\", .n_states = 1, .rhs = rhs, .y0 = y0_,\n"
         "  .states = st, .n_outputs = 2};\n"
         "const dyn_model *dynkit_model(void) { return &m; }",
         "n_outputs = 2 but no outputs array"},
        {"int dynkit_modell(void) { return 0; }", "does not define the entry point"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[2048], err[ERRLEN];
        snprintf(text, sizeof text,
                 "#include <dynkit/model.h>\n"
                 "static int rhs(double t, const double *y, double *d, void *p)\n"
                 "{ (void)t, (void)p; d[0] = -y[0]; return 0; }\n"
                 "static const double y0_[] = {1.0};\n"
                 "static const dyn_var st[] = {{\"x\", \"m\", \"\"}};\n"
                 "%s\n",
                 cases[i].body);
        const dyn_jit_opts *opts[2] = {&f->cc, &f->tcc};
        for (int b = 0; b < 2; b++) {
            if (!dyn_jit_backend_available(opts[b]->backend))
                continue;
            dyn_jit_model jm;
            int rc =
                dyn_jit_load_source(text, strlen(text), "null.c", opts[b], &jm, err, sizeof err);
            if (rc == 0 || !strstr(err, cases[i].message))
                print_error("case %zu (%s): no '%s' in '%s'\n", i,
                            dyn_jit_backend_name(opts[b]->backend), cases[i].message, err);
            assert_int_not_equal(rc, 0);
            assert_non_null(strstr(err, cases[i].message));
            assert_null(jm.model);
        }
    }
}

/* no compiler: a message that says what to install */
static void test_missing_compiler(void **state)
{
    fixture *f = *state;
    char err[ERRLEN];
    dyn_jit_model jm;
    dyn_jit_opts opts = f->cc;
    opts.cc = "/nonexistent/dynkit-cc";
    assert_int_not_equal(
        dyn_jit_load_source(vdp_source, strlen(vdp_source), "vdp.c", &opts, &jm, err, sizeof err),
        0);
    assert_non_null(strstr(err, "the C compiler '/nonexistent/dynkit-cc' was not found"));
    assert_non_null(strstr(err, "apt-get install gcc"));
    assert_non_null(strstr(err, "DYNKIT_CC"));
    /* the automatic choice falls back to libtcc when there is no system compiler at all */
    if (dyn_jit_backend_available(DYN_JIT_TCC)) {
        const char *path = getenv("PATH"), *cc_env = getenv("CC");
        char *saved_path = path ? strdup(path) : NULL, *saved_cc = cc_env ? strdup(cc_env) : NULL;
        setenv("PATH", "/nonexistent", 1);
        unsetenv("CC");
        dyn_jit_opts automatic = {.cache_dir = f->cache};
        load_ok(vdp_source, "vdp.c", &automatic, &jm);
        assert_int_equal(jm.backend, DYN_JIT_TCC);
        dyn_jit_unload(&jm);
        if (saved_path)
            setenv("PATH", saved_path, 1);
        if (saved_cc)
            setenv("CC", saved_cc, 1);
        free(saved_path);
        free(saved_cc);
    }
    /* and a bad DYNKIT_JIT is named */
    setenv("DYNKIT_JIT", "gcc", 1);
    dyn_jit_opts automatic = {.cache_dir = f->cache};
    assert_int_not_equal(dyn_jit_load_source(vdp_source, strlen(vdp_source), "vdp.c", &automatic,
                                             &jm, err, sizeof err),
                         0);
    assert_non_null(strstr(err, "DYNKIT_JIT=gcc"));
    unsetenv("DYNKIT_JIT");
    /* a missing file */
    assert_int_not_equal(dyn_jit_load_c_file("/nonexistent/model.c", &f->cc, &jm, err, sizeof err),
                         0);
    assert_non_null(strstr(err, "cannot open /nonexistent/model.c"));
}

/* With the automatic choice (when this dynkit has libtcc), opts's compiler failing: libtcc
 * compiles van der Pol instead, the note says why, and the numbers are the built-in model's
 * bit for bit. */
static void libtcc_instead(dyn_jit_opts opts, const char *why)
{
    if (!dyn_jit_backend_available(DYN_JIT_TCC))
        return;
    dyn_jit_model jm;
    opts.backend = DYN_JIT_AUTO;
    load_ok(vdp_source, "vdp.c", &opts, &jm);
    assert_int_equal(jm.backend, DYN_JIT_TCC);
    assert_non_null(strstr(jm.note, why));
    assert_non_null(strstr(jm.note, "compiled with libtcc instead"));
    double ref[2], y[2];
    rk4_run(&dyn_model_vanderpol, NULL, 0, 15.0, 0.01, ref);
    rk4_run(jm.model, NULL, 0, 15.0, 0.01, y);
    assert_true(same_bits(y[0], ref[0]) && same_bits(y[1], ref[1]));
    dyn_jit_unload(&jm);
}

/* a compiler that never finishes (a script that sleeps 30 s) is stopped at the time limit,
 * 0.2 s: with the system compiler chosen the message names the bound, with the automatic
 * choice libtcc compiles the model instead, says so in the note, and gives van der Pol's
 * numbers bit for bit */
static void test_compiler_time_limit(void **state)
{
    fixture *f = *state;
    char script[512], err[ERRLEN];
    snprintf(script, sizeof script, "%s/slow cc", f->dir);
    write_text(script, "#!/bin/sh\nexec sleep 30\n");
    assert_int_equal(chmod(script, 0755), 0);
    dyn_jit_opts opts = f->cc;
    opts.cc = script;
    opts.cc_timeout = 0.2;
    dyn_jit_model jm;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    assert_int_not_equal(
        dyn_jit_load_source(vdp_source, strlen(vdp_source), "vdp.c", &opts, &jm, err, sizeof err),
        0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    assert_true((double)(t1.tv_sec - t0.tv_sec) < 20); /* stopped, not waited for */
    assert_non_null(strstr(err, "did not finish within 0.2 s and was stopped"));
    assert_non_null(strstr(err, "DYNKIT_CC_TIMEOUT"));
    /* the variable is read in decimal seconds: 0x10 is refused, not read as 16 */
    dyn_jit_opts env_opts = f->cc;
    env_opts.cc_timeout = 0;
    setenv("DYNKIT_CC_TIMEOUT", "0x10", 1);
    const int hex_rc = dyn_jit_load_source(vdp_source, strlen(vdp_source), "vdp.c", &env_opts,
                                           &jm, err, sizeof err);
    unsetenv("DYNKIT_CC_TIMEOUT");
    assert_int_not_equal(hex_rc, 0);
    assert_non_null(strstr(err, "DYNKIT_CC_TIMEOUT=0x10 is not a number of seconds > 0 "
                                "written in decimal"));
    libtcc_instead(opts, "did not finish within 0.2 s");
}

/* a directory (with a file in it), then a FIFO, planted under a compiled object's name: the
 * model is compiled again, the directory moved aside with a note (it made every later
 * compilation fail: an object cannot be renamed over a directory), the FIFO replaced without
 * blocking; the next load comes from the cache without a note */
static void test_what_is_planted_under_an_objects_name_is_moved_aside(void **state)
{
    fixture *f = *state;
    dyn_jit_model jm;
    load_ok(vdp_source, "vdp.c", &f->cc, &jm);
    char so[sizeof jm.so_path], inside[sizeof so + 16];
    snprintf(so, sizeof so, "%s", jm.so_path);
    dyn_jit_unload(&jm);
    for (int kind = 0; kind < 2; kind++) {
        assert_int_equal(unlink(so), 0);
        if (kind == 0) {
            assert_int_equal(mkdir(so, 0700), 0);
            snprintf(inside, sizeof inside, "%s/file", so);
            write_text(inside, "x");
        } else {
            assert_int_equal(mkfifo(so, 0600), 0);
        }
        load_ok(vdp_source, "vdp.c", &f->cc, &jm);
        assert_int_equal(jm.cached, 0);
        assert_non_null(strstr(jm.note, "is not a regular file"));
        if (kind == 0)
            assert_non_null(strstr(jm.note, "moved it aside to tmp-replaced-"));
        assert_null(strchr(jm.note, '\n'));
        double ref[2], y[2];
        rk4_run(&dyn_model_vanderpol, NULL, 0, 15.0, 0.01, ref);
        rk4_run(jm.model, NULL, 0, 15.0, 0.01, y);
        assert_true(same_bits(y[0], ref[0]) && same_bits(y[1], ref[1]));
        dyn_jit_unload(&jm);
        struct stat st;
        assert_int_equal(lstat(so, &st), 0);
        assert_true(S_ISREG(st.st_mode));
        load_ok(vdp_source, "vdp.c", &f->cc, &jm);
        assert_int_equal(jm.cached, 1);
        assert_string_equal(jm.note, "");
        dyn_jit_unload(&jm);
    }
    /* nothing of the planted directory is left in the cache */
    DIR *d = opendir(f->cache);
    assert_non_null(d);
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        assert_true(strncmp(e->d_name, "tmp-", 4) != 0);
    closedir(d);
}

/* a compiler that cannot write its output for want of room (a script that says what cc
 * says on a full disk, "No space left on device", and fails): with the system compiler named
 * the message says the cache cannot be written and what to do; with the automatic choice
 * libtcc compiles the model in memory instead, says why in the note, and gives van der Pol's
 * numbers bit for bit */
static void test_a_full_cache_falls_back_to_libtcc(void **state)
{
    fixture *f = *state;
    char script[512], err[ERRLEN];
    snprintf(script, sizeof script, "%s/full cc", f->dir);
    write_text(script, "#!/bin/sh\necho \"/usr/bin/ld: final link failed: No space left on "
                       "device\" >&2\nexit 1\n");
    assert_int_equal(chmod(script, 0755), 0);
    dyn_jit_opts opts = f->cc;
    opts.cc = script;
    dyn_jit_model jm;
    assert_int_not_equal(
        dyn_jit_load_source(vdp_source, strlen(vdp_source), "vdp.c", &opts, &jm, err, sizeof err),
        0);
    assert_non_null(strstr(err, "could not write its output (No space left on device)"));
    assert_non_null(strstr(err, "the cache of compiled models cannot be written"));
    assert_non_null(strstr(err, "DYNKIT_CACHE_DIR"));
    libtcc_instead(opts, "could not write its output (No space left on device)");
}

/* the cache directory: the option, then DYNKIT_CACHE_DIR, XDG_CACHE_HOME, HOME */
static void test_cache_dir(void **state)
{
    (void)state;
    char buf[512];
    dyn_jit_opts opts = {.cache_dir = "/x/y"};
    assert_int_equal(dyn_jit_cache_dir(&opts, buf, sizeof buf), 0);
    assert_string_equal(buf, "/x/y");
    char *saved[3];
    const char *names[3] = {"DYNKIT_CACHE_DIR", "XDG_CACHE_HOME", "HOME"};
    for (int i = 0; i < 3; i++) {
        const char *v = getenv(names[i]);
        saved[i] = v ? strdup(v) : NULL;
    }
    setenv("DYNKIT_CACHE_DIR", "/a", 1);
    setenv("XDG_CACHE_HOME", "/b", 1);
    setenv("HOME", "/c", 1);
    assert_int_equal(dyn_jit_cache_dir(NULL, buf, sizeof buf), 0);
    assert_string_equal(buf, "/a");
    unsetenv("DYNKIT_CACHE_DIR");
    assert_int_equal(dyn_jit_cache_dir(NULL, buf, sizeof buf), 0);
    assert_string_equal(buf, "/b/dynkit");
    unsetenv("XDG_CACHE_HOME");
    assert_int_equal(dyn_jit_cache_dir(NULL, buf, sizeof buf), 0);
    assert_string_equal(buf, "/c/.cache/dynkit");
    unsetenv("HOME");
    assert_int_not_equal(dyn_jit_cache_dir(NULL, buf, sizeof buf), 0);
    for (int i = 0; i < 3; i++) {
        if (saved[i])
            setenv(names[i], saved[i], 1);
        free(saved[i]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_spring_mass_example, setup, teardown),
        cmocka_unit_test_setup_teardown(test_vanderpol_bit_for_bit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_tcc_and_cc_agree, setup, teardown),
        cmocka_unit_test_setup_teardown(test_translated_examples_agree, setup, teardown),
        cmocka_unit_test_setup_teardown(test_model_calls_library, setup, teardown),
        cmocka_unit_test_setup_teardown(test_second_load_is_cached, setup, teardown),
        cmocka_unit_test_setup_teardown(test_concurrent_first_loads, setup, teardown),
        cmocka_unit_test_setup_teardown(test_syntax_error_names_the_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_abi_mismatch_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_models_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_compiler, setup, teardown),
        cmocka_unit_test_setup_teardown(test_compiler_time_limit, setup, teardown),
        cmocka_unit_test_setup_teardown(test_what_is_planted_under_an_objects_name_is_moved_aside,
                                        setup, teardown),
        cmocka_unit_test_setup_teardown(test_a_full_cache_falls_back_to_libtcc, setup, teardown),
        cmocka_unit_test(test_cache_dir),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
