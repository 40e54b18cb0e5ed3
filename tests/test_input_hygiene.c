/* SPDX-License-Identifier: BSD-3-Clause */
/* Inputs that are no doubles, bytes that are no text, and a zero with a sign:
 *
 * - a model file's number beyond the range of doubles (1e999) or below it (1e-999, which
 *   would be 0), and a parameter's, number's, initial value's or initial guess's constant
 *   formula that is not finite (1/0, exp(1000)) are refused when the file is translated,
 *   at FILE:LINE:COL, as the command line refuses them; a value that depends on parameters
 *   is checked at each run;
 * - `info` of a model whose title, description, units and descriptions hold terminal
 *   control sequences (ESC [, OSC ... BEL, the C1 CSI 0x9B), and the error messages of
 *   sweep --from and --resume quoting a file's column names and header, and the message of
 *   a failed run naming a model file, write those bytes as \xNN: nothing reaches the
 *   terminal raw; UTF-8 text (units in degrees) is kept; so do a parse error's FILE:LINE:COL
 *   and source line (DEL, C1 controls; the caret under the escaped text), derive's and
 *   linearize's headers and --verbose's notes for a file so named;
 * - JSON writes negative zero as -0.0, which Python's json reads back as -0.0 (it reads
 *   "-0" as the integer 0);
 * - sweep --sample refuses, before any run, a distribution whose values can be infinite:
 *   uniform(-1e308,1e308) (B - A overflows), normal(1e308,1e307), lognormal(0,100). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/lang.h"
#include "test_cli_run.h"
#include "test_util.h"

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("hygiene");
}

static void write_text(const char *name, const char *text)
{
    assert_int_equal(cli_write_file(name, text), 0);
}

/* 1 if text holds a byte below 0x20 other than line feed and tab, DEL or a C1 byte after
 * 0xC2 (U+0080..U+009F), or 0x9B alone. */
static int has_control_bytes(const char *text)
{
    for (const unsigned char *p = (const unsigned char *)text; *p; p++)
        if ((*p < 0x20 && *p != '\n' && *p != '\t') || *p == 0x7F ||
            (*p == 0xC2 && p[1] >= 0x80 && p[1] <= 0x9F) || *p == 0x9B)
            return 1;
    return 0;
}

