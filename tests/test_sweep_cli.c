/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit sweep through the command line (cli/commands/cmd_sweep.c):
 * - `dynkit sweep pendulum --vary dphi=0.1:1.9:50 --reduce event:turn` (dop853 at rtol =
 *   atol = 1e-12 over 0:5) gives the period curve: each first turn at K(k)/w with
 *   k = dphi0/(2w), K by the arithmetic-geometric mean, to 1e-10 s; the varied values end
 *   exactly at 0.1 and 1.9;
 * - the same bytes for --threads 1 and 2 (a Monte Carlo table of 2000 runs);
 * - --from FILE.csv gives the rows of the same values given by --vary;
 * - a failing run (van der Pol with mu = 1000 under RK4 at h = 0.5) is a row of nan with the
 *   status nonfinite, and the others are ok;
 * - --resume: a table cut after some rows (as Ctrl-C leaves it) is completed to the bytes of
 *   the uninterrupted sweep; a real SIGINT writes the finished runs, exits 130, says how to
 *   resume; a table of another sweep is refused;
 * - every example of `dynkit sweep --help` runs (exit 0) and every option is in the help;
 * - a model file (.ode) gives the built-in model's bytes on 1 and 2 threads;
 * - dynkit plot TABLE.csv: lines and a heat map; .json and .npy output;
 * - usage errors name the bad input. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

static double ellip_k(double k)
{
    double a = 1.0, b = sqrt(1.0 - k * k);
    for (int i = 0; i < 60 && fabs(a - b) > 1e-17 * a; i++) {
        const double an = 0.5 * (a + b);
        b = sqrt(a * b);
        a = an;
    }
    return DYN_PI / (a + b);
}

static void test_period_curve(void **state)
{
    (void)state;
    cli_result r = cli("sweep pendulum --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:5 "
                       "--vary dphi=0.1:1.9:50 --reduce event:turn");
    assert_int_equal(r.status, 0);
    assert_true(strncmp(r.out, "run,dphi,event_turn\n", 20) == 0);
    assert_int_equal(csv_rows(r.out), 50);
    const char *p = strchr(r.out, '\n') + 1;
    double worst = 0.0;
    for (int i = 0; i < 50; i++) {
        char *end;
        assert_int_equal(strtol(p, &end, 10), i);
        const double dphi = strtod(end + 1, &end);
        const double turn = strtod(end + 1, &end);
        assert_true(*end == '\n');
        if (i == 0)
            assert_true(dphi == 0.1);
        if (i == 49)
            assert_true(dphi == 1.9);
        /* g = l: w = 1; phi_max from the energy: sin(phi_max/2) = dphi0 / (2 w) */
        worst = fmax(worst, fabs(turn - ellip_k(dphi / 2.0)));
        p = end + 1;
    }
    assert_true(worst < 1e-10);
    cli_free(&r);
}

static void test_threads_same_bytes(void **state)
{
    (void)state;
    const char *args = "sweep vanderpol --method dp45 --rtol 1e-6 --tspan 0:5 "
                       "--sample 'mu=uniform(0.5,3)' --sample 'y1=normal(2,0.2)' --runs 2000 "
                       "--seed 42 --reduce final,max:y2,mean:y1,argmin:y2";
    cli_result a = cli("%s --threads 1", args);
    cli_result b = cli("%s --threads 2", args);
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_int_equal(csv_rows(a.out), 2000);
    assert_int_equal(a.out_len, b.out_len);
    assert_memory_equal(a.out, b.out, a.out_len);
    cli_free(&a);
    cli_free(&b);
}

static void test_from(void **state)
{
    (void)state;
    FILE *f = fopen(cli_path("runs.csv"), "w");
    assert_non_null(f);
    fputs("l,dphi\n2,0.5\n2,1\n5,0.5\n5,1\n", f);
    fclose(f);
    cli_result a = cli_in_tmpdir("sweep pendulum --method rk4 --step 0.01 --tspan 0:3 "
                                 "--from runs.csv --reduce final,max:energy");
    cli_result b = cli("sweep pendulum --method rk4 --step 0.01 --tspan 0:3 --vary l=2,5 "
                       "--vary dphi=0.5,1 --reduce final,max:energy");
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_string_equal(a.out, b.out);
    assert_true(strncmp(a.out, "run,l,dphi,final_phi,final_dphi,max_energy\n", 43) == 0);
    cli_free(&a);
    cli_free(&b);
    /* a sweep's table, CSV or JSON, failed runs and all: its runs again (its varied names) */
    cli_result t = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 "
                                 "--vary mu=1,1000,0.5 --reduce final,max:y1 --output t.json");
    assert_int_equal(t.status, 0);
    cli_free(&t);
    t = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 --vary mu=1,1000,0.5 "
                      "--reduce final,max:y1 --output t.csv");
    assert_int_equal(t.status, 0);
    cli_free(&t);
    char *want = cli_read_file(cli_path("t.csv"), NULL);
    for (int k = 0; k < 2; k++) {
        t = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 --from t.%s "
                          "--reduce final,max:y1",
                          k ? "json" : "csv");
        CHECK(t.status == 0 && strcmp(t.out, want) == 0, "--from t.%s: exit %d: %s%s",
              k ? "json" : "csv", t.status, t.out, t.err);
        cli_free(&t);
    }
    free(want);
    unlink(cli_path("t.csv"));
    unlink(cli_path("t.json"));
    /* a column that is neither a parameter nor a state */
    f = fopen(cli_path("bad.csv"), "w");
    assert_non_null(f);
    fputs("l,speed\n2,0.5\n", f);
    fclose(f);
    cli_result e = cli_in_tmpdir("sweep pendulum --from bad.csv");
    assert_int_equal(e.status, 2);
    assert_non_null(strstr(e.err, "'speed' is neither a parameter nor a state of pendulum"));
    cli_free(&e);
    unlink(cli_path("bad.csv"));
}

