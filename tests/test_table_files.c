/* SPDX-License-Identifier: BSD-3-Clause */
/* What a model file's `table NAME FILE` may open: a regular file beside the model file,
 * named without a folder, and not a symbolic link; a file anywhere else only when the
 * command line names it (--table NAME=FILE). Each refusal is a usage error (exit 2) at
 * FILE:LINE:COL naming the file and what is accepted, and a FIFO is refused at once rather
 * than blocking the tool (each command runs under `timeout`, so a blocked open fails the
 * test instead of hanging it).
 *
 * The table read is checked by a closed form: x' = h(t), x(0) = 0, with h interpolating
 * (0, 0), (1, 1), (2, 4) linearly, gives x(2) = 1/2 + 5/2 = 3. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "dynkit/lang.h"
#include "test_cli_run.h"
#include "test_util.h"

static int setup(void **state)
{
    (void)state;
    if (cli_make_tmpdir("tables"))
        return -1;
    char cmd[700];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s/m/sub' '%s/data'", cli_tmpdir, cli_tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

static void write_text(const char *name, const char *text)
{
    assert_int_equal(cli_write_file(name, text), 0);
}

#define TABLE "3 0 2\n0 1 4\n"

/* m/NAME.ode reading its table h from `file`. */
static void write_model(const char *name, const char *file)
{
    char path[128], text[1024];
    snprintf(path, sizeof path, "m/%s.ode", name);
    snprintf(text, sizeof text, "table h %s\nx'=h(t)\ninit x=0\n@ total=2\ndone\n", file);
    write_text(path, text);
}

/* `dynkit ARGS` from inside tmpdir/m, ended after 20 s if it blocks (exit 124). */
static cli_result in_model_dir(const char *args)
{
    char dir[300];
    snprintf(dir, sizeof dir, "%s/m", cli_tmpdir);
    return cli_run_at(dir, "timeout 20 ", args);
}

/* The final x of a --final run's CSV output "t,x\n2,X\n". */
static double final_x(const char *out)
{
    const char *row = strchr(out, '\n');
    assert_non_null(row);
    const char *comma = strchr(row + 1, ',');
    assert_non_null(comma);
    return strtod(comma + 1, NULL);
}

static void test_a_table_beside_the_model_is_read(void **state)
{
    (void)state;
    write_text("m/pump.tab", TABLE);
    write_model("beside", "pump.tab");
    cli_result r = in_model_dir("run beside.ode --final --rtol 1e-10 --atol 1e-12");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK(fabs(final_x(r.out) - 3.0) < 1e-8, "x(2) = %s, expected 3", r.out);
    cli_free(&r);
    /* from another folder: beside the model file, not the current folder */
    r = cli_in_tmpdir("run m/beside.ode --final --rtol 1e-10 --atol 1e-12");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK(fabs(final_x(r.out) - 3.0) < 1e-8, "x(2) = %s, expected 3", r.out);
    cli_free(&r);
}

