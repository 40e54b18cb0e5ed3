/* SPDX-License-Identifier: BSD-3-Clause */
/* Defects that lost or faked data, each stated as the fact that now holds:
 *
 * - an output file survives, byte for byte, any error found before the run produced a
 *   sample (bad options found late, a bad --events-output); --output and --events-output
 *   naming one file are refused, and so is an output naming a file the command reads; a missing directory, a directory, a full device give an
 *   error naming the file and exit 1; a failed write to standard output is exit 1 with a
 *   message, for every command; a closed pipe ends quietly; SIGINT and SIGTERM end a run
 *   after a complete row, with exit 130/143 and a valid file; plots and pages replace
 *   their file in one rename, as run's outputs do;
 * - a run always reaches T1: a step far larger than the span is one shorter step; a
 *   fixed-step run that fails with --every K keeps its last good sample. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
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

#include "dynkit/io.h"
#include "dynkit/models.h"
#include "dynkit/solve.h"
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
              "%s: exit %d, p1.csv changed or a file left beside it; stderr: %s", late[i], r.status,
              r.err);
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

/* 1 if files a and b of the temporary directory hold the same bytes. */
static int same_bytes(const char *a, const char *b)
{
    size_t la, lb;
    char *ta = cli_read_file(cli_path(a), &la);
    char *tb = cli_read_file(cli_path(b), &lb);
    const int same = la == lb && la > 0 && memcmp(ta, tb, la) == 0;
    free(ta);
    free(tb);
    return same;
}

static void test_outputs_never_replace_inputs(void **state)
{
    (void)state;
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && cp '%s/examples/mechanisms/double_pendulum.mech' dp.mech && "
             "cp '%s/examples/mechanisms/cart.mech' cart.mech && "
             "printf 't,Fx,Fy\n0,0,0\n1,1,0\n' > f.csv && printf '0\n0.5\n1\n' > t.csv && "
             "ln -sf dp.mech link.mech && ln -f f.csv hard.csv && mkdir -p sub && "
             "'%s' sweep pendulum --vary l=1:2:3 -o s.csv",
             cli_tmpdir, DYNKIT_SOURCE_DIR, DYNKIT_SOURCE_DIR, DYNKIT_CLI);
    assert_int_equal(system(cmd), 0);
    static const struct {
        const char *args, *input, *what;
    } cases[] = {
        {"derive dp.mech --c dp.mech", "dp.mech", "model file"},
        {"derive dp.mech --c ./link.mech", "dp.mech", "model file"},
        {"derive dp.mech --c sub/../dp.mech", "dp.mech", "model file"},
        {"run cart.mech --forces f.csv -o f.csv", "f.csv", "--forces"},
        {"run cart.mech --forces f.csv -o hard.csv", "f.csv", "--forces"},
        {"run pendulum --times @t.csv -o t.csv", "t.csv", "--times"},
        {"run pendulum --times @t.csv --event turn --events-output ./t.csv", "t.csv", "--times"},
        {"sweep pendulum --from s.csv -o s.csv", "s.csv", "--from"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(cmd, sizeof cmd, "cd '%s' && cp '%s' before", cli_tmpdir, cases[i].input);
        assert_int_equal(system(cmd), 0);
        cli_result r = cli_in_tmpdir("%s", cases[i].args);
        CHECK(r.status == 2 && strstr(r.err, "would destroy") && strstr(r.err, cases[i].what) &&
                  same_bytes("before", cases[i].input) && leftovers() == 0,
              "%s: want exit 2, 'would destroy' naming the %s, %s unchanged; got %d: %s",
              cases[i].args, cases[i].what, cases[i].input, r.status, r.err);
        cli_free(&r);
    }
    /* another name is written as before */
    cli_result r = cli_in_tmpdir("derive dp.mech --c dp.c");
    CHECK(r.status == 0 && file_is("dp.c", "") == 0, "derive --c dp.c: %d %s", r.status, r.err);
    cli_free(&r);
}

/* The value of column col in row row (0: the header) of a CSV text. */
static double csv_value(const char *text, int row, int col)
{
    const char *p = text;
    for (int r = 0; r < row && p; r++) {
        p = strchr(p, '\n');
        p = p ? p + 1 : NULL;
    }
    for (int c = 0; c < col && p; c++) {
        p = strchr(p, ',');
        p = p ? p + 1 : NULL;
    }
    return p ? strtod(p, NULL) : NAN;
}

/* --init, --set and --vary take formulas of the parameters, as a model file's init lines:
 * each value as C computes it (pendulum: m = 1, l = g = 9.81 by default). */