static void test_failed_run(void **state)
{
    (void)state;
    cli_result r = cli("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 "
                       "--vary mu=1,1000,0.5 --reduce final,max:y1");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "run,mu,final_y1,final_y2,max_y1,status\n"));
    assert_non_null(strstr(r.out, "\n1,1000,nan,nan,nan,nonfinite\n"));
    assert_non_null(strstr(r.out, "\n0,1,"));
    assert_non_null(strstr(r.out, "nonfinite\n2,0.5,"));
    assert_non_null(strstr(r.err, "1 of 3 runs failed"));
    cli_free(&r);
    /* the data files of run: JSON (nan as null, the status as a number), NPY */
    r = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 "
                      "--vary mu=1,1000,0.5 --reduce final,argmax:y1 --output t.json");
    assert_int_equal(r.status, 0);
    char *json = cli_read_file(cli_path("t.json"), NULL);
    assert_non_null(strstr(json, "\"columns\": [\"run\", \"mu\", \"final_y1\", \"final_y2\", "
                                 "\"argmax_y1\", \"status\"]"));
    /* the counts: the model's states, the varied names, the reductions */
    assert_non_null(strstr(json, "\"states\": 2,\n  \"varied\": 1,\n  \"reduced\": 3,\n"));
    assert_non_null(strstr(json, "\"units\": [\"1\", \"1\", \"1\", \"1/s\", \"s\", \"1\"]"));
    assert_non_null(strstr(json, "[1,1000,null,null,null,3]"));
    free(json);
    cli_free(&r);
    r = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.1 --tspan 0:2 --vary mu=1,2 "
                      "--output t.npy");
    assert_int_equal(r.status, 0);
    size_t len;
    char *npy = cli_read_file(cli_path("t.npy"), &len);
    assert_true(len > 10 && memcmp(npy, "\x93NUMPY", 6) == 0);
    assert_non_null(strstr(npy + 10, "'shape': (2, 4)"));
    free(npy);
    cli_free(&r);
    unlink(cli_path("t.json"));
    unlink(cli_path("t.npy"));
}

static void test_resume(void **state)
{
    (void)state;
    const char *args = "sweep vanderpol --method rk4 --step 0.01 --tspan 0:10 "
                       "--vary mu=0.5:3:40 --vary y1=1,2 --reduce final,max:y2";
    cli_result full = cli_in_tmpdir("%s --output full.csv", args);
    assert_int_equal(full.status, 0);
    size_t len;
    char *whole = cli_read_file(cli_path("full.csv"), &len);
    assert_int_equal(csv_rows(whole), 80);
    /* as an interrupted sweep leaves it: the header and some finished rows, not in order */
    FILE *f = fopen(cli_path("part.csv"), "w");
    assert_non_null(f);
    const char *p = whole;
    for (int line = 0; *p; line++) {
        const char *nl = strchr(p, '\n');
        if (line == 0 || line % 3 == 1)
            fwrite(p, 1, (size_t)(nl - p + 1), f);
        p = nl + 1;
    }
    fclose(f);
    cli_result res = cli_in_tmpdir("%s --resume part.csv", args);
    assert_int_equal(res.status, 0);
    size_t len2;
    char *resumed = cli_read_file(cli_path("part.csv"), &len2);
    assert_int_equal(len, len2);
    assert_memory_equal(whole, resumed, len);
    /* a table whose reductions are named OP:NAME, as earlier versions wrote them: resumed,
     * written with the names of now */
    f = fopen(cli_path("old.csv"), "w");
    assert_non_null(f);
    const char *body = strchr(whole, '\n') + 1;
    fprintf(f, "run,mu,y1,final:y1,final:y2,max:y2\n%.*s", (int)(strchr(body, '\n') + 1 - body),
            body);
    fclose(f);
    cli_result old = cli_in_tmpdir("%s --resume old.csv", args);
    assert_int_equal(old.status, 0);
    char *renamed = cli_read_file(cli_path("old.csv"), NULL);
    assert_string_equal(renamed, whole);
    free(renamed);
    cli_free(&old);
    unlink(cli_path("old.csv"));
    /* the last row cut mid-line, as a crash leaves it (no line end): dropped with a note and
     * its run made again; a UTF-8 BOM before the header, as editors write it, is read as
     * the other readers read it; both complete to the bytes of the whole table */
    const char *third = strchr(strchr(strchr(whole, '\n') + 1, '\n') + 1, '\n') + 1;
    f = fopen(cli_path("cut.csv"), "w");
    assert_non_null(f);
    fprintf(f, "\xEF\xBB\xBF%.*s", (int)(third - whole + 7), whole);
    fclose(f);
    cli_result cut = cli_in_tmpdir("%s --resume cut.csv", args);
    CHECK(cut.status == 0 && strstr(cut.err, "cut.csv:4: the last row is cut off"),
          "a table whose last row is cut: exit %d: %s", cut.status, cut.err);
    char *completed = cli_read_file(cli_path("cut.csv"), NULL);
    CHECK(strcmp(completed, whole) == 0, "the cut table is not completed to the whole one");
    free(completed);
    cli_free(&cut);
    unlink(cli_path("cut.csv"));
    /* another sweep's table is refused */
    cli_result other = cli_in_tmpdir("sweep vanderpol --vary mu=1,2 --resume full.csv");
    assert_int_equal(other.status, 2);
    assert_non_null(strstr(other.err, "is not a table of this sweep"));
    /* so is a table of the same header and runs made with another step, tspan or method
     * (its runs would be mixed with runs of these options), and the file is left as it was */
    static const char *const others[] = {
        "sweep vanderpol --method rk4 --step 0.005 --tspan 0:10",
        "sweep vanderpol --method rk4 --step 0.01 --tspan 0:9",
        "sweep vanderpol --method heun --step 0.01 --tspan 0:10",
        "sweep vanderpol --method rk4 --step 0.01 --tspan 0:10 --init y2=0.1"};
    for (size_t i = 0; i < sizeof others / sizeof others[0]; i++) {
        cli_free(&other);
        other = cli_in_tmpdir("%s --vary mu=0.5:3:40 --vary y1=1,2 --reduce final,max:y2 "
                              "--resume full.csv --output again.csv",
                              others[i]);
        CHECK(other.status == 2 && strstr(other.err, "was made with other run options"),
              "%s --resume of a table made with --step 0.01 --tspan 0:10 (rk4): exit %d: %s",
              others[i], other.status, other.err);
        struct stat st;
        CHECK(stat(cli_path("again.csv"), &st) != 0, "%s: a refused resume wrote again.csv",
              others[i]);
    }
    cli_free(&full);
    cli_free(&res);
    cli_free(&other);
    free(whole);
    free(resumed);
    unlink(cli_path("full.csv"));
    unlink(cli_path("part.csv"));
}

