/* Defects that lost or faked data, each stated as the fact that now holds:
 *
 * - an output file survives, byte for byte, any error found before the run produced a
 *   sample (bad options found late, a bad --events-output); --output and --events-output
 *   naming one file are refused; a missing directory, a directory, a full device give an
 *   error naming the file and exit 1; a failed write to standard output is exit 1 with a
 *   message, for every command; a closed pipe ends quietly; SIGINT and SIGTERM end a run
 *   after a complete row, with exit 130/143 and a valid file;
 * - a run always reaches T1: a step far larger than the span is one shorter step; a
 *   fixed-step run that fails with --every K keeps its last good sample. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
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

#include "dynkit/models.h"
#include "test_cli_run.h"
#include "test_util.h"

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("trust");
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cli_tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

static void write_text(const char *name, const char *text)
{
    FILE *f = fopen(cli_path(name), "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* 1 if file name of the temporary directory holds exactly text. */
static int file_is(const char *name, const char *text)
{
    size_t len;
    char *got = cli_read_file(cli_path(name), &len);
    int same = len == strlen(text) && memcmp(got, text, len) == 0;
    free(got);
    return same;
}

/* Number of temporary output files left in the temporary directory. */
static int leftovers(void)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | grep -c '[.]tmp'", cli_tmpdir);
    int status;
    char *out = cli_capture(cmd, &status);
    int n = atoi(out);
    free(out);
    return n;
}

/* ---- output files ---- */

static void test_late_errors_keep_the_output_file(void **state)
{
    (void)state;
    static const char *const late[] = {
        /* found by the solver after the files were opened */
        "run pendulum --method dp45 --rtol 0,0 --atol 0,0 --output p1.csv",
        /* a bad events file */
        "run pendulum --method dp45 --event turn --events-output nodir/e.csv --output p1.csv",
        "run pendulum --method dp45 --event turn --events-output /dev/full --output p1.csv",
        /* a bad option after --output */
        "run pendulum --output p1.csv --step -1",
        /* one file for both */
        "run pendulum --method dp45 --event turn --events-output p1.csv --output p1.csv",
        "run pendulum --method dp45 --event turn --events-output ./p1.csv --output p1.csv",
    };
    for (size_t i = 0; i < sizeof late / sizeof late[0]; i++) {
        write_text("p1.csv", "x\n");
        cli_result r = cli_in_tmpdir("%s", late[i]);
        CHECK(r.status != 0 && file_is("p1.csv", "x\n") && leftovers() == 0,
              "%s: exit %d, p1.csv changed or a file left beside it; stderr: %s", late[i],
              r.status, r.err);
        cli_free(&r);
    }
    /* the same file twice is refused with a message */
    cli_result r = cli_in_tmpdir(
        "run pendulum --method dp45 --event turn --events-output p1.csv --output p1.csv");
    CHECK(r.status == 2 && strstr(r.err, "same file"), "same file: %d %s", r.status, r.err);
    cli_free(&r);
    /* a successful run replaces it, with the permissions of the file it replaces */
    chmod(cli_path("p1.csv"), 0640);
    r = cli_in_tmpdir("run pendulum --method rk4 --step 0.1 --tspan 0:1 --output p1.csv");
    struct stat st;
    assert_int_equal(stat(cli_path("p1.csv"), &st), 0);
    CHECK(r.status == 0 && (st.st_mode & 0777) == 0640 && leftovers() == 0,
          "success: exit %d, mode %o", r.status, (unsigned)(st.st_mode & 0777));
    cli_free(&r);
}

static void test_failed_run_with_samples_keeps_them(void **state)
{
    (void)state;
    write_text("p1.csv", "x\n");
    cli_result r = cli_in_tmpdir(
        "run vanderpol --set mu=1e6 --method euler --step 0.1 --tspan 0:15 --output p1.csv");
    size_t len;
    char *got = cli_read_file(cli_path("p1.csv"), &len);
    CHECK(r.status == 1 && strncmp(got, "t,y1,y2\n0,2,0\n", 14) == 0,
          "failed run: exit %d, file '%s'", r.status, got);
    free(got);
    cli_free(&r);
}