#define PI 3.14159265358979323846
static void test_values_may_be_formulas_of_the_parameters(void **state)
{
    (void)state;
    const char *step = "--method rk4 --step 1e-9 --tspan 0:1e-9";
    cli_result r = cli("run pendulum --init 'dphi=200-g*cos(0.3)' %s", step);
    CHECK(r.status == 0 && csv_value(r.out, 1, 2) == 200 - 9.81 * cos(0.3), "%d %s %s",
          r.status, r.out, r.err);
    cli_free(&r);
    /* --init after every --set; a --set formula after the --set numbers */
    r = cli("run pendulum --init dphi=g/l --set l=2 --set 'm=2*l^2' --set l=3 --outputs %s",
            step);
    const double dphi = 9.81 / 3, m = 2 * 3 * 3.0; /* energy = m l^2 dphi^2 / 2 */
    CHECK(r.status == 0 && csv_value(r.out, 1, 2) == dphi &&
              fabs(csv_value(r.out, 1, 3) - 0.5 * m * 9 * dphi * dphi) <= 1e-12 * m * 9 * dphi,
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    /* docs/cli.md's example, as printed */
    r = cli("run pendulum --set l=2 --init 'dphi=2*g/l-cos(0.3)' %s", step);
    CHECK(r.status == 0 && strstr(r.out, "\n0,0,8.854663510874394\n") &&
              csv_value(r.out, 1, 2) == 2 * 9.81 / 2 - cos(0.3),
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    /* the conveniences stay: degrees, multiples of pi */
    r = cli("run pendulum --init phi=45deg --init dphi=-pi/4 %s", step);
    CHECK(r.status == 0 && csv_value(r.out, 1, 1) == PI / 4 && csv_value(r.out, 1, 2) == -PI / 4,
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    /* --vary's bounds and list items, max(a,b) one item */
    r = cli("sweep pendulum --set l=2 --vary 'dphi=g/l:2*g/l:3' %s", step);
    CHECK(r.status == 0 && csv_value(r.out, 1, 1) == 9.81 / 2 && csv_value(r.out, 3, 1) == 9.81,
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli("sweep pendulum --set l=2 --vary 'dphi=max(l,1),sqrt(g*l)' %s", step);
    CHECK(r.status == 0 && csv_value(r.out, 1, 1) == 2 && csv_value(r.out, 2, 1) == sqrt(9.81 * 2),
          "%d %s %s", r.status, r.out, r.err);
    cli_free(&r);
    /* what is no such formula is refused, saying why */
    static const char *const bad[][2] = {
        {"--init dphi=2*q", "'q' is no parameter"},
        {"--init dphi=t", "time t"},
        {"--init dphi=1/0*l", "not finite"},
        {"--set 'l=2*'", "expected a number"},
        {"--vary dphi=1:w:3", "two numbers"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        r = cli("%s pendulum %s %s", strstr(bad[i][0], "vary") ? "sweep" : "run", bad[i][0],
                step);
        CHECK(r.status == 2 && strstr(r.err, bad[i][1]), "%s: %d %s", bad[i][0], r.status, r.err);
        cli_free(&r);
    }
}

/* -o -.EXT is standard output in the format of EXT: the bytes of -o F.EXT, and no file
 * named -.EXT; an extension the command does not write is refused naming -.EXT's form. */
static void test_dash_with_a_format_is_standard_output(void **state)
{
    (void)state;
    static const char *const cmds[][2] = {
        {"run pendulum --method rk4 --step 0.1 --tspan 0:1 -o %s", "json"},
        {"run pendulum --method rk4 --step 0.1 --tspan 0:1 -o %s", "npy"},
        {"sweep pendulum --vary l=1:2:3 --method rk4 --step 0.1 --tspan 0:1 -o %s", "json"},
        {"linearize pendulum -o %s", "json"},
        {"plot pendulum --method rk4 --step 0.1 --tspan 0:1 --y phi -o %s", "svg"},
    };
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        char dash[16], file[16], args[512];
        snprintf(dash, sizeof dash, "-.%s", cmds[i][1]);
        snprintf(file, sizeof file, "f.%s", cmds[i][1]);
        snprintf(args, sizeof args, cmds[i][0], file);
        cli_result r = cli_in_tmpdir("%s", args);
        assert_int_equal(r.status, 0);
        cli_free(&r);
        size_t len;
        char *want = cli_read_file(cli_path(file), &len);
        snprintf(args, sizeof args, cmds[i][0], dash);
        r = cli_in_tmpdir("%s", args);
        struct stat st;
        CHECK(r.status == 0 && r.out_len == len && len > 0 && memcmp(r.out, want, len) == 0 &&
                  stat(cli_path(dash), &st) != 0,
              "%s: exit %d, %zu bytes on stdout, %zu in %s, or a file %s made: %s", args,
              r.status, r.out_len, len, file, dash, r.err);
        free(want);
        cli_free(&r);
    }
    cli_result r = cli_in_tmpdir("plot pendulum --y phi -o -.png");
    CHECK(r.status == 2 && strstr(r.err, "'-.svg'"), "%d %s", r.status, r.err);
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

/* Pages and plots replace their file in one rename, like run's --output: a second name (a
 * hard link) of the old file keeps the old bytes, the new file is complete, nothing is left
 * beside it; a page that cannot be written leaves the old file as it was. */
static void test_pages_replace_their_file_in_one_rename(void **state)
{
    (void)state;
    static const struct {
        const char *file, *args, *start;
    } pages[] = {
        {"p.svg", "plot pendulum --y phi --tspan 0:1 --output p.svg", "<?xml"},
        {"a.html", "animate pendulum --tspan 0:1 --output a.html", "<!DOCTYPE html>"},
        {"r.html", "report --no-studies --html r.html", "<!DOCTYPE html>"},
    };
    for (size_t i = 0; i < sizeof pages / sizeof pages[0]; i++) {
        write_text(pages[i].file, "x\n");
        char old_name[64];
        snprintf(old_name, sizeof old_name, "old-%s", pages[i].file);
        char from[600], to[600]; /* cli_path's buffer is reused by each call */
        snprintf(from, sizeof from, "%s", cli_path(pages[i].file));
        snprintf(to, sizeof to, "%s", cli_path(old_name));
        unlink(to);
        assert_int_equal(link(from, to), 0);
        cli_result r = cli_in_tmpdir("%s", pages[i].args);
        size_t len;
        char *got = cli_read_file(cli_path(pages[i].file), &len);
        CHECK(r.status == 0 && file_is(old_name, "x\n") &&
                  strncmp(got, pages[i].start, strlen(pages[i].start)) == 0 && leftovers() == 0,
              "%s: exit %d, the old file's other name changed or the new one is not whole; "
              "stderr: %s",
              pages[i].args, r.status, r.err);
        free(got);
        cli_free(&r);
    }
    /* a page into a missing directory: an error naming it, nothing written */
    cli_result r = cli_in_tmpdir("report --no-studies --html nodir/r.html");
    CHECK(r.status != 0 && strstr(r.err, "nodir/r.html") && leftovers() == 0,
          "report into a missing directory: exit %d, stderr %s", r.status, r.err);
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
        {"run pendulum --method dp45 --event turn --events-output nodir/e.csv", "nodir/e.csv"},
    };
    mkdir(cli_path("dir.csv"), 0755);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cli_result r = cli_in_tmpdir("%s", bad[i].args);
        CHECK(r.status == 1 && strstr(r.err, bad[i].expect), "%s: exit %d, stderr %s", bad[i].args,
              r.status, r.err);
        cli_free(&r);
    }
    /* a device is written directly, as CSV whatever its name (docs/data-files.md):
     * -o /dev/stdout gives the same bytes as no --output, for a run and a sweep */
    static const char *const dev[] = {"run pendulum --tspan 0:0.05 --step 0.01",
                                      "sweep pendulum --tspan 0:1 --vary dphi=1,2"};
    for (size_t i = 0; i < sizeof dev / sizeof dev[0]; i++) {
        cli_result a = cli("%s", dev[i]), b = cli("%s -o /dev/stdout", dev[i]);
        CHECK(a.status == 0 && b.status == 0 && strcmp(a.out, b.out) == 0,
              "%s -o /dev/stdout: exit %d, %s", dev[i], b.status, b.err);
        cli_free(&a);
        cli_free(&b);
    }
}

static void test_stdout_failures_are_reported(void **state)
{
    (void)state;
    static const char *const commands[] = {
        "models",       "methods",    "info pendulum", "--help",
        "--version",    "run --help", "run pendulum",  "verify --quick --problem oscillator",
        "inverse cart",
    };
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        char cmd[1024];
        snprintf(cmd, sizeof cmd, "'%s' %s >/dev/full 2>'%s'", DYNKIT_CLI, commands[i],
                 cli_path("err"));
        int w = system(cmd);
        char *err = cli_read_file(cli_path("err"), NULL);
        CHECK(WIFEXITED(w) && WEXITSTATUS(w) == 1 && strstr(err, "writ"),
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
        snprintf(cmd, sizeof cmd, "%s'%s' methods 2>'%s' | head -1 >/dev/null", how[i], DYNKIT_CLI,
                 cli_path("err"));
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
        if (chdir(cli_tmpdir) != 0 || !freopen(out, "w", stdout) || !freopen("err", "w", stderr))
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
            /* 1e10 steps: ended by the signal (--max-steps lets such a grid run) */
            const char *const args_file[] = {
                "run",    "pendulum",    "--method", "rk4",      "--step",  "1e-7", "--tspan",
                "0:1000", "--max-steps", "1e10",     "--output", "sig.csv", NULL};
            const char *const args_out[] = {"run",         "pendulum", "--method", "rk4",
                                            "--step",      "1e-7",     "--tspan",  "0:1000",
                                            "--max-steps", "1e10",     NULL};
            unlink(cli_path("sig.csv"));
            pid_t pid = start(to_file ? "stdout.txt" : "sig.csv", to_file ? args_file : args_out);
            /* signal once rows are being written (the handler is in place by then) */
            struct timespec ts = {0, 20000000};
            struct stat st;
            for (int wait = 0; wait < 1000; wait++) {
                if (stat(cli_path("sig.csv"), &st) == 0 && st.st_size > 4096)
                    break;
                if (to_file && stat(cli_path("."), &st) == 0 && leftovers() > 0 && wait > 25)
                    break; /* --output: the temporary file exists, rows are on their way */
                nanosleep(&ts, NULL);
            }
            kill(pid, sigs[s]);
            int w;
            assert_int_equal(waitpid(pid, &w, 0), pid);
            char *text = cli_read_file(cli_path("sig.csv"), NULL);
            char *err = cli_read_file(cli_path("err"), NULL);
            long rows = valid_csv_rows(text, 3);
            CHECK(WIFEXITED(w) && WEXITSTATUS(w) == 128 + sigs[s] && rows > 1 &&
                      strncmp(text, "t,phi,dphi\n0,0,", 15) == 0,
                  "signal %d, %s: status %d, %ld valid rows, stderr %s", sigs[s],
                  to_file ? "--output" : "stdout", WIFEXITED(w) ? WEXITSTATUS(w) : -1, rows, err);
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
    assert_int_equal(dyn_fixed_solve(rk4, &sys, 0.0, 1.0, 1e300, y0, y, work, NULL, &res), DYN_OK);
    CHECK(res.t == 1.0 && res.stats.steps == 1 && y[0] != y0[0], "h = 1e300: t %g, %ld steps",
          res.t, res.stats.steps);
    dyn_grid g;
    assert_int_equal(dyn_grid_plan(0.0, 1e-13, 0.01, DYN_END_EXACT, &g, NULL, 0), DYN_OK);
    CHECK(g.samples == 2 && dyn_grid_time(&g, 1) == 1e-13, "span 1e-13: %ld samples", g.samples);

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
    CHECK(r.status == 1 && strstr(r.out, "\n0.7000000000000001,"), "exit %d, out %s", r.status,
          r.out);
    cli_free(&r);
}

/* ---- tolerances, step limits ---- */

static int singular_at_zero(double t, const double *y, double *dydt, void *par)
{
    (void)y;
    (void)par;
    dydt[0] = t > 0.0 ? 1.0 / t : 0.0; /* y = log t: no step size passes near t = 0 */
    return 0;
}

static void test_tolerances_below_rounding_are_raised(void **state)
{
    (void)state;
    const dyn_tableau *methods[] = {dyn_method_find("dp45"), dyn_method_find("rodas4")};
    dyn_pendulum_par par = {.m = 1.0, .l = 1.0, .g = 9.81};
    dyn_system sys = {dyn_pendulum_rhs, 2, &par};
    const double y0[2] = {0.0, DYN_PI / 2.0};
    for (int i = 0; i < 2; i++) {
        dyn_solve_opts o = {0};
        o.rtol = i == 0 ? 1e-30 : 1e-300;
        o.atol = o.rtol;
        o.max_steps = 1000000; /* a run that never ends stops here instead */
        double y[2];
        double *work = malloc(dyn_solve_work_size(methods[i], 2, &o) * sizeof *work);
        int *iwork = malloc((dyn_solve_iwork_size(methods[i], 2) + 1) * sizeof *iwork);
        o.iwork = iwork;
        dyn_result res;
        int rc = dyn_solve(methods[i], &sys, 0.0, 10.0, y0, y, work, &o, &res);
        CHECK(rc == DYN_OK && res.rtol_raised && res.t == 10.0 && res.stats.steps < 100000,
              "%s at rtol %g: status %d (%s), raised %d, %ld steps", methods[i]->name, o.rtol, rc,
              res.message, res.rtol_raised, res.stats.steps);
        free(work);
        free(iwork);
    }
    /* per-state tolerances below rounding are refused with a message */
    const double rtolv[2] = {1e-20, 1e-6};
    dyn_solve_opts o = {0};
    o.rtolv = rtolv;
    double y[2], work[256];
    dyn_result res;
    assert_int_equal(dyn_solve(methods[0], &sys, 0.0, 1.0, y0, y, work, &o, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "below rounding"));

    /* the command line says that it raised them, and the run ends */
    cli_result r = cli("run pendulum --method dp45 --rtol 1e-30 --atol 1e-30 --tspan 0:10 --final");
    CHECK(r.status == 0 && strstr(r.err, "raised to 2.22e-14") &&
              strncmp(r.out, "t,phi,dphi\n10,", 14) == 0,
          "rtol 1e-30: %d %s", r.status, r.err);
    cli_free(&r);
}

static void test_step_size_underflow_near_zero(void **state)
{
    (void)state;
    const dyn_tableau *dp45 = dyn_method_find("dp45");
    dyn_system sys = {singular_at_zero, 1, NULL};
    const double y0[1] = {0.0};
    double y[1], work[256];
    dyn_result res;
    dyn_solve_opts o = {0};
    int rc = dyn_solve(dp45, &sys, 0.0, 1.0, y0, y, work, &o, &res);
    /* h falls by about 1.4 a rejection from 1e-6: the limit 16 eps^3 of the span (1e-30) is
     * reached after some 180 rejections (before: at h ~ 1e-323, after some 2300) */
    CHECK(rc == DYN_ERR_STEP_SIZE && res.stats.rejected < 400, "status %d, %ld rejected: %s", rc,
          res.stats.rejected, res.message);
}

static void test_adaptive_runs_have_a_step_limit(void **state)
{
    (void)state;
    cli_result r = cli("run pendulum --method bs23 --rtol 1e-3 --atol 1e-3 --tspan 0:1e8 --final");
    CHECK(r.status == 1 && strstr(r.err, "limit of 10000000 steps") && strstr(r.err, "--max-steps"),
          "default limit: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run pendulum --method dp45 --tspan 0:100 --max-steps 50 --final");
    CHECK(r.status == 1 && strstr(r.err, "limit of 50 steps"), "--max-steps 50: %d %s", r.status,
          r.err);
    cli_free(&r);
}

/* A fixed-step run has the same limit: its grid is counted before the first step, so a step
 * of 1e-9 over 1000 s (1e12 steps, hours of rk4) is refused at once, with the number of
 * steps and the option that raises the limit; a grid within the limit runs as before. */
static void test_fixed_step_runs_have_a_step_limit(void **state)
{
    (void)state;
    cli_result r = cli("run pendulum --method rk4 --step 1e-9 --tspan 0:1e3");
    CHECK(r.status == 1 && strstr(r.err, "1000000000000 steps of h = 1e-09") &&
              strstr(r.err, "limit of 10000000 steps") && strstr(r.err, "--max-steps") &&
              strstr(r.err, "no step was taken") && strcmp(r.out, "t,phi,dphi\n") == 0,
          "default limit: %d %s", r.status, r.err);
    cli_free(&r);
    /* 200 steps of 0.01: refused under --max-steps 199, run under --max-steps 200 */
    r = cli("run pendulum --method rk4 --step 0.01 --tspan 0:2 --max-steps 199 --final");
    CHECK(r.status == 1 && strstr(r.err, "200 steps of h = 0.01 from t = 0 to 2") &&
              strstr(r.err, "limit of 199 steps"),
          "--max-steps 199: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run pendulum --method rk4 --step 0.01 --tspan 0:2 --max-steps 200 --stats");
    long rows = 0;
    for (const char *p = r.out; (p = strchr(p, '\n')) != NULL; p++)
        rows++;
    CHECK(r.status == 0 && rows == 202 && strstr(r.err, "steps=200"),
          "--max-steps 200: %d, %ld lines, %s", r.status, rows, r.err);
    cli_free(&r);
    /* with an event (the general driver on the fixed grid), and a model with noise
     * (Euler-Maruyama) */
    r = cli("run pendulum --method rk4 --step 0.01 --tspan 0:2 --max-steps 100 --event bottom");
    CHECK(r.status == 1 && strstr(r.err, "limit of 100 steps"), "with an event: %d %s", r.status,
          r.err);
    cli_free(&r);
    r = cli(
        "run %s/examples/models/ornstein_uhlenbeck.ode --method euler --step 1e-9 --tspan 0:100",
        DYNKIT_SOURCE_DIR);
    CHECK(r.status == 1 && strstr(r.err, "limit of 10000000 steps"), "noise: %d %s", r.status,
          r.err);
    cli_free(&r);
}

/* ---- safe defaults ---- */

static void test_default_runs_are_accurate_for_any_span(void **state)
{
    (void)state;
    /* the README's line: energy 0.6 J stays 0.6 J (one Euler step of 0.2 s made it 144 J) */
    cli_result r = cli("run pendulum --set l=1 --init dphi=pi/4 --tspan 0:10 --outputs --every 10");
    assert_int_equal(r.status, 0);
    const char *p = strchr(r.out, '\n');
    long rows = 0;
    double e0 = NAN, worst = 0.0;
    while (p && p[1]) {
        double t, phi, dphi, e, h;
        if (sscanf(p + 1, "%lf,%lf,%lf,%lf,%lf", &t, &phi, &dphi, &e, &h) != 5)
            break;
        if (rows++ == 0)
            e0 = e;
        worst = fmax(worst, fabs(e - e0));
        p = strchr(p + 1, '\n');
    }
    CHECK(rows == 101 && worst < 1e-6 * e0, "%ld rows, energy drift %g of %g", rows, worst, e0);
    cli_free(&r);
    /* every model's default run: adaptive, reaches its T1, and the picture of the pendulum
     * has a whole swing (not 2 samples) */
    for (int i = 0; i < dyn_model_count(); i++) {
        const dyn_model *m = dyn_model_at(i);
        const dyn_tableau *mt = dyn_method_find(m->method);
        CHECK(mt && dyn_method_is_adaptive(mt) && m->rtol > 0 && m->rtol <= 1e-6 && m->atol > 0,
              "%s: default method %s, rtol %g, atol %g", m->name, m->method, m->rtol, m->atol);
    }
    r = cli("plot pendulum --y phi");
    CHECK(r.status == 0 && strstr(r.out, "dp45"), "plot pendulum: %d %s", r.status, r.err);
    cli_free(&r);
}

static void test_robertson_stays_in_its_domain(void **state)
{
    (void)state;
    cli_result r = cli("methods");
    const int cvode = strstr(r.out, "cvode") != NULL;
    cli_free(&r);
    const char *methods[] = {"rodas4", "cvode"};
    for (int i = 0; i < 1 + cvode; i++) {
        r = cli("run robertson --method %s --tspan 0:1e11 --final", methods[i]);
        double t, y1, y2, y3;
        const char *row = strchr(r.out, '\n');
        CHECK(r.status == 0 && row && sscanf(row + 1, "%lf,%lf,%lf,%lf", &t, &y1, &y2, &y3) == 4 &&
                  t == 1e11 && y1 >= 0 && y2 >= 0 && y3 >= 0 && !strstr(r.err, "negative"),
              "%s: %d %s %s", methods[i], r.status, r.out, r.err);
        cli_free(&r);
    }
    /* tolerances that let it leave the domain give a warning */
    r = cli("run robertson --method %s --tspan 0:1e11 --rtol 1e-3 --atol 1e-6 --final",
            cvode ? "cvode" : "bs23 --max-steps 100000");
    CHECK(!cvode || strstr(r.err, "concentration is negative"), "loose cvode: %s %s", r.out, r.err);
    cli_free(&r);
}

/* ---- info ---- */

/* The value after "default " on the line of info's output that starts with "  NAME ". */
static const char *info_default(const char *out, const char *name, char *buf, size_t size)
{
    char key[64];
    snprintf(key, sizeof key, "\n  %s ", name);
    const char *table = strstr(out, "\nStates (");
    const char *line = table ? strstr(table, key) : NULL;
    const char *d = line ? strstr(line, " default ") : NULL;
    if (!d)
        return NULL;
    d += 9;
    size_t n = strcspn(d, " \n");
    snprintf(buf, size, "%.*s", (int)(n < size ? n : size - 1), d);
    return buf;
}

static void test_info_numbers_events_columns(void **state)
{
    (void)state;
    for (int i = 0; i < dyn_model_count(); i++) {
        const dyn_model *m = dyn_model_at(i);
        cli_result r = cli("info %s", m->name);
        assert_int_equal(r.status, 0);
        /* every parameter's default reads back exactly, and no shorter %g does */
        for (int k = 0; k < m->n_params; k++) {
            char got[64], shorter[64];
            const double v = m->params[k].value;
            CHECK(info_default(r.out, m->params[k].name, got, sizeof got) && strtod(got, NULL) == v,
                  "info %s: %s printed '%s', value %.17g", m->name, m->params[k].name,
                  info_default(r.out, m->params[k].name, got, sizeof got), v);
            for (int p = 1; p <= 17; p++) {
                snprintf(shorter, sizeof shorter, "%.*g", p, v);
                CHECK(!(strtod(shorter, NULL) == v && strlen(shorter) < strlen(got)),
                      "info %s: %s printed '%s', '%s' is shorter", m->name, m->params[k].name, got,
                      shorter);
            }
        }
        /* events: name, direction, terminal, description */
        for (int k = 0; k < m->n_events; k++) {
            char key[64];
            snprintf(key, sizeof key, "\n  %s ", m->events[k].name);
            const char *line = strstr(r.out, key);
            CHECK(line && strstr(line, m->events[k].description), "info %s lacks event %s", m->name,
                  m->events[k].name);
        }
        CHECK(strstr(r.out, "--rtol ") && strstr(r.out, "--atol "), "info %s: tolerances", m->name);
        cli_free(&r);
    }
    cli_result r = cli("info hires");
    CHECK(strstr(r.out, "--tspan 0:321.8122 ") != NULL, "%s", r.out);
    cli_free(&r);
    r = cli("info pendulum");
    char buf[64];
    CHECK(strcmp(info_default(r.out, "g", buf, sizeof buf), "9.81") == 0 &&
              strstr(r.out, "turn    both       no ") != NULL,
          "%s", r.out);
    cli_free(&r);
    /* columns aligned: the unit of every output starts where constraint_residual's does */
    r = cli("info cart");
    const char *outputs = strstr(r.out, "\nExtra outputs");
    assert_non_null(outputs);
    const char *a = strstr(outputs, "\n  Fx "), *b = strstr(outputs, "\n  constraint_residual ");
    assert_true(a && b);
    const size_t ua = 3 + strcspn(a + 3, " ") + strspn(a + 3 + strcspn(a + 3, " "), " ");
    const size_t ub = 3 + strcspn(b + 3, " ") + strspn(b + 3 + strcspn(b + 3, " "), " ");
    CHECK(ua == ub && strncmp(a + ua, "N ", 2) == 0, "columns of info cart: %s", outputs);
    cli_free(&r);
}

/* ---- animate and plot take what their help lists ---- */

static void test_view_commands_take_what_they_list(void **state)
{
    (void)state;
    static const char *const commands[] = {"animate", "plot"};
    static const char *const not_theirs[] = {
        "--final",  "--trace",   "--stats",       "--events-output",
        "--header", "--outputs", "write the CSV", "instead of standard output"};
    for (int c = 0; c < 2; c++) {
        cli_result r = cli("%s --help", commands[c]);
        assert_int_equal(r.status, 0);
        for (size_t k = 0; k < sizeof not_theirs / sizeof not_theirs[0]; k++)
            CHECK(strstr(r.out, not_theirs[k]) == NULL, "%s --help lists '%s'", commands[c],
                  not_theirs[k]);
        CHECK(strstr(r.out, "--output") && strstr(r.out, "--every") && strstr(r.out, "--event"),
              "%s --help lacks its options", commands[c]);
        cli_free(&r);
        /* what it does not list is refused, with a message */
        static const char *const refused[] = {"--final", "--trace 1", "--stats",
                                              "--event turn --events-output e.csv", "--outputs"};
        for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
            r = cli("%s pendulum %s %s --output '%s'", commands[c], c ? "--y phi" : "", refused[k],
                    cli_path(c ? "view.svg" : "view.html"));
            CHECK(r.status == 2 && strstr(r.err, "not"), "%s %s: %d %s", commands[c], refused[k],
                  r.status, r.err);
            cli_free(&r);
        }
    }
    /* what it lists works: --every thins, --event NAME:stop ends the run at the event */
    cli_result r = cli("plot pendulum --y phi --every 10");
    cli_result full = cli("plot pendulum --y phi");
    CHECK(r.status == 0 && strlen(r.out) < strlen(full.out), "--every 10: %d %s", r.status, r.err);
    cli_free(&r);
    cli_free(&full);
    r = cli("plot pendulum --y phi --event turn:stop");
    CHECK(r.status == 0, "--event: %d %s", r.status, r.err);
    cli_free(&r);
}

/* ---- numbers, parameters and initial states ---- */

static void test_numbers_states_and_results_checked(void **state)
{
    (void)state;
    /* one rule for numbers and expressions: what cannot be a double is refused */
    static const char *const refused[] = {"inf",          "1/inf", "1e400", "1/1e400", "1e-400",
                                          "1e-300/1e300", "nan",   "1/0",   "pi/inf"};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        cli_result r = cli("run pendulum --init phi=%s --final", refused[i]);
        CHECK(r.status == 2, "--init phi=%s: exit %d", refused[i], r.status);
        cli_free(&r);
    }
    /* numbers are decimal (docs/cli.md): strtod's hexadecimal form is refused, as model
     * files refuse it, in values, spans, sweeps' values and counts alike */
    static const char *const hex[] = {
        "run pendulum --set m=0x10 --final", "run pendulum --tspan 0:0x1 --final",
        "run pendulum --init phi=-0X1p-2 --final", "sweep pendulum --vary dphi=0x1:2:2",
        "sweep pendulum --sample 'dphi=uniform(0,1)' --runs 0x10"};
    for (size_t i = 0; i < sizeof hex / sizeof hex[0]; i++) {
        cli_result h = cli("%s", hex[i]);
        CHECK(h.status == 2 && strstr(h.err, "0"), "%s: exit %d (hexadecimal accepted)", hex[i],
              h.status);
        cli_free(&h);
    }
    /* subnormal numbers are finite numbers > 0: accepted */
    cli_result r = cli("run pendulum --init phi=1e-310 --method rk4 --step 0.1 --tspan 0:0.1");
    CHECK(r.status == 0 && strstr(r.out, "\n0,1e-310,"), "subnormal: %d %s %s",
          r.status, r.out, r.err);
    cli_free(&r);
    /* plane --set k=0: the default sZ = l0 + m g/k is infinite, named */
    r = cli("run plane --set k=0 --final");
    CHECK(r.status == 2 && strstr(r.err, "sZ"), "k=0: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run plane --set k=0 --init sZ=1 --method rk4 --tspan 0:0.1 --final");
    CHECK(r.status == 0, "k=0 with sZ given: %d %s", r.status, r.err);
    cli_free(&r);
    /* a zero quaternion, named */
    r = cli("run plane-quat --init qw=0 --final");
    CHECK(r.status == 2 && strstr(r.err, "quaternion"), "zero quaternion: %d %s", r.status, r.err);
    cli_free(&r);
    /* inverse cart: a table that is not finite is refused, no NaN/Inf written */
    r = cli("inverse cart --set v0=1e308");
    CHECK(r.status == 2 && strstr(r.err, "not finite") && !strstr(r.out, "inf") &&
              !strstr(r.out, "nan"),
          "v0=1e308: %d %s", r.status, r.err);
    cli_free(&r);
    /* its --output survives a failure too */
    write_text("f.csv", "x\n");
    r = cli_in_tmpdir("inverse cart --set v0=1e308 --output f.csv");
    CHECK(r.status != 0 && file_is("f.csv", "x\n"), "inverse --output after failure: %d", r.status);
    cli_free(&r);
}

/* ---- tables and --times files ---- */

/* A file of raw bytes for an input option, and the message it must give (NULL: accepted). */
typedef struct input_file {
    const char *name, *bytes;
    size_t len; /* 0: strlen(bytes) */
    const char *expect;
} input_file;

/* Each file written byte for byte, then `dynkit BEFORE NAME AFTER` run in the temporary
 * directory: exit 2 with the expected message and no raw escape byte, or exit 0. */
static void check_input_files(const input_file *files, size_t n, const char *before,
                              const char *after)
{
    for (size_t i = 0; i < n; i++) {
        FILE *f = fopen(cli_path(files[i].name), "wb");
        assert_non_null(f);
        fwrite(files[i].bytes, 1, files[i].len ? files[i].len : strlen(files[i].bytes), f);
        fclose(f);
        cli_result r = cli_in_tmpdir("%s%s%s", before, files[i].name, after);
        if (files[i].expect)
            CHECK(r.status == 2 && strstr(r.err, files[i].expect) && !strchr(r.err, 0x1B),
                  "%s: %d %s", files[i].name, r.status, r.err);
        else
            CHECK(r.status == 0, "%s: %d %s", files[i].name, r.status, r.err);
        cli_free(&r);
    }
}

static void test_table_files_of_every_kind(void **state)
{
    (void)state;
    static const input_file files[] = {
        {"bom.csv", "\xEF\xBB\xBFt,Fx,Fy\n0,1,2\n0.04,1,2\n", 0, NULL},
        {"cr.csv", "t,Fx,Fy\r0,1,2\r0.04,1,2\r", 0, "CR only"},
        {"u16.csv", "\xFF\xFEt\0,\0F\0x\0", 9, "UTF-16"},
        {"nul.csv", "t,Fx,Fy\n0,1\0,2\n", 15, "NUL byte"},
        {"esc.csv", "t,Fx,Fy\n0,\x1B[31mred,2\n", 0, "'\\x1B[31mred' is not a number"},
        {"dup.csv", "t,Fx,Fy,Fx\n0,1,2,3\n", 0, "'Fx' appears twice"},
    };
    check_input_files(files, sizeof files / sizeof files[0], "run cart --forces ", " --final");
    mkdir(cli_path("dir.csv"), 0755);
    cli_result r = cli_in_tmpdir("run cart --forces dir.csv");
    CHECK(r.status == 2 && strstr(r.err, "Is a directory"), "directory: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("run cart --forces /dev/zero");
    CHECK(r.status == 2 && strstr(r.err, "NUL byte"), "/dev/zero: %d %s", r.status, r.err);
    cli_free(&r);
    /* 150000 columns: the duplicate check is n log n (a quadratic one took 38 s) */
    FILE *f = fopen(cli_path("wide.csv"), "w");
    assert_non_null(f);
    fputs("t", f);
    for (int k = 0; k < 150000; k++)
        fprintf(f, ",c%d", k);
    fputs(",c7\n", f);
    fclose(f);
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    dyn_table t;
    char err[256];
    int rc = dyn_table_read_file(cli_path("wide.csv"), 0, &t, err, sizeof err);
    clock_gettime(CLOCK_MONOTONIC, &b);
    const double secs = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    CHECK(rc == DYN_ERR_ARG && strstr(err, "'c7' appears twice") && secs < 2.0,
          "150001 columns: rc %d in %.2f s: %s", rc, secs, err);
}

static void test_times_files_of_every_kind(void **state)
{
    (void)state;
    static const input_file files[] = {
        {"t_bom.txt",
         "\xEF\xBB\xBF"
         "0\n0.5\n",
         0, NULL},
        {"t_cr.txt", "0\r0.5\r", 0, "CR only"},
        {"t_u16.txt",
         "\xFF\xFE"
         "0\0\n\0",
         6, "UTF-16"},
        {"t_nul.txt",
         "0\n0.\0"
         "5\n",
         7, "NUL byte"},
        {"t_esc.txt", "0\n\x1B[2J\n", 0, "\\x1B[2J"},
    };
    check_input_files(files, sizeof files / sizeof files[0], "run pendulum --method dp45 --times @",
                      "");
    /* a line of 300 digits is one time, not two */
    FILE *f = fopen(cli_path("t_long.txt"), "w");
    assert_non_null(f);
    fputs("0.", f);
    for (int k = 0; k < 300; k++)
        fputc('0', f);
    fputs("1\n0.5\n", f);
    fclose(f);
    cli_result r = cli_in_tmpdir("run pendulum --method dp45 --times @t_long.txt");
    CHECK(r.status == 0 && valid_csv_rows(r.out, 3) == 2, "long line: %d %s %s", r.status, r.out,
          r.err);
    cli_free(&r);
    r = cli("run pendulum --method dp45 --times @/dev/zero");
    CHECK(r.status == 2 && strstr(r.err, "NUL byte"), "/dev/zero: %d %s", r.status, r.err);
    cli_free(&r);
    mkdir(cli_path("tdir"), 0755);
    r = cli_in_tmpdir("run pendulum --method dp45 --times @tdir");
    CHECK(r.status == 2 && strstr(r.err, "Is a directory"), "directory: %d %s", r.status, r.err);
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_late_errors_keep_the_output_file),
        cmocka_unit_test(test_outputs_never_replace_inputs),
        cmocka_unit_test(test_values_may_be_formulas_of_the_parameters),
        cmocka_unit_test(test_dash_with_a_format_is_standard_output),
        cmocka_unit_test(test_failed_run_with_samples_keeps_them),
        cmocka_unit_test(test_pages_replace_their_file_in_one_rename),
        cmocka_unit_test(test_bad_output_paths_name_the_file),
        cmocka_unit_test(test_stdout_failures_are_reported),
        cmocka_unit_test(test_closed_pipe_ends_quietly),
        cmocka_unit_test(test_signals_leave_complete_rows),
        cmocka_unit_test(test_step_larger_than_span_reaches_t1),
        cmocka_unit_test(test_failed_thinned_run_keeps_last_good_sample),
        cmocka_unit_test(test_tolerances_below_rounding_are_raised),
        cmocka_unit_test(test_step_size_underflow_near_zero),
        cmocka_unit_test(test_adaptive_runs_have_a_step_limit),
        cmocka_unit_test(test_fixed_step_runs_have_a_step_limit),
        cmocka_unit_test(test_default_runs_are_accurate_for_any_span),
        cmocka_unit_test(test_robertson_stays_in_its_domain),
        cmocka_unit_test(test_info_numbers_events_columns),
        cmocka_unit_test(test_view_commands_take_what_they_list),
        cmocka_unit_test(test_numbers_states_and_results_checked),
        cmocka_unit_test(test_table_files_of_every_kind),
        cmocka_unit_test(test_times_files_of_every_kind),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