/* A real Ctrl-C: the finished runs are written, exit 130, the way to resume is printed;
 * the resumed table equals the uninterrupted one. */
static void test_interrupt(void **state)
{
    (void)state;
    const char *args = "sweep vanderpol --method rk4 --step 0.001 "
                       "--vary mu=0.5:3:300 --reduce final --threads 2 --tspan 0:60";
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && exec '%s' %s --output int.csv 2>int.err", cli_tmpdir,
             DYNKIT_CLI, args);
    /* a signal that comes before the sweep has started (the program starting, the model
     * opening) ends the program as usual: then try again with a longer delay */
    int w = 0;
    for (int attempt = 0; attempt < 6; attempt++) {
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
            _exit(127);
        }
        const long ms = 300L << attempt;
        struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
        nanosleep(&ts, NULL);
        kill(pid, SIGINT);
        waitpid(pid, &w, 0);
        if (!(WIFSIGNALED(w) && WTERMSIG(w) == SIGINT))
            break;
    }
    char *err = cli_read_file(cli_path("int.err"), NULL);
    if (WEXITSTATUS(w) == 130) {
        assert_non_null(strstr(err, "interrupted:"));
        assert_non_null(strstr(err, "--resume int.csv"));
    } else {
        assert_int_equal(WEXITSTATUS(w), 0); /* finished before the signal came */
    }
    free(err);
    cli_result res = cli_in_tmpdir("%s --resume int.csv", args);
    assert_int_equal(res.status, 0);
    cli_result full = cli_in_tmpdir("%s --threads 1", args);
    assert_int_equal(full.status, 0);
    char *resumed = cli_read_file(cli_path("int.csv"), NULL);
    assert_string_equal(resumed, full.out);
    free(resumed);
    cli_free(&res);
    cli_free(&full);
    unlink(cli_path("int.csv"));
    unlink(cli_path("int.err"));
}

/* SIGINT ignored when dynkit starts (a background job of a shell without job control,
 * nohup) stays ignored during a sweep: a SIGINT sent while it runs neither stops it nor
 * cuts its table; it finishes with exit 0 and every run. */
static void test_ignored_interrupt_stays_ignored(void **state)
{
    (void)state;
    const char *args = "sweep vanderpol --method rk4 --step 0.001 "
                       "--vary mu=0.5:3:200 --reduce final --threads 2 --tspan 0:60";
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && exec '%s' %s --output ign.csv 2>ign.err", cli_tmpdir,
             DYNKIT_CLI, args);
    /* ignored before the fork, so that the child has it ignored from its first instant
     * (set in the child, a signal could come before the child ran, on a loaded machine),
     * and inherited through exec, as a shell's & does */
    void (*was)(int) = signal(SIGINT, SIG_IGN);
    pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    signal(SIGINT, was);
    assert_true(pid >= 0);
    int w = 0;
    for (int k = 0; k < 8; k++) { /* while it starts, opens the model and runs */
        struct timespec ts = {0, 150000000L};
        nanosleep(&ts, NULL);
        kill(pid, SIGINT);
    }
    waitpid(pid, &w, 0);
    CHECK(WIFEXITED(w) && WEXITSTATUS(w) == 0, "a sweep with SIGINT ignored: %s %d",
          WIFSIGNALED(w) ? "signal" : "exit", WIFSIGNALED(w) ? WTERMSIG(w) : WEXITSTATUS(w));
    char *table = cli_read_file(cli_path("ign.csv"), NULL);
    CHECK(table && csv_rows(table) == 200, "the table of a sweep with SIGINT ignored has %d rows",
          table ? csv_rows(table) : -1);
    free(table);
    unlink(cli_path("ign.csv"));
    unlink(cli_path("ign.err"));
}