static void test_files_elsewhere_are_refused_by_name(void **state)
{
    (void)state;
    write_text("data/pump.tab", TABLE);
    write_text("m/sub/pump.tab", TABLE);
    char target[600], link[600], fifo[600];
    snprintf(target, sizeof target, "%s/data/pump.tab", cli_tmpdir);
    snprintf(link, sizeof link, "%s/m/outside.tab", cli_tmpdir);
    assert_int_equal(symlink(target, link), 0);
    snprintf(link, sizeof link, "%s/m/inside.tab", cli_tmpdir);
    assert_int_equal(symlink("sub/pump.tab", link), 0);
    snprintf(fifo, sizeof fifo, "%s/m/fifo.tab", cli_tmpdir);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    static const struct {
        const char *file, *why;
    } cases[] = {
        {NULL, "is not read"}, /* the absolute path of data/pump.tab */
        {"../data/pump.tab", "is not read"},
        {"sub/pump.tab", "is not read"},
        {"/dev/stdin", "is not read"},
        {"/etc/passwd", "is not read"},
        {"..", "is not read"},
        {"fifo.tab", "is a FIFO"},
        {"outside.tab", "is a symbolic link"},
        {"inside.tab", "is a symbolic link"},
        {"sub", "is a directory"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const char *file = cases[k].file ? cases[k].file : target;
        write_model("bad", file);
        cli_result r = in_model_dir("run bad.ode --final");
        CHECK(r.status == 2, "table h %s: exit %d, expected 2: %s", file, r.status, r.err);
        CHECK(strstr(r.err, "bad.ode:1:9: error: table 'h': ") && strstr(r.err, cases[k].why) &&
                  strstr(r.err, file),
              "table h %s: the message does not name the file and '%s': %s", file,
              cases[k].why, r.err);
        if (strcmp(cases[k].why, "is not read") == 0 || strcmp(cases[k].why, "is a FIFO") == 0)
            CHECK(strstr(r.err, "a regular file beside the model file, named without a folder") &&
                      strstr(r.err, "--table h=FILE"),
                  "table h %s: the message does not say what is accepted: %s", file, r.err);
        cli_free(&r);
    }
    /* the library alone, with the model's text in memory: the same rule */
    char *c_src = NULL;
    dyn_lang_diag d;
    static const char fifo_model[] = "table h fifo.tab\nx'=h(t)\ndone\n";
    char model_path[600];
    snprintf(model_path, sizeof model_path, "%s/m/lib.ode", cli_tmpdir);
    assert_int_equal(dyn_ode_to_c(model_path, fifo_model, strlen(fifo_model), &c_src, &d, NULL,
                                  NULL),
                     2);
    CHECK(strstr(d.message, "is a FIFO") && d.line == 1 && d.col == 9, "%s", d.message);
}

static void test_the_command_line_names_a_table_file(void **state)
{
    (void)state;
    write_text("data/pump.tab", TABLE);
    write_model("pump", "pump.tab"); /* no pump.tab beside it */
    cli_result r = in_model_dir("run pump.ode --table h=../data/pump.tab --final");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK(fabs(final_x(r.out) - 3.0) < 1e-5, "x(2) = %s, expected 3", r.out);
    cli_free(&r);
    /* instead of a file the model may not read, for plot, sweep and info too */
    write_model("etc", "/etc/passwd");
    r = in_model_dir("run etc.ode --table H=../data/pump.tab --final --rtol 1e-10 --atol 1e-12");
    CHECK(r.status == 0 && fabs(final_x(r.out) - 3.0) < 1e-8, "exit %d: %s%s", r.status, r.out,
          r.err);
    cli_free(&r);
    r = in_model_dir("plot etc.ode --table h=../data/pump.tab --y x --output ../x.svg");
    CHECK(r.status == 0, "plot: exit %d: %s", r.status, r.err);
    cli_free(&r);
    r = in_model_dir("sweep etc.ode --table h=../data/pump.tab --vary x=0:1:2 --rtol 1e-10 "
                     "--atol 1e-12");
    /* the last run starts at x = 1: x(2) = 1 + 3 */
    const char *last = strrchr(r.out, ',');
    CHECK(r.status == 0 && last && fabs(strtod(last + 1, NULL) - 4.0) < 1e-8, "sweep: exit %d: %s%s",
          r.status, r.out, r.err);
    cli_free(&r);
    r = in_model_dir("info etc.ode --table h=../data/pump.tab");
    CHECK(r.status == 0 && strstr(r.out, "States"), "info: exit %d: %s", r.status, r.err);
    cli_free(&r);

    static const struct {
        const char *args, *why;
    } bad[] = {
        /* a named file must be a regular file too, and is never waited on */
        {"run pump.ode --table h=fifo.tab --final", "the file named for it, is a FIFO"},
        {"run pump.ode --table h=/dev/stdin --final", "the file named for it, is a"},
        {"run pump.ode --table h=sub --final", "the file named for it, is a directory"},
        {"run pump.ode --table h=nosuch.tab --final", "cannot read 'nosuch.tab'"},
        {"run pump.ode --table g=../data/pump.tab --final", "reads no table 'g' from a file"},
        {"run pump.ode --table h --final", "give NAME=FILE"},
        {"run pump.ode --table =x --final", "give NAME=FILE"},
        {"run pendulum --table h=../data/pump.tab --final", "not a model file NAME.ode"},
        {"info pump.ode --table", "needs a value"},
        {"info pump.ode --tabel h=x", "accepted: --table NAME=FILE"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        r = in_model_dir(bad[k].args);
        CHECK(r.status == 2 && strstr(r.err, bad[k].why), "%s: exit %d, expected 2 and '%s': %s",
              bad[k].args, r.status, bad[k].why, r.err);
        cli_free(&r);
    }
}

static void test_help_lists_the_option(void **state)
{
    (void)state;
    static const char *const commands[] = {"run", "plot", "animate", "sweep", "info"};
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) {
        cli_result r = cli("%s --help", commands[k]);
        CHECK(r.status == 0 && strstr(r.out, "--table NAME=FILE"), "%s --help: %s", commands[k],
              r.out);
        cli_free(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_table_beside_the_model_is_read),
        cmocka_unit_test(test_files_elsewhere_are_refused_by_name),
        cmocka_unit_test(test_the_command_line_names_a_table_file),
        cmocka_unit_test(test_help_lists_the_option),
    };
    return cmocka_run_group_tests(tests, setup, cli_remove_tmpdir);
}
