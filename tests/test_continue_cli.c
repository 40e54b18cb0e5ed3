/* SPDX-License-Identifier: BSD-3-Clause */
/* test_continue_cli.c — dynkit continue's command line (docs/analysis.md, "Continuation"):
 * - the AUTO settings of a model file's @ lines are read by the model file's parser: a line
 *   continued with '\', blanks around '=', names in upper case, and not a commented line;
 *   a bad value is refused at its FILE:LINE:COL with what is accepted (exit 2); AUTOVAR
 *   names the state on the diagram's y axis;
 * - -o FILE writes the file and nothing on standard output, as run and equilibria do; '-'
 *   is CSV on standard output and '-.json' JSON, without the summary; no output option
 *   prints the summary;
 * - -o FILE.svg (and --svg): the Hopf normal form's diagram with the axes named with their
 *   units, the unstable equilibria dashed, HB labelled, the periodic branch by its maximum
 *   and minimum (two lines of segments, x = +-sqrt(p) for the circles of radius sqrt(p));
 * - -o FILE.html (and --html): a page holding the orbits, a dot per orbit at its maximum
 *   and minimum; orbits beyond the page's budget are thinned, the labelled ones kept;
 *   extensions that are not accepted are refused with the accepted ones;
 * - the summary's words at a Hopf point: the normal form's is supercritical (l1 = -1 < 0),
 *   a linear centre's (l1 = 0 exactly) degenerate; both points are marginal, not unstable
 *   (their eigenvalues +-i lie on the axis);
 * - a forced model (Duffing's x'' + d x' + x + x^3 = a cos(w t)) has no equilibria: its
 *   branch, that of the model frozen at t = 0, comes with a note naming the time t and the
 *   state whose rate moves with it, also from a = 0 when a is the parameter continued (the
 *   forcing grows along the branch); with a = 0 fixed there is no note (x = v = 0); a map
 *   whose F depends on the iteration t gets the same note;
 * - a start on a fold (x' = p - x^2 from p = 0, x = 0: f_x is singular, [f_x f_p] is not)
 *   is continued, along x > 0 with ds > 0 (the stable half x = sqrt(p) up to parmax) and
 *   along x < 0 with ds < 0 (the unstable half);
 * - every example of continue --help runs. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "test_cli_run.h"
#include "test_util.h"

/* the Hopf normal form z' = (p + i) z - z |z|^2 with units (x, y in m, p in 1/s): the
 * equilibrium 0 loses stability at p = 0, the circles of radius sqrt(p) and period 2 pi */
static const char hopf_ode[] = "# Hopf normal form\n"
                               "#: x [m] first coordinate\n"
                               "#: y [m] second coordinate\n"
                               "#: p [1/s] the real part of the eigenvalues\n"
                               "par p=-0.5\n"
                               "init x=0, y=0\n"
                               "x'=p*x-y-x*(x^2+y^2)\n"
                               "y'=x+p*y-y*(x^2+y^2)\n"
                               "# @ parmax=9\n"
                               "@ total=10, ds = 0.05,\\\n"
                               " PARMAX=1.5, parmin=-1\n"
                               "done\n";

static int setup(void **state)
{
    (void)state;
    if (cli_make_tmpdir("continue"))
        return -1;
    return cli_write_file("hopf.ode", hopf_ode);
}

static long count(const char *text, const char *what)
{
    long n = 0;
    for (const char *p = text; (p = strstr(p, what)) != NULL; p += strlen(what))
        n++;
    return n;
}