/* Every example of the help runs; every option is described. */
static void test_help_examples(void **state)
{
    (void)state;
    cli_result h = cli("sweep --help");
    assert_int_equal(h.status, 0);
    static const char *const options[] = {"--vary", "--sample", "--runs", "--seed", "--from",
                                          "--reduce", "--threads", "--output", "--resume",
                                          "--bands", "--quiet"};
    for (size_t k = 0; k < sizeof options / sizeof options[0]; k++)
        assert_non_null(strstr(h.out, options[k]));
    FILE *f = fopen(cli_path("runs.csv"), "w");
    assert_non_null(f);
    fputs("l,dphi\n2,0.5\n5,1\n", f);
    fclose(f);
    /* the examples' model files, as from the source tree */
    unlink(cli_path("examples"));
    assert_int_equal(symlink(DYNKIT_SOURCE_DIR "/examples", cli_path("examples")), 0);
    int examples = 0;
    for (const char *p = strstr(h.out, "\n  dynkit sweep "); p;
         p = strstr(p + 1, "\n  dynkit sweep ")) {
        const char *start = p + strlen("\n  dynkit ");
        const char *nl = strchr(start, '\n');
        char args[1024];
        snprintf(args, sizeof args, "%.*s", (int)(nl - start), start);
        cli_result r = cli_in_tmpdir("%s", args);
        if (r.status != 0)
            fprintf(stderr, "example failed: dynkit %s\n%s", args, r.err);
        assert_int_equal(r.status, 0);
        assert_true(csv_rows(r.out) > 0 || strstr(args, "--output") || strstr(args, "--resume"));
        cli_free(&r);
        examples++;
    }
    assert_true(examples >= 5);
    char *mc = cli_read_file(cli_path("mc.csv"), NULL);
    assert_int_equal(csv_rows(mc), 1000);
    free(mc);
    /* 1000 runs of the noise: the band table has the grid's 501 times */
    char *bands = cli_read_file(cli_path("ou_bands.csv"), NULL);
    assert_non_null(bands);
    assert_int_equal(csv_rows(bands), 501);
    free(bands);
    cli_free(&h);
    unlink(cli_path("mc.csv"));
    unlink(cli_path("ou_bands.csv"));
    unlink(cli_path("ou_runs.csv"));
    unlink(cli_path("examples"));
}

/* The same runs with sriw1 (Rößler's SRIW1, adaptive): the same run table and bands on 1 and
 * 3 threads, and the mean at t = 5 within 5 standard errors of the closed form. */
static void test_noise_bands_sriw1(void **state)
{
    (void)state;
    const char *ou = DYNKIT_SOURCE_DIR "/examples/models/ornstein_uhlenbeck.ode";
    cli_result a = cli_in_tmpdir("sweep %s --method sriw1 --runs 800 --seed 4 --threads 1 "
                                 "--bands s1.csv --quiet", ou);
    cli_result b = cli_in_tmpdir("sweep %s --method sriw1 --runs 800 --seed 4 --threads 3 "
                                 "--bands s3.csv --quiet", ou);
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_string_equal(a.out, b.out);
    char *t1 = cli_read_file(cli_path("s1.csv"), NULL), *t3 = cli_read_file(cli_path("s3.csv"), NULL);
    assert_non_null(t1);
    assert_non_null(t3);
    assert_string_equal(t1, t3);
    const char *last = t1 + strlen(t1) - 2;
    while (last > t1 && *last != '\n')
        last--;
    double t, mean, p5, p50, p95;
    assert_int_equal(sscanf(last + 1, "%lf,%lf,%lf,%lf,%lf", &t, &mean, &p5, &p50, &p95), 5);
    const double m = 0.5 + 1.5 * exp(-5.0), sd = 0.3 * sqrt((1 - exp(-10.0)) / 2);
    assert_true(t == 5.0);
    assert_true(fabs(mean - m) < 5 * sd / sqrt(800.0));
    free(t1);
    free(t3);
    cli_free(&a);
    cli_free(&b);
    unlink(cli_path("s1.csv"));
    unlink(cli_path("s3.csv"));
}

/* Runs over the noise of the Ornstein-Uhlenbeck example: the band table's mean and
 * percentiles at t = 5 against the closed form (mean 0.5 + 1.5 e^-5, standard deviation
 * 0.3 sqrt((1 - e^-10)/2)), and the same bytes on 1 and 3 threads. */