static void test_values_that_are_no_doubles_are_refused_at_their_place(void **state)
{
    (void)state;
    static const struct {
        const char *text, *why;
        int line, col;
    } cases[] = {
        {"x'=1e999\ninit x=1\n", "'1e999' is beyond the range of doubles", 1, 4},
        {"x'=-x*1e-999\ninit x=1\n", "'1e-999' is below the smallest double", 1, 7},
        {"par a=1e999\nx'=-a*x\n", "'1e999' is beyond the range of doubles", 1, 7},
        {"par a=1/0\nx'=-a*x\n", "the value of parameter 'a' is not finite (inf)", 1, 8},
        {"number a=-exp(1000)\nx'=-a*x\n", "the value of number 'a' is not finite", 1, 10},
        {"par a=1\nx'=-x+y\nsolv y=1/0\n0=y-1\ninit x=1\n",
         "the initial guess of 'y' is not finite (inf)", 3, 9},
        {"x'=-x\ninit x=0/0\n", "the initial value of 'x' is not finite", 2, 9},
        {"x'=-x\nx(0)=exp(1000)\n", "the initial value of 'x' is not finite (inf)", 2, 6},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char *c_src = NULL;
        dyn_lang_diag d;
        const int rc = dyn_ode_to_c("v.ode", cases[k].text, strlen(cases[k].text), &c_src, &d,
                                    NULL, NULL);
        CHECK(rc == 2 && strstr(d.message, cases[k].why) && d.line == cases[k].line &&
                  d.col == cases[k].col,
              "%s: rc %d, %d:%d: %s", cases[k].text, rc, d.line, d.col, d.message);
        free(c_src);
    }
    /* the smallest subnormal and the largest double are numbers; so is 0e999 */
    static const char fine[] = "par a=4.9e-324,b=1.7976931348623157e308,c=0e999\nx'=-a*x\n";
    char *c_src = NULL;
    dyn_lang_diag d;
    CHECK(dyn_ode_to_c("v.ode", fine, strlen(fine), &c_src, &d, NULL, NULL) == 0, "%s",
          d.message);
    free(c_src);
    /* through the command line: exit 2 with the place, not a run that fails */
    write_text("big.ode", "x'=1e999\ninit x=1\ndone\n");
    cli_result r = cli("run %s --final", cli_path("big.ode"));
    CHECK(r.status == 2 && strstr(r.err, "big.ode:1:4: error: the number '1e999'") &&
              r.out_len == 0,
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
}

static void test_terminal_control_bytes_are_escaped(void **state)
{
    (void)state;
    /* ESC [ 31 m (colour), OSC 0 ; title BEL, ESC [ 2 J (clear), C1 CSI (0xC2 0x9B) */
    write_text("esc.ode", "#: title T\033[31mRED\n"
                          "#: description D\033]0;pwned\007 x\n"
                          "#: x [m\033[2J] pos \033[5m\n"
                          "#: k [\xC2\x9B" "31m] kk\n"
                          "#: v [\xC2\xB0/s] rate in degrees\n"
                          "par k=1\nx'=-k*x\naux v=x\ninit x=1\ndone\n");
    cli_result r = cli("info %s", cli_path("esc.ode"));
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    CHECK(!has_control_bytes(r.out), "info writes control bytes raw:\n%s", r.out);
    CHECK(strstr(r.out, "T\\x1B[31mRED") && strstr(r.out, "D\\x1B]0;pwned\\x07 x") &&
              strstr(r.out, "m\\x1B[2J") && strstr(r.out, "\\xC2\\x9B31m") &&
              strstr(r.out, "\xC2\xB0/s"),
          "info does not show the bytes escaped (and UTF-8 kept):\n%s", r.out);
    cli_free(&r);

    /* sweep --from: a column name; --resume: the header quoted */
    write_text("from.csv", "run,mu\033[31m\n0,1\n");
    r = cli("sweep vanderpol --from %s", cli_path("from.csv"));
    CHECK(r.status == 2 && strstr(r.err, "mu\\x1B[31m") && !has_control_bytes(r.err),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    write_text("resume.csv", "run,m\033[1mu,final_y1\n0,1,2\n");
    r = cli("sweep vanderpol --vary mu=1:2:2 --resume %s", cli_path("resume.csv"));
    CHECK(r.status == 2 && strstr(r.err, "run,m\\x1B[1mu,final_y1") && !has_control_bytes(r.err),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* a model file whose name holds ESC [ 31 m: the message of a failed run names it
     * escaped (x' = sqrt(1 - t) is NaN after t = 1) */
    write_text("m\033[31m.ode", "x'=sqrt(1-t)\ninit x=1\n@ total=2\ndone\n");
    r = cli("run '%s' --final", cli_path("m\033[31m.ode"));
    CHECK(r.status == 1 && strstr(r.err, "of model m\\x1B[31m became") && !has_control_bytes(r.err),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* a --from table of numbers: the field quoted in the message */
    write_text("field.csv", "mu\n1\x1B[1m\n");
    r = cli("sweep vanderpol --from %s", cli_path("field.csv"));
    CHECK(r.status == 2 && !has_control_bytes(r.err), "exit %d: %s", r.status, r.err);
    cli_free(&r);
}

/* A file name holding ESC [ 31 m, the C1 CSI as UTF-8 (0xC2 0x9B) and alone (0x9B), and a
 * source line holding DEL and the C1 CSI: the FILE:LINE:COL of a parse error, its source
 * excerpt, derive's and linearize's headers, info, and the notes of --verbose (compiled in
 * or loaded from the cache) show them \xNN, and the caret stands under the escaped byte. */
static void test_hostile_file_names_in_every_message(void **state)
{
    (void)state;
#define HOSTILE "h\033[31m\xC2\x9B\x9B"
#define SHOWN "h\\x1B[31m\\xC2\\x9B\\x9B"
    char cmd[2048], mech[600], ode[600]; /* cli_path's buffer is static: copied */
    snprintf(mech, sizeof mech, "%s", cli_path(HOSTILE ".mech"));
    snprintf(ode, sizeof ode, "%s", cli_path(HOSTILE ".ode"));
    snprintf(cmd, sizeof cmd, "cp '%s/examples/mechanisms/double_pendulum.mech' '%s' && "
             "cp '%s/examples/models/pendulum.ode' '%s'", DYNKIT_SOURCE_DIR, mech,
             DYNKIT_SOURCE_DIR, ode);
    assert_int_equal(system(cmd), 0);
    static const struct {
        const char *args; /* %s: the file */
        int mech, on_stdout, status;
        const char *want;
    } cases[] = {
        {"derive '%s'", 1, 1, 0, SHOWN ": equations of motion by TMT"},
        {"linearize '%s'", 0, 1, 0, SHOWN " at t = 0:"},
        {"info '%s'", 0, 1, 0, SHOWN},
        {"run '%s' --verbose --tspan 0:0.1", 0, 0, 0, SHOWN ".ode: "},
        {"run '%s' --verbose --tspan 0:0.1", 1, 0, 0, SHOWN ".mech: "},
        /* the reports' own lines: --project-init's, a run that fails */
        {"run '%s' --project-init --tspan 0:0.01", 1, 0, 0,
         SHOWN ".mech has no constraints; nothing changed"},
        {"run '%s' --method euler --step 1 --tspan 0:2 --set l=0", 0, 0, 1,
         "of model " SHOWN " became NaN or Inf"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char args[1024];
        snprintf(args, sizeof args, cases[i].args, cases[i].mech ? mech : ode);
        cli_result r = cli("%s", args);
        const char *text = cases[i].on_stdout ? r.out : r.err;
        CHECK(r.status == cases[i].status && !has_control_bytes(r.out) &&
                  !has_control_bytes(r.err) && strstr(text, cases[i].want),
              "%s: exit %d, want '%s' and no control byte; stdout:\n%s\nstderr:\n%s", args,
              r.status, cases[i].want, r.out, r.err);
        cli_free(&r);
    }
    /* a parse error in such a file, at a line holding DEL, U+009B and a lone 0x9B */
    write_text(HOSTILE "-bad.ode", "x'=-x + \x7F\xC2\x9B\x9B 1\ndone\n");
    cli_result r = cli("run '%s'", cli_path(HOSTILE "-bad.ode"));
    CHECK(r.status == 2 && !has_control_bytes(r.err) &&
              strstr(r.err, SHOWN "-bad.ode:1:9: error: ") &&
              strstr(r.err, "\n  x'=-x + \\x7F\\xC2\\x9B\\x9B 1\n          ^\n"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* and in a mechanism file: a bad statement, its name escaped */
    write_text(HOSTILE "-bad.mech", "coord q=0 [rad]\nbody b mass=1 \x7F at (q, 0, 0)\n");
    r = cli("derive '%s'", cli_path(HOSTILE "-bad.mech"));
    CHECK(r.status == 2 && !has_control_bytes(r.err) && strstr(r.err, SHOWN "-bad.mech:2:"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* a model's boundary conditions, which run does not use: said with the model's name */
    write_text(HOSTILE "-bvp.ode", "x'=y\ny'=-x\nbdry x\nbdry y-1\ndone\n");
    r = cli("run '%s' --tspan 0:1 --final", cli_path(HOSTILE "-bvp.ode"));
    CHECK(r.status == 0 && !has_control_bytes(r.err) &&
              strstr(r.err, "note: " SHOWN "-bvp's boundary conditions are not used"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
    /* the library's formatter itself: the caret counts a UTF-8 character as one column and
     * an escaped byte as four */
    dyn_lang_diag d;
    memset(&d, 0, sizeof d);
    snprintf(d.path, sizeof d.path, "a\033b.ode");
    snprintf(d.message, sizeof d.message, "m\033[2Jm");
    snprintf(d.excerpt, sizeof d.excerpt, "\xC2\xB0\x01=?");
    d.line = 3;
    d.col = 4; /* the '=': after the 2 bytes of the degree sign and the byte 1 */
    char buf[512];
    assert_string_equal(dyn_lang_diag_format(&d, buf, sizeof buf),
                        "a\\x1Bb.ode:3:4: error: m\\x1B[2Jm\n  \xC2\xB0\\x01=?\n       ^\n");
#undef HOSTILE
#undef SHOWN
}

static void test_negative_zero_reads_back_in_json(void **state)
{
    (void)state;
    /* x(0) = -0.0; after a step -0.0 + 0.5 * 0 = +0.0 (IEEE 754 round to nearest), so only
     * the first row has -0.0 */
    write_text("negz.ode", "x'=0\ny'=-1\ninit x=-0,y=0\n@ total=1\ndone\n");
    char model[600];
    snprintf(model, sizeof model, "%s", cli_path("negz.ode"));
    cli_result r = cli("run %s --method euler --step 0.5 --output %s", model,
                       cli_path("negz.json"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *json = cli_read_file(cli_path("negz.json"), NULL);
    CHECK(strstr(json, "[0,-0.0,0]") != NULL, "no -0.0 in:\n%s", json);
    free(json);
    if (access("/usr/bin/python3", X_OK) != 0)
        return;
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "/usr/bin/python3 -c \"import json, math; d = json.load(open('%s')); "
             "print(math.copysign(1, d['rows'][0][1]), type(d['rows'][0][1]).__name__)\"",
             cli_path("negz.json"));
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(status == 0 && strcmp(out, "-1.0 float\n") == 0, "python reads: %s", out);
    free(out);
}

static void test_samples_that_can_be_infinite_are_refused(void **state)
{
    (void)state;
    static const struct {
        const char *sample, *why;
    } cases[] = {
        {"mu=uniform(-1e308,1e308)", "B - A is beyond the range of doubles"},
        {"mu=normal(1e308,1e307)", "must be finite numbers"},
        {"mu=lognormal(0,100)", "beyond the range of doubles: give M + 8.65 S <= 709.783"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cli_result r = cli("sweep vanderpol --tspan 0:1 --sample '%s' --runs 3", cases[k].sample);
        CHECK(r.status == 2 && strstr(r.err, cases[k].why) && r.out_len == 0,
              "%s: exit %d: %s", cases[k].sample, r.status, r.err);
        cli_free(&r);
    }
    /* wide but finite: accepted, and the values drawn are finite */
    cli_result r = cli("sweep vanderpol --tspan 0:1e-3 --sample 'y1=uniform(-8e307,8e307)' "
                       "--runs 3");
    CHECK(r.status == 0 && !strstr(r.out, "inf"), "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values_that_are_no_doubles_are_refused_at_their_place),
        cmocka_unit_test(test_terminal_control_bytes_are_escaped),
        cmocka_unit_test(test_hostile_file_names_in_every_message),
        cmocka_unit_test(test_negative_zero_reads_back_in_json),
        cmocka_unit_test(test_samples_that_can_be_infinite_are_refused),
    };
    return cmocka_run_group_tests(tests, setup, cli_remove_tmpdir);
}