static void test_bad_output_paths_name_the_file(void **state)
{
    (void)state;
    static const struct {
        const char *args, *expect;
    } bad[] = {
        {"run pendulum --output nodir/x.csv", "nodir/x.csv"},
        {"run pendulum --output dir.csv", "is a directory"},
        {"run pendulum --method dp45 --event turn --events-output /dev/full", "/dev/full"},
    };
    mkdir(cli_path("dir.csv"), 0755);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cli_result r = cli_in_tmpdir("%s", bad[i].args);
        CHECK(r.status == 1 && strstr(r.err, bad[i].expect), "%s: exit %d, stderr %s",
              bad[i].args, r.status, r.err);
        cli_free(&r);
    }
}

static void test_stdout_failures_are_reported(void **state)
{
    (void)state;
    static const char *const commands[] = {
        "models", "methods", "info pendulum", "--help", "--version", "run --help",
        "run pendulum", "verify --quick --problem oscillator", "inverse cart",
    };
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        char cmd[1024];
        snprintf(cmd, sizeof cmd, "'%s' %s >/dev/full 2>'%s'", DYNKIT_CLI, commands[i],
                 cli_path("err"));
        int w = system(cmd);
        char *err = cli_read_file(cli_path("err"), NULL);
        CHECK(WIFEXITED(w) && WEXITSTATUS(w) == 1 && strstr(err, "write"),
              "%s > /dev/full: status %d, stderr %s", commands[i], WEXITSTATUS(w), err);
        free(err);
    }
}

static void test_closed_pipe_ends_quietly(void **state)
{
    (void)state;
    /* with SIGPIPE ignored (as some parents leave it), writes fail with EPIPE */
    static const char *const how[] = {"", "trap '' PIPE; "};
    for (size_t i = 0; i < 2; i++) {
        char cmd[1024];
        snprintf(cmd, sizeof cmd,
                 "%s'%s' run pendulum --method rk4 --step 1e-5 --tspan 0:50 2>'%s' | head -1 "
                 ">/dev/null",
                 how[i], DYNKIT_CLI, cli_path("err"));
        int w = system(cmd);
        char *err = cli_read_file(cli_path("err"), NULL);
        CHECK(w != -1 && err[0] == '\0', "%s| head -1: stderr '%s'", how[i], err);
        free(err);
        snprintf(cmd, sizeof cmd, "%s'%s' methods 2>'%s' | head -1 >/dev/null", how[i],
                 DYNKIT_CLI, cli_path("err"));
        w = system(cmd);
        err = cli_read_file(cli_path("err"), NULL);
        CHECK(w != -1 && err[0] == '\0', "%smethods | head -1: stderr '%s'", how[i], err);
        free(err);
    }
}

/* Start `dynkit ARGS...` with stdout to file out (in the temporary directory) and default
 * signal dispositions; return its pid. */
static pid_t start(const char *out, const char *const *args)
{
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        if (chdir(cli_tmpdir) != 0 || !freopen(out, "w", stdout) ||
            !freopen("err", "w", stderr))
            _exit(99);
        char *argv[32];
        int n = 0;
        argv[n++] = (char *)DYNKIT_CLI;
        for (; args[n - 1] && n < 31; n++)
            argv[n] = (char *)args[n - 1];
        argv[n] = NULL;
        execv(DYNKIT_CLI, argv);
        _exit(98);
    }
    return pid;
}

/* Every line of text (after the header) has exactly cols fields, each a number that reads
 * back entirely, and the text ends with a newline; returns the number of rows. */
static long valid_csv_rows(const char *text, int cols)
{
    const char *p = strchr(text, '\n');
    if (!p)
        return -1;
    long rows = 0;
    for (p++; *p; rows++) {
        for (int c = 0; c < cols; c++) {
            char *end;
            strtod(p, &end);
            if (end == p)
                return -1;
            p = end;
            if (*p != (c + 1 < cols ? ',' : '\n'))
                return -1;
            p++;
        }
    }
    return rows;
}