static void test_noise_bands(void **state)
{
    (void)state;
    const char *ou = DYNKIT_SOURCE_DIR "/examples/models/ornstein_uhlenbeck.ode";
    cli_result a = cli_in_tmpdir("sweep %s --runs 800 --seed 4 --threads 1 --bands b1.csv "
                                 "--quiet", ou);
    cli_result b = cli_in_tmpdir("sweep %s --runs 800 --seed 4 --threads 3 --bands b3.json "
                                 "--quiet", ou);
    cli_result c = cli_in_tmpdir("sweep %s --runs 800 --seed 4 --threads 3 --bands b3.csv "
                                 "--quiet", ou);
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_int_equal(c.status, 0);
    assert_string_equal(a.out, c.out); /* the run table */
    char *t1 = cli_read_file(cli_path("b1.csv"), NULL), *t3 = cli_read_file(cli_path("b3.csv"), NULL);
    assert_non_null(t1);
    assert_non_null(t3);
    assert_string_equal(t1, t3);
    const char *last = t1 + strlen(t1) - 2;
    while (last > t1 && *last != '\n')
        last--;
    double t, mean, p5, p50, p95;
    assert_int_equal(sscanf(last + 1, "%lf,%lf,%lf,%lf,%lf", &t, &mean, &p5, &p50, &p95), 5);
    const double m = 0.5 + 1.5 * exp(-5.0), sd = 0.3 * sqrt((1 - exp(-10.0)) / 2);
    assert_true(t == 5.0);
    assert_true(fabs(mean - m) < 5 * sd / sqrt(800.0));
    assert_true(fabs(p50 - m) < 0.04);
    assert_true(fabs(p5 - (m - 1.6449 * sd)) < 0.06 && fabs(p95 - (m + 1.6449 * sd)) < 0.06);
    free(t1);
    free(t3);
    cli_free(&a);
    cli_free(&b);
    cli_free(&c);
    cli_result p = cli_in_tmpdir("plot b1.csv --output b1.svg");
    assert_int_equal(p.status, 0);
    char *svg = cli_read_file(cli_path("b1.svg"), NULL);
    assert_non_null(svg);
    assert_non_null(strstr(svg, "<polygon"));
    assert_non_null(strstr(svg, "mean x (shaded: 5% to 95% of the runs)"));
    free(svg);
    cli_free(&p);
    /* a picture's --compare runs take the methods for noise only */
    cli_result r = cli_in_tmpdir("plot %s --y x --compare rk4 --output c.svg", ou);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "only euler (Euler-Maruyama), rkmil and sriw1"));
    cli_free(&r);
    static const char *const files[] = {"b1.csv", "b3.csv", "b3.json", "b1.svg"};
    for (size_t k = 0; k < sizeof files / sizeof *files; k++)
        unlink(cli_path(files[k]));
}

/* Runs of a noisy integrate-and-fire neuron with a global reset: the same table on 1 and 3
 * threads (the seed and the run's number fix each run's noise, events and all), and its
 * mean spike count over 100 s that of a renewal process of inverse Gaussian intervals
 * (mean 1, variance 0.09): 100 + (0.09 - 1)/2, standard deviation sqrt(100 * 0.09). */
static void test_noise_events(void **state)
{
    (void)state;
    const char *f = DYNKIT_SOURCE_DIR "/tests/xppaut/noise/noisy_if.ode";
    cli_result a = cli_in_tmpdir("sweep %s --runs 24 --seed 4 --threads 1 "
                                 "--reduce count:spike,event:spike,final --quiet", f);
    cli_result b = cli_in_tmpdir("sweep %s --runs 24 --seed 4 --threads 3 "
                                 "--reduce count:spike,event:spike,final --quiet", f);
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_string_equal(a.out, b.out);
    assert_int_equal(csv_rows(a.out), 24);
    double sum = 0.0;
    int runs = 0;
    for (const char *p = strchr(a.out, '\n'); p && p[1]; p = strchr(p + 1, '\n')) {
        int run;
        double count;
        if (sscanf(p + 1, "%d,%lf", &run, &count) == 2) {
            sum += count;
            runs++;
        }
    }
    assert_int_equal(runs, 24);
    const double mean = sum / runs, want = 100.0 + (0.09 - 1.0) / 2.0;
    if (!(fabs(mean - want) < 5.0 * 3.0 / sqrt(24.0)))
        fprintf(stderr, "mean spike count %g, renewal theory %g\n", mean, want);
    assert_true(fabs(mean - want) < 5.0 * 3.0 / sqrt(24.0));
    cli_free(&a);
    cli_free(&b);
}