static void test_settings_from_the_files_at_lines(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("continue hopf.ode --par p --json");
    CHECK(r.status == 0, "%s", r.err);
    /* the continued line's parmax and parmin, not the commented parmax=9 */
    CHECK(strstr(r.out, "\"parmin\":-1,\"parmax\":1.5") != NULL, "%.300s", r.out);
    CHECK(strstr(r.out, "\"ds\":0.050000000000000003") != NULL, "%.300s", r.out);
    cli_free(&r);

    cli_write_file("bad.ode", "par p=-0.5\nx'=p*x\n@ total=10\n@ ds=0.01, ntst=abc\ndone\n");
    r = cli_in_tmpdir("continue bad.ode --par p");
    CHECK(r.status == 2 && strstr(r.err, "bad.ode:4:17: ntst=abc: give a finite number"),
          "exit %d: %s", r.status, r.err);
    CHECK(r.out[0] == 0, "%s", r.out);
    cli_free(&r);
    cli_write_file("bad.ode", "par p=-0.5\nx'=p*x\n@ NMAX=0\ndone\n");
    r = cli_in_tmpdir("continue bad.ode --par p");
    CHECK(r.status == 2 && strstr(r.err, "bad.ode:3:8: nmax=0: give a whole number from 1"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);

    /* AUTOVAR names the state on the diagram's y axis (--y wins); a name that is no
     * state is refused at its place */
    cli_write_file("var.ode", "par p=-0.5\ninit x=0, y=0\nx'=p*x-y\ny'=x+p*y\n"
                              "@ total=10, parmax=1, autovar=y\ndone\n");
    r = cli_in_tmpdir("continue var.ode --par p -o var.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *svg = cli_read_file(cli_path("var.svg"), NULL);
    CHECK(svg && strstr(svg, ">y</text>") && !strstr(svg, ">x</text>"), "%.400s", svg);
    free(svg);
    r = cli_in_tmpdir("continue var.ode --par p --y x -o var.svg");
    cli_free(&r);
    svg = cli_read_file(cli_path("var.svg"), NULL);
    CHECK(svg && strstr(svg, ">x</text>") && !strstr(svg, ">y</text>"), "%.400s", svg);
    free(svg);
    cli_write_file("bad.ode", "par p=-0.5\nx'=p*x\n@ autovar=v\ndone\n");
    r = cli_in_tmpdir("continue bad.ode --par p");
    CHECK(r.status == 2 && strstr(r.err, "bad.ode:3:11: autovar=v: not a state of bad"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
}

static void test_output_file_keeps_stdout_empty(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("continue hopf.ode --par p");
    CHECK(r.status == 0 && strstr(r.out, "branch 1: equilibrium") && strstr(r.out, "HB  p = "),
          "%s%s", r.out, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("continue hopf.ode --par p -o d.csv");
    CHECK(r.status == 0 && r.out[0] == 0, "exit %d, stdout '%s': %s", r.status, r.out, r.err);
    cli_free(&r);
    char *csv = cli_read_file(cli_path("d.csv"), NULL);
    CHECK(strncmp(csv, "branch,kind,label,p,x,y,min_x,min_y,period,stable\n", 50) == 0, "%.80s",
          csv);
    free(csv);
    r = cli_in_tmpdir("continue hopf.ode --par p -o -");
    CHECK(r.status == 0 && strncmp(r.out, "branch,kind,label,p,", 20) == 0 &&
              !strstr(r.out, "branch 1:"),
          "%.200s", r.out);
    cli_free(&r);
    r = cli_in_tmpdir("continue hopf.ode --par p -o -.json");
    CHECK(r.status == 0 && r.out[0] == '{' && !strstr(r.out, "branch 1:"), "%.200s", r.out);
    cli_free(&r);
    r = cli_in_tmpdir("continue hopf.ode --par p --svg d2.svg");
    CHECK(r.status == 0 && r.out[0] == 0, "exit %d, stdout '%.100s'", r.status, r.out);
    cli_free(&r);
}

static void test_summary_words_at_a_hopf_point(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("continue hopf.ode --par p");
    const char *hb = strstr(r.out, "HB  p = ");
    CHECK(r.status == 0 && hb && strstr(hb, "(supercritical)  marginal\n"), "%s%s", r.out, r.err);
    cli_free(&r);
    CHECK(cli_write_file("centre.ode", "par p=-0.5\ninit x=0, y=0\nx'=p*x-y\ny'=x+p*y\n"
                                       "@ parmin=-1, parmax=1\ndone\n") == 0, "centre.ode");
    r = cli_in_tmpdir("continue centre.ode --par p");
    hb = strstr(r.out, "HB  p = ");
    CHECK(r.status == 0 && hb && strstr(hb, "l1 = 0 (degenerate") && strstr(hb, "marginal\n"),
          "%s%s", r.out, r.err);
    cli_free(&r);
}

static void test_forced_model_gets_a_note(void **state)
{
    (void)state;
    CHECK(cli_write_file("forced.ode", "par a=0.3, w=1.2, d=0.2\ninit x=0, v=0\nx'=v\n"
                                       "v'=-d*v-x-x^3+a*cos(w*t)\ndone\n") == 0, "forced.ode");
    static const char *const forced[] = {"continue forced.ode --par a",
                                         "continue forced.ode --par a --set a=0",
                                         "continue forced.ode --par d"};
    for (size_t i = 0; i < sizeof forced / sizeof *forced; i++) {
        cli_result r = cli_in_tmpdir(forced[i]);
        CHECK(r.status == 0 && strstr(r.out, "branch 1: equilibrium") &&
                  strstr(r.err, "note: f depends on the time t (v' at ") &&
                  strstr(r.err, "equilibria of the model frozen at t = 0, not of the forced"),
              "%s: exit %d: %s%s", forced[i], r.status, r.out, r.err);
        cli_free(&r);
    }
    cli_result r = cli_in_tmpdir("continue forced.ode --par d --set a=0");
    CHECK(r.status == 0 && strstr(r.out, "EP  d = 0.2  x = 0, v = 0  stable") &&
              !strstr(r.err, "depends on the time"),
          "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    CHECK(cli_write_file("tmap.ode", "par r=2.5\ninit x=0.5\nx(t+1)=r*x*(1-x)+0.01*cos(t)\n"
                                     "@ meth=discrete, parmax=4\ndone\n") == 0, "tmap.ode");
    r = cli_in_tmpdir("continue tmap.ode --par r");
    CHECK(r.status == 0 && strstr(r.err, "F depends on the time t (x(t+1) at r = 2.5") &&
              strstr(r.err, "fixed points of the model frozen at t = 0"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
}

static void test_start_on_a_fold(void **state)
{
    (void)state;
    CHECK(cli_write_file("fold0.ode", "par p=0\ninit x=0\nx'=p-x^2\n@ parmin=-1, parmax=1\n"
                                      "done\n") == 0, "fold0.ode");
    cli_result r = cli_in_tmpdir("continue fold0.ode --par p");
    CHECK(r.status == 0 && strstr(r.out, "stopped: reached parmax = 1") &&
              strstr(r.out, "EP  p = 1  x = 1  stable"), "exit %d: %s%s", r.status, r.out, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("continue fold0.ode --par p --opt ds=-0.02");
    CHECK(r.status == 0 && strstr(r.out, "EP  p = 1  x = -1  unstable"), "exit %d: %s%s",
          r.status, r.out, r.err);
    cli_free(&r);
}

static void test_svg_of_the_diagram(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("continue hopf.ode --par p -o d.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *svg = cli_read_file(cli_path("d.svg"), NULL);
    CHECK(strstr(svg, ">p [1/s]</text>") && strstr(svg, ">x [m]</text>"), "axis names: %.400s",
          svg);
    CHECK(strstr(svg, ">HB</text>") && strstr(svg, ">stable</text>") &&
              strstr(svg, ">unstable</text>"),
          "labels and key");
    /* the equilibria past p = 0 dashed; the periodic branch (every point stable) twice */
    const long dashed = count(svg, "stroke-dasharray=\"5,4\"/>");
    CHECK(dashed >= 4, "%ld dashed segments (the key has one)", dashed);
    CHECK(count(svg, "dk-orbit") == 0, "no dots in the SVG of --output");
    char *csv = NULL;
    r = cli_in_tmpdir("continue hopf.ode --par p -o -");
    csv = r.out;
    long periodic = count(csv, ",periodic,");
    CHECK(periodic >= 5, "%ld periodic points", periodic);
    const long solid = count(svg, "stroke=\"#d62728\"/>");
    CHECK(solid == 2 * (periodic - 1), "%ld segments of the periodic branch for %ld points", solid,
          periodic);
    /* --svg writes the same picture */
    cli_result r2 = cli_in_tmpdir("continue hopf.ode --par p --svg same.svg");
    CHECK(r2.status == 0, "%s", r2.err);
    char *same = cli_read_file(cli_path("same.svg"), NULL);
    CHECK(strcmp(same, svg) == 0, "--svg and -o FILE.svg differ");
    free(same);
    cli_free(&r2);
    cli_free(&r);
    free(svg);
}

static void test_page_of_the_diagram(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("continue hopf.ode --par p -o d.html");
    CHECK(r.status == 0 && r.out[0] == 0, "exit %d: %s", r.status, r.err);
    cli_free(&r);
    char *page = cli_read_file(cli_path("d.html"), NULL);
    CHECK(strstr(page, "\"kind\":\"diagram\"") != NULL, "the diagram's data");
    r = cli_in_tmpdir("continue hopf.ode --par p -o -");
    const long periodic = count(r.out, ",periodic,");
    cli_free(&r);
    const long orbits = count(page, "\"period\":");
    CHECK(orbits == periodic && periodic > 0, "%ld orbits on the page, %ld periodic points", orbits,
          periodic);
    CHECK(count(page, "class=\\\"dk-orbit\\\"") == 2 * orbits, "%ld dots for %ld orbits",
          count(page, "class=\\\"dk-orbit\\\""), orbits);
    /* no address but the SVG's namespace (a name, never fetched) */
    CHECK(count(page, "http://") == count(page, "http://www.w3.org/2000/svg") &&
              !strstr(page, "https://"),
          "no address in the page");
    free(page);
    r = cli_in_tmpdir("continue hopf.ode --par p --html d2.htm --output d2.csv");
    CHECK(r.status == 0 && r.out[0] == 0, "exit %d: %s", r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("continue hopf.ode --par p --html d.svg");
    CHECK(r.status == 2 && strstr(r.err, "--html") && strstr(r.err, ".html"), "exit %d: %s",
          r.status, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("continue hopf.ode --par p --output d.png");
    CHECK(r.status == 2 && strstr(r.err, ".csv") && strstr(r.err, ".svg") && strstr(r.err, ".html"),
          "exit %d: %s", r.status, r.err);
    cli_free(&r);
}

/* more orbits than the page holds: 60 intervals of 4 points, short steps */
static void test_page_thins_its_orbits(void **state)
{
    (void)state;
    cli_result r = cli("continue '%s/examples/models/brusselator.ode' --par b --opt ntst=60 "
                       "--opt dsmax=0.05 -o '%s'",
                       DYNKIT_SOURCE_DIR, cli_path("thin.html"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *page = cli_read_file(cli_path("thin.html"), NULL);
    const char *c = strstr(page, "\"orbits_computed\":");
    assert_non_null(c);
    const long computed = strtol(c + 18, NULL, 10), kept = count(page, "\"period\":");
    /* 241 nodes of t, x, y per orbit: at most 30000 numbers */
    CHECK(kept < computed && kept * 241 * 3 <= 30000 && kept >= 30000 / (2 * 241 * 3),
          "%ld of %ld orbits kept", kept, computed);
    /* the branch's end points are labelled: both kept */
    CHECK(count(page, "\"label\":\"EP\"") == 2, "%ld EP orbits", count(page, "\"label\":\"EP\""));
    free(page);
}

/* every example of `dynkit continue --help` runs (from a folder with examples/ linked in) */
static void test_help_examples_run(void **state)
{
    (void)state;
    char link[600];
    snprintf(link, sizeof link, "%s/examples", cli_tmpdir);
    assert_int_equal(symlink(DYNKIT_SOURCE_DIR "/examples", link), 0);
    cli_result h = cli("continue --help");
    const char *ex = strstr(h.out, "Examples:\n");
    assert_non_null(ex);
    char line[2048] = "";
    int shown = 0;
    for (const char *p = ex + 10; *p;) {
        const char *e = strchr(p, '\n');
        const size_t n = e ? (size_t)(e - p) : strlen(p);
        size_t b = 0;
        while (b < n && p[b] == ' ')
            b++;
        strncat(line, p + b,
                n - b < sizeof line - strlen(line) - 1 ? n - b : sizeof line - strlen(line) - 1);
        p += n + (e ? 1 : 0);
        const size_t len = strlen(line);
        if (len && line[len - 1] == '\\') {
            line[len - 1] = ' ';
            continue;
        }
        if (strncmp(line, "dynkit ", 7) == 0) {
            cli_result r = cli_in_tmpdir("%s", line + 7);
            CHECK(r.status == 0, "shown: %s: exit %d: %s", line, r.status, r.err);
            cli_free(&r);
            shown++;
        }
        line[0] = 0;
    }
    CHECK(shown >= 3, "%d examples", shown);
    cli_free(&h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_settings_from_the_files_at_lines),
        cmocka_unit_test(test_output_file_keeps_stdout_empty),
        cmocka_unit_test(test_summary_words_at_a_hopf_point),
        cmocka_unit_test(test_forced_model_gets_a_note),
        cmocka_unit_test(test_start_on_a_fold),
        cmocka_unit_test(test_svg_of_the_diagram),
        cmocka_unit_test(test_page_of_the_diagram),
        cmocka_unit_test(test_page_thins_its_orbits),
        cmocka_unit_test(test_help_examples_run),
    };
    return cmocka_run_group_tests(tests, setup, cli_remove_tmpdir);
}