static void test_signals_leave_complete_rows(void **state)
{
    (void)state;
    static const int sigs[] = {SIGINT, SIGTERM};
    for (int s = 0; s < 2; s++) {
        for (int to_file = 0; to_file < 2; to_file++) {
            const char *const args_file[] = {"run",    "pendulum", "--method", "rk4", "--step",
                                             "1e-7",   "--tspan",  "0:1000",   "--output",
                                             "sig.csv", NULL};
            const char *const args_out[] = {"run",  "pendulum", "--method", "rk4", "--step",
                                            "1e-7", "--tspan",  "0:1000",   NULL};
            unlink(cli_path("sig.csv"));
            pid_t pid = start(to_file ? "stdout.txt" : "sig.csv", to_file ? args_file : args_out);
            struct timespec ts = {0, 400000000};
            nanosleep(&ts, NULL);
            kill(pid, sigs[s]);
            int w;
            assert_int_equal(waitpid(pid, &w, 0), pid);
            char *text = cli_read_file(cli_path("sig.csv"), NULL);
            char *err = cli_read_file(cli_path("err"), NULL);
            long rows = valid_csv_rows(text, 3);
            CHECK(WIFEXITED(w) && WEXITSTATUS(w) == 128 + sigs[s] && rows > 1 &&
                      strncmp(text, "t,phi,dphi\n0,0,", 15) == 0,
                  "signal %d, %s: status %d, %ld valid rows, stderr %s", sigs[s],
                  to_file ? "--output" : "stdout", WIFEXITED(w) ? WEXITSTATUS(w) : -1, rows,
                  err);
            free(text);
            free(err);
        }
    }
    unlink(cli_path("stdout.txt"));
    assert_int_equal(leftovers(), 0);
}

/* ---- a run reaches T1 ---- */

static void test_step_larger_than_span_reaches_t1(void **state)
{
    (void)state;
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    dyn_vanderpol_par par = {.mu = 1.0};
    dyn_system sys = {dyn_vanderpol_rhs, 2, &par};
    const double y0[2] = {2.0, 0.0};
    double y[2], work[TEST_WORK];
    dyn_result res;
    assert_int_equal(dyn_fixed_solve(rk4, &sys, 0.0, 1.0, 1e300, y0, y, work, NULL, &res),
                     DYN_OK);
    CHECK(res.t == 1.0 && res.stats.steps == 1 && y[0] != y0[0], "h = 1e300: t %g, %ld steps",
          res.t, res.stats.steps);
    dyn_grid g;
    assert_int_equal(dyn_grid_plan(0.0, 1e-13, 0.01, DYN_END_EXACT, &g, NULL, 0), DYN_OK);
    CHECK(g.samples == 2 && dyn_grid_time(&g, 1) == 1e-13, "span 1e-13: %ld samples",
          g.samples);

    cli_result r = cli("run pendulum --step 1e300 --tspan 0:1 --method rk4 --final");
    CHECK(r.status == 0 && strncmp(r.out, "t,phi,dphi\n1,", 13) == 0, "step 1e300: %d %s %s",
          r.status, r.out, r.err);
    cli_free(&r);
    r = cli("run vanderpol --tspan 0:1e-13 --final");
    CHECK(r.status == 0 && strncmp(r.out, "t,y1,y2\n1e-13,", 14) == 0, "span 1e-13: %d %s %s",
          r.status, r.out, r.err);
    cli_free(&r);
    r = cli("run pendulum --method rk4 --step 2 --tspan 0:1 --end grid");
    CHECK(r.status == 2 && strstr(r.err, "longer than"), "grid, no sample after T0: %d %s",
          r.status, r.err);
    cli_free(&r);
}

static void test_failed_thinned_run_keeps_last_good_sample(void **state)
{
    (void)state;
    cli_result r =
        cli("run vanderpol --set mu=1e6 --method euler --step 0.1 --tspan 0:15 --every 1000");
    /* the run fails at t = 0.8; its last good sample, t = 0.7, is the last row */
    CHECK(r.status == 1 && strstr(r.out, "\n0.70000000000000007,"), "exit %d, out %s",
          r.status, r.out);
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_late_errors_keep_the_output_file),
        cmocka_unit_test(test_failed_run_with_samples_keeps_them),
        cmocka_unit_test(test_bad_output_paths_name_the_file),
        cmocka_unit_test(test_stdout_failures_are_reported),
        cmocka_unit_test(test_closed_pipe_ends_quietly),
        cmocka_unit_test(test_signals_leave_complete_rows),
        cmocka_unit_test(test_step_larger_than_span_reaches_t1),
        cmocka_unit_test(test_failed_thinned_run_keeps_last_good_sample),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