static void test_errors(void **state)
{
    (void)state;
    static const struct {
        const char *args, *message;
    } cases[] = {
        {"sweep pendulum --vary mass=1:2:3", "'mass' is neither a parameter nor a state"},
        {"sweep pendulum --vary l=1:2", "A:B:N needs two numbers and a count"},
        {"sweep pendulum --vary l=1,x", "'x' is not a number"},
        {"sweep pendulum --sample 'l=uniform(1,2)'", "--sample needs --runs N"},
        {"sweep pendulum --sample 'l=gauss(1,2)' --runs 3", "uniform(A,B), normal(MEAN,SD)"},
        {"sweep pendulum --sample 'l=uniform(2,1)' --runs 3", "needs A < B"},
        {"sweep pendulum --vary l=1,2 --sample 'm=uniform(1,2)' --runs 3", "one way"},
        {"sweep pendulum", "give the runs"},
        {"sweep pendulum --vary l=1,2 --final", "--final does not apply to a sweep"},
        {"sweep pendulum --vary l=1,2 --reduce max:speed", "neither a state nor an output"},
        {"sweep pendulum --vary l=1,2 --reduce event:top", "events: turn, bottom"},
        {"sweep pendulum --vary l=1,2 --threads 0", "--threads '0'"},
        {"sweep pendulum --vary l=1,2 --runs 5", "--runs and --seed go with --sample"},
        {"sweep " DYNKIT_SOURCE_DIR "/examples/models/ornstein_uhlenbeck.ode --runs 5 --method "
         "rk4", "cannot integrate: use euler"},
        {"sweep " DYNKIT_SOURCE_DIR "/examples/models/ornstein_uhlenbeck.ode --runs 5 --bands "
         "b.csv --resume r.csv", "--bands with --resume"},
        {"sweep pendulum --runs 5", "give the runs"},
        {"sweep pendulum --vary l=1,2 --method sriw1", "--method sriw1 integrates models with "
         "noise (wiener, normal, ran), and pendulum has none"},
        {"sweep " DYNKIT_SOURCE_DIR "/tests/xppaut/noise/draws.ode --runs 2 --method sriw1",
         "--method sriw1 needs noise that enters the equations as c*w"},
        {"sweep " DYNKIT_SOURCE_DIR "/examples/models/ornstein_uhlenbeck.ode --runs 2 --method "
         "srw1", "did you mean 'sriw1'?"},
        {"sweep " DYNKIT_SOURCE_DIR "/tests/xppaut/noise/noisy_if.ode --runs 2 --method sriw1",
         "--method sriw1 does not locate events"},
        {"sweep pendulum --vary l=1,l=2", "'l=2' is not a number"},
        {"sweep pendulum --vary l=1,2 --vary l=3", "varied twice"},
        {"sweep pendulum --vary l=1,2 --output t.txt", "unknown file extension '.txt'"},
        {"sweep pendulum --vary l=1,2 --resume missing.csv", "cannot open missing.csv"},
        {"sweep", "missing MODEL"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cli_result r = cli_in_tmpdir("%s", cases[k].args);
        if (r.status != 2 || !strstr(r.err, cases[k].message))
            fprintf(stderr, "dynkit %s: status %d\n%s", cases[k].args, r.status, r.err);
        assert_int_equal(r.status, 2);
        assert_non_null(strstr(r.err, cases[k].message));
        cli_free(&r);
    }
    /* a sweep's .npz and .mat have a variable per column: a varied parameter named like
     * another of their variables is refused before the runs */
    FILE *f = fopen(cli_path("clash.ode"), "w");
    assert_non_null(f);
    fputs("par step=1\nx'=-step*x\ninit x=1\ndone\n", f);
    fclose(f);
    cli_result c = cli_in_tmpdir("sweep clash.ode --vary step=1,2 --output c.npz");
    CHECK(c.status == 2 && strstr(c.err, "the column step would have the name of another "
                                         "variable of the .npz file"),
          "a column named step in .npz: exit %d: %s", c.status, c.err);
    cli_free(&c);
    unlink(cli_path("clash.ode"));
    /* parameters the model refuses: a row with the status 'parameters' */
    cli_result r = cli("sweep pendulum --method rk4 --step 0.1 --tspan 0:1 --vary l=-1,1");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "\n0,-1,nan,nan,parameters\n"));
    cli_free(&r);
    /* an event that never occurs: a note */
    r = cli("sweep pendulum --tspan 0:1 --vary dphi=0.5,1 --reduce event:turn");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "event turn occurred in no run within 0:1 s"));
    cli_free(&r);
}

/* dynkit plot TABLE.csv: lines against one varied name; a heat map over two with a colour
 * bar, a cell per run, failed runs grey; errors name the accepted columns. */
static void test_plot_table(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("sweep pendulum --method rk4 --step 0.01 --tspan 0:5 "
                                 "--vary dphi=0.5:1.5:5 --reduce max:height,event:turn "
                                 "--output p.csv");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot p.csv --output p.svg");
    assert_int_equal(r.status, 0);
    char *svg = cli_read_file(cli_path("p.svg"), NULL);
    assert_non_null(strstr(svg, "<svg"));
    assert_non_null(strstr(svg, "<polyline"));
    assert_non_null(strstr(svg, "event_turn"));
    assert_non_null(strstr(svg, "max_height"));
    free(svg);
    cli_free(&r);
    /* the same sweep's JSON table carries the units: the axes are labelled with them (a
     * reduction may be named as in --reduce) */
    r = cli_in_tmpdir("sweep pendulum --method rk4 --step 0.01 --tspan 0:5 "
                      "--vary dphi=0.5:1.5:5 --reduce max:height,event:turn --output p.json");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot p.json --y max:height --output pj.svg");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    svg = cli_read_file(cli_path("pj.svg"), NULL);
    CHECK(strstr(svg, ">dphi [rad/s]</text>") && strstr(svg, ">max_height [m]</text>"),
          "the axes of a JSON table's plot are not labelled with units:\n%.2000s", svg);
    free(svg);
    /* a height in m and a time in s are not drawn on one axis: a panel each, as the plots
     * of a model's run */
    r = cli_in_tmpdir("plot p.json --y max_height,event_turn --output pu.svg");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    svg = cli_read_file(cli_path("pu.svg"), NULL);
    int frames = 0;
    for (const char *q = svg; (q = strstr(q, "<rect class=\"frame\"")) != NULL; q++)
        frames++;
    CHECK(frames == 2 && strstr(svg, ">max_height [m]</text>") &&
              strstr(svg, ">event_turn [s]</text>"),
          "m and s on one axis (%d panels):\n%.2000s", frames, svg);
    free(svg);
    unlink(cli_path("pu.svg"));
    r = cli_in_tmpdir("sweep pendulum --method rk4 --step 0.01 --tspan 0:5 --vary l=1,2 "
                      "--vary dphi=0.5:1.5:5 --reduce max:height,event:turn --output pg.json");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot pg.json --y event_turn");
    CHECK(r.status == 0 && strstr(r.out, ">l [m]</text>") && strstr(r.out, ">dphi [rad/s]</text>") &&
              strstr(r.out, ">event_turn [s]</text>"),
          "a heat map of a JSON table: exit %d: %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("plot pg.json --y event_turn --html pg.html");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    char *pg = cli_read_file(cli_path("pg.html"), NULL);
    assert_non_null(strstr(pg, "\"event_turn\":\"event_turn [s]\""));
    free(pg);
    unlink(cli_path("p.json"));
    unlink(cli_path("pj.svg"));
    unlink(cli_path("pg.json"));
    unlink(cli_path("pg.html"));
    r = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.5 --tspan 0:20 --vary mu=0.5,1,1000 "
                      "--vary y1=1,2 --reduce max:y1,final:y2 --output g.csv");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot g.csv --y max:y1");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "class=\"colorbar\""));
    assert_non_null(strstr(r.out, "fill=\"#bbbbbb\"><title>mu=1000 y1=1: max_y1=nan"));
    long cells = 0;
    for (const char *p = strstr(r.out, "<title>mu="); p; p = strstr(p + 1, "<title>mu="))
        cells++;
    assert_int_equal(cells, 6);
    cli_free(&r);
    r = cli_in_tmpdir("plot g.csv --x y1 --y final:y2");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "mu = 0.5"));
    cli_free(&r);
    /* the same pictures in a page: --html FILE, or --output FILE.html; every number of the
     * columns drawn, round-trip, nan as null, nothing fetched from outside */
    r = cli_in_tmpdir("plot g.csv --y max:y1 --html g.html");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    char *page = cli_read_file(cli_path("g.html"), NULL);
    assert_non_null(page);
    assert_null(strstr(page, "http://"));
    assert_null(strstr(page, "https://"));
    assert_non_null(strstr(page, "\"kind\":\"sweep\""));
    assert_non_null(strstr(page, "\"picture\":\"heat\""));
    assert_non_null(strstr(page, "\"other\":\"y1\""));
    assert_non_null(strstr(page, "\"mu\":[0.5,0.5,1,1,1000,1000]"));
    assert_non_null(strstr(page, "\"max_y1\":["));
    assert_non_null(strstr(page, "null")); /* the failed runs */
    free(page);
    /* values sampled at random (Monte Carlo): a line follows the varied value, not the run
     * order (its points in increasing mu), and two sampled names give a point per run, not
     * a grid of mostly empty cells */
    r = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.01 --tspan 0:5 "
                      "--sample 'mu=uniform(0.5,2)' --sample 'y1=normal(2,0.1)' --runs 40 "
                      "--seed 7 --reduce final --output mc.csv");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot mc.csv --y final:y1");
    long points = 0;
    for (const char *p = strstr(r.out, "<circle "); p; p = strstr(p + 1, "<circle "))
        points++;
    CHECK(r.status == 0 && strstr(r.out, "class=\"points\"") && !strstr(r.out, "class=\"cells\"") &&
              points == 40,
          "a Monte Carlo table over two sampled names: exit %d, %ld points", r.status, points);
    cli_free(&r);
    r = cli_in_tmpdir("plot mc.csv --x mu --y final:y1");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("sweep vanderpol --method rk4 --step 0.01 --tspan 0:5 "
                      "--sample 'mu=uniform(0.5,2)' --runs 40 --seed 7 --reduce final "
                      "--output mc1.csv");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    r = cli_in_tmpdir("plot mc1.csv --y final:y1");
    const char *pts = strstr(r.out, "<polyline");
    pts = pts ? strstr(pts, "points=\"") : NULL;
    CHECK(r.status == 0 && pts, "no line: %s", r.err);
    int ordered = 1, n_pts = 0;
    double last_x = -1e300;
    for (const char *q = pts + 8; *q && *q != '"';) {
        char *end;
        const double px = strtod(q, &end);
        if (end == q)
            break;
        ordered &= px >= last_x;
        last_x = px;
        n_pts++;
        q = strchr(end, ' ');
        if (!q)
            break;
        q++;
    }
    CHECK(ordered && n_pts == 40, "the line's %d points are not in increasing mu", n_pts);
    cli_free(&r);
    r = cli_in_tmpdir("plot p.csv --y event:turn --output p.html");
    assert_int_equal(r.status, 0);
    cli_free(&r);
    page = cli_read_file(cli_path("p.html"), NULL);
    assert_non_null(strstr(page, "\"picture\":\"lines\""));
    assert_non_null(strstr(page, "\"y\":[\"event_turn\"]"));
    assert_non_null(strstr(page, "\"other\":null"));
    free(page);
    static const struct {
        const char *args, *message;
    } errors[] = {
        {"plot g.csv --y max:y1,final:y2", "shows one reduced column: give --y NAME"},
        {"plot g.csv --y speed", "not a reduced column of g.csv (accepted: max_y1, final_y2)"},
        {"plot g.csv --x max:y1 --y final:y2", "not a varied name of g.csv (accepted: mu, y1)"},
        {"plot missing.csv", "cannot open missing.csv"},
        {"plot g.csv --y max:y1 --compare euler", "a sweep's table takes --y"},
        {"plot g.csv --y max:y1 --html a.html --output b.svg", "give --html FILE or --output FILE"},
        {"plot g.csv --y max:y1 --html", "--html needs a value"},
    };
    for (size_t k = 0; k < sizeof errors / sizeof errors[0]; k++) {
        r = cli_in_tmpdir("%s", errors[k].args);
        if (r.status != 2 || !strstr(r.err, errors[k].message))
            fprintf(stderr, "dynkit %s: status %d\n%s", errors[k].args, r.status, r.err);
        assert_int_equal(r.status, 2);
        assert_non_null(strstr(r.err, errors[k].message));
        cli_free(&r);
    }
    /* a JSON table that is not a sweep's: refused with its line and what is wrong */
    FILE *f = fopen(cli_path("bad.json"), "w");
    assert_non_null(f);
    fputs("{\"columns\": [\"run\", \"a\", \"max_b\"],\n \"rows\": [[0, 1, 2], [1, 2]]}\n", f);
    fclose(f);
    r = cli_in_tmpdir("plot bad.json");
    CHECK(r.status == 2 && strstr(r.err, "bad.json:2: not a sweep's JSON table: a row of fewer "
                                         "numbers than columns"),
          "plot of a bad JSON table: exit %d: %s", r.status, r.err);
    cli_free(&r);
    unlink(cli_path("bad.json"));
    unlink(cli_path("p.csv"));
    unlink(cli_path("p.svg"));
    unlink(cli_path("g.csv"));
    unlink(cli_path("g.html"));
    unlink(cli_path("p.html"));
}

/* The commands of docs/sweeps.md's pictures section run as shown, one after the other (the
 * plots read the tables the sweeps wrote), and the heat map's axes carry the units. */
static void test_doc_pictures(void **state)
{
    (void)state;
    char *doc = cli_read_file(DYNKIT_SOURCE_DIR "/docs/sweeps.md", NULL);
    const char *sec = strstr(doc, "## Pictures");
    const char *block = sec ? strstr(sec, "```sh\n") : NULL;
    const char *end = block ? strstr(block + 6, "```") : NULL;
    CHECK(end, "docs/sweeps.md has no ```sh block under '## Pictures'");
    char cmd[2048] = "";
    int ran = 0;
    for (const char *p = block + 6; p < end;) {
        const char *nl = strchr(p, '\n');
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(nl - p), p);
        p = nl + 1;
        char *hash = strstr(line, " #");
        if (hash)
            *hash = '\0';
        const size_t len = strlen(line);
        const int more = len > 0 && line[len - 1] == '\\';
        if (more)
            line[len - 1] = '\0';
        strncat(cmd, line, sizeof cmd - strlen(cmd) - 1);
        if (more)
            continue;
        if (strncmp(cmd, "dynkit ", 7) == 0) {
            cli_result r = cli_in_tmpdir("%s", cmd + 7);
            CHECK(r.status == 0, "docs/sweeps.md: %s: exit %d: %s", cmd, r.status, r.err);
            cli_free(&r);
            ran++;
        }
        cmd[0] = '\0';
    }
    CHECK(ran >= 6, "docs/sweeps.md's pictures: %d commands run", ran);
    char *svg = cli_read_file(cli_path("heat.svg"), NULL);
    CHECK(strstr(svg, ">l [m]</text>") && strstr(svg, ">max_height [m]</text>"),
          "heat.svg of docs/sweeps.md: no units on its axes");
    free(svg);
    free(doc);
}

/* A model file is a model like any other: the .ode van der Pol gives the built-in model's
 * bytes, on 1 and 2 threads (its generated code is re-entrant). */
static void test_model_file(void **state)
{
    (void)state;
    const char *args = "--method rk4 --step 0.01 --tspan 0:5 --vary mu=0.5:3:24 "
                       "--reduce final,max:y1,mean:y2";
    cli_result a = cli("sweep " DYNKIT_SOURCE_DIR "/examples/models/vanderpol.ode %s --threads 1",
                       args);
    cli_result b = cli("sweep " DYNKIT_SOURCE_DIR "/examples/models/vanderpol.ode %s --threads 2",
                       args);
    cli_result c = cli("sweep vanderpol %s", args);
    if (a.status != 0)
        fprintf(stderr, "%s", a.err);
    assert_int_equal(a.status, 0);
    assert_int_equal(b.status, 0);
    assert_int_equal(c.status, 0);
    assert_int_equal(csv_rows(a.out), 24);
    assert_string_equal(a.out, b.out);
    assert_string_equal(a.out, c.out);
    cli_free(&a);
    cli_free(&b);
    cli_free(&c);
}

static int setup(void **state)
{
    (void)state;
    if (cli_make_tmpdir("sweep"))
        return -1;
    /* a cache of compiled model files for this test run, inherited by every dynkit below */
    static char cache[600];
    snprintf(cache, sizeof cache, "%s/cache", cli_tmpdir);
    return setenv("DYNKIT_CACHE_DIR", cache, 1);
}

static int teardown(void **state)
{
    (void)state;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cli_tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_period_curve), cmocka_unit_test(test_threads_same_bytes),
        cmocka_unit_test(test_from),         cmocka_unit_test(test_failed_run),
        cmocka_unit_test(test_resume),       cmocka_unit_test(test_interrupt),
        cmocka_unit_test(test_ignored_interrupt_stays_ignored),
        cmocka_unit_test(test_help_examples),
        cmocka_unit_test(test_noise_bands), cmocka_unit_test(test_noise_events),
        cmocka_unit_test(test_noise_bands_sriw1), cmocka_unit_test(test_errors),
        cmocka_unit_test(test_plot_table),    cmocka_unit_test(test_model_file),
        cmocka_unit_test(test_doc_pictures),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
