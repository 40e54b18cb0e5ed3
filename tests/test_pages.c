/* SPDX-License-Identifier: BSD-3-Clause */
/* The commands that draw, through the built binary (DYNKIT_CLI):
 * - `plot` writes a standalone SVG with a frame, ticks with numbers, axis labels with the
 *   model's units, a legend, and one polyline per line with one point per sample (thinned
 *   to at most 2000 for a long run, first and last kept); bad names exit 2 and list what is
 *   accepted (t, the states and the outputs).
 * - `animate` and `report --html` write one self-contained page: no http(s) reference, no
 *   external script, style or image, no marker of the template left, the data inline.
 * - --compare METHOD[:STEP] is validated (unknown method, bad step, missing value: exit 2),
 *   and each run it asks for is in the page or the plot, adaptive methods too (sampled on
 *   the grid of STEP). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_cli_run.h"
#include "test_util.h"

/* A file of the temporary directory (malloc'd). */
static char *file_in_tmp(const char *name) { return cli_read_file(cli_path(name), NULL); }

/* The last value of column col (0 = t) of the page's series labelled label, or NaN. */
static double last_series_value(const char *html, const char *label, int col)
{
    char want[160];
    snprintf(want, sizeof want, "\"label\":\"%s\"", label);
    const char *p = strstr(html, want);
    p = p ? strstr(p, "\"data\":[[") : NULL;
    if (!p)
        return NAN;
    p += strlen("\"data\":[");
    for (int c = 0; c < col && p; c++) {
        p = strchr(p, ']');
        p = p ? p + 2 : NULL; /* "],[" */
    }
    const char *end = p ? strchr(p, ']') : NULL;
    if (!end)
        return NAN;
    const char *q = end;
    while (q > p && q[-1] != ',' && q[-1] != '[')
        q--;
    return strtod(q, NULL);
}

static int count(const char *text, const char *what)
{
    int n = 0;
    for (const char *p = text; (p = strstr(p, what)) != NULL; p += strlen(what))
        n++;
    return n;
}

/* Points of the k-th polyline (0-based) of an SVG, or -1 when there is none. */
static long polyline_points(const char *svg, int k)
{
    const char *p = svg;
    for (int i = 0; i <= k; i++) {
        p = strstr(p, "<polyline");
        if (!p)
            return -1;
        p += 9;
    }
    p = strstr(p, "points=\"");
    assert_non_null(p);
    p += 8;
    long n = 1;
    for (; *p && *p != '"'; p++)
        n += *p == ' ';
    return n;
}

/* The text of the element with class name (first one), into buf. */
static const char *element_text(const char *svg, const char *cls, char *buf, size_t size)
{
    char key[64];
    snprintf(key, sizeof key, "class=\"%s\"", cls);
    const char *p = strstr(svg, key);
    buf[0] = '\0';
    if (!p || !(p = strchr(p, '>')))
        return buf;
    const char *end = strchr(++p, '<');
    size_t len = end ? (size_t)(end - p) : 0;
    if (len >= size)
        len = size - 1;
    memcpy(buf, p, len);
    buf[len] = '\0';
    return buf;
}

static int setup(void **state)
{
    (void)state;
    return cli_make_tmpdir("pages");
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"a.svg",      "b.svg",     "c.svg",  "report.html",
                                        "plane.html", "cart.html", "x.html", "vanderpol.html",
                                        "vanderpol-2.html", NULL};
    return cli_teardown_files(files);
}

/* ---- plot ---- */

static void test_plot_svg_has_axes_labels_units_and_every_sample(void **state)
{
    (void)state;
    cli_result r = cli("plot pendulum --method rk4 --step 0.01 --tspan 0:2 --y phi "
                       "--output '%s/a.svg'",
                       cli_tmpdir);
    CHECK(r.status == 0, "plot exit %d: %s", r.status, r.err);
    cli_free(&r);
    char *svg = file_in_tmp("a.svg"), text[256];
    CHECK(strncmp(svg, "<?xml", 5) == 0 && strstr(svg, "<svg xmlns=\"http://www.w3.org/2000/svg\""),
          "not an SVG document: %.80s", svg);
    CHECK(strstr(svg, "</svg>") != NULL, "unterminated SVG");
    CHECK(strstr(svg, "class=\"frame\"") != NULL, "no frame");
    CHECK(strcmp(element_text(svg, "xlabel", text, sizeof text), "t [s]") == 0, "x label '%s'",
          text);
    CHECK(strcmp(element_text(svg, "ylabel", text, sizeof text), "phi [rad]") == 0, "y label '%s'",
          text);
    CHECK(strstr(element_text(svg, "title", text, sizeof text), "pendulum") != NULL, "title '%s'",
          text);
    /* ticks: a numbered tick for 0 and 2 on the time axis, several on each axis */
    CHECK(count(svg, "text-anchor=\"middle\" stroke=\"none\">") >= 4, "too few x ticks");
    CHECK(count(svg, "text-anchor=\"end\" stroke=\"none\">") >= 4, "too few y ticks");
    CHECK(strstr(svg, ">0.0</text>") || strstr(svg, ">0</text>"), "no tick at 0");
    CHECK(strstr(svg, "class=\"legend\"") != NULL, "no legend");
    CHECK(count(svg, "<polyline") == 1, "%d polylines", count(svg, "<polyline"));
    CHECK(polyline_points(svg, 0) == 201, "%ld points for 201 samples", polyline_points(svg, 0));
    free(svg);
}

static void test_plot_several_names_units_and_compare(void **state)
{
    (void)state;
    cli_result r = cli("plot pendulum --method rk4 --step 0.01 --tspan 0:1 --y phi,dphi "
                       "--compare euler:0.02 --output '%s/b.svg'",
                       cli_tmpdir);
    CHECK(r.status == 0, "plot exit %d: %s", r.status, r.err);
    cli_free(&r);
    char *svg = file_in_tmp("b.svg"), text[256];
    /* rad and rad/s: one panel each, phi's first (its lines: the run, then the compared one) */
    CHECK(strcmp(element_text(svg, "ylabel", text, sizeof text), "phi [rad]") == 0,
          "y label '%s'", text);
    CHECK(count(svg, "class=\"panel\"") == 2 && count(svg, "class=\"ylabel\"") == 2,
          "%d panels, one per unit", count(svg, "class=\"panel\""));
    CHECK(strstr(svg, ">dphi [rad/s]</text>") != NULL, "no panel for dphi [rad/s]");
    CHECK(count(svg, "<polyline") == 4, "%d polylines for 2 names x 2 runs",
          count(svg, "<polyline"));
    CHECK(polyline_points(svg, 0) == 101 && polyline_points(svg, 2) == 101, "main run points");
    CHECK(polyline_points(svg, 1) == 51 && polyline_points(svg, 3) == 51, "euler:0.02 points");
    CHECK(strstr(svg, "phi (rk4, h = 0.01 s)") && strstr(svg, "dphi (euler, h = 0.02 s)"),
          "legend does not name the runs");
    free(svg);
    /* another abscissa, and an extra output as a name */
    r = cli("plot vanderpol --x y1 --y y2 --output '%s/c.svg'", cli_tmpdir);
    CHECK(r.status == 0, "phase plot exit %d: %s", r.status, r.err);
    cli_free(&r);
    svg = file_in_tmp("c.svg");
    CHECK(strstr(element_text(svg, "xlabel", text, sizeof text), "y1 [") == text, "x label '%s'",
          text);
    free(svg);
    /* energy [J] and height [m] on an axis each, never squashed onto one */
    r = cli("plot pendulum --y energy,height");
    CHECK(r.status == 0 && strstr(r.out, ">energy [J]</text>") && strstr(r.out, ">height [m]</text>") &&
              count(r.out, "class=\"panel\"") == 2,
          "outputs as names, a panel per unit: %d %s", r.status, r.err);
    /* the pendulum's energy, conserved by rk4 to about 1e-8 J of 237.45 J: its ticks differ
     * in the ninth decimal and are labelled from an offset (short labels that fit the
     * margin), the offset and scale written above the axis */
    cli_free(&r);
    r = cli("plot pendulum --method rk4 --step 0.01 --tspan 0:10 --y energy");
    const char *note = strstr(r.out, "class=\"offset\"");
    CHECK(r.status == 0 && note && strstr(note, "\xc3\x97" "1e-") &&
              strstr(note, " + 237.45"),
          "the energy axis has no offset note: %d %.300s", r.status, note ? note : r.err);
    for (const char *p = strstr(r.out, "text-anchor=\"end\" stroke=\"none\">"); p;
         p = strstr(p + 1, "text-anchor=\"end\" stroke=\"none\">")) {
        const char *label = strchr(p, '>') + 1;
        CHECK(strchr(label, '<') - label <= 4, "a long tick label: %.40s", label);
    }
    /* the same unit shares one axis */
    cli_free(&r);
    r = cli("plot plane --y sX,sZ --method rk4 --step 0.01 --tspan 0:0.5");
    CHECK(r.status == 0 && count(r.out, "class=\"panel\"") == 0 &&
              strstr(r.out, ">sX, sZ [m]</text>"),
          "sX and sZ, both in m, on one axis: %d %s", r.status, r.err);
    cli_free(&r);
}

static void test_plot_long_run_is_thinned(void **state)
{
    (void)state;
    cli_result r = cli("plot vanderpol --step 0.001 --tspan 0:100 --y y1");
    CHECK(r.status == 0, "plot exit %d: %s", r.status, r.err);
    long n = polyline_points(r.out, 0);
    CHECK(n <= 2000 && n >= 1900, "%ld points of 100001 samples (want at most 2000)", n);
    /* the first point is at the left of the frame, the last at t = 100 */
    const char *pts = strstr(strstr(r.out, "<polyline"), "points=\"") + 8;
    double x0 = strtod(pts, NULL);
    const char *last = strchr(pts, '"');
    while (last > pts && last[-1] != ' ')
        last--;
    double x1 = strtod(last, NULL);
    CHECK(x0 > 84.0 && x0 < 120.0 && x1 > 700.0 && x1 < 776.0, "ends at %g and %g px", x0, x1);
    cli_free(&r);
}

static void test_plot_bad_names_exit_2(void **state)
{
    (void)state;
    cli_result r = cli("plot vanderpol --y y1,nope --output '%s/a.svg'", cli_tmpdir);
    CHECK(r.status == 2, "bad --y exit %d", r.status);
    CHECK(strstr(r.err, "'nope'") && strstr(r.err, "accepted: t, y1, y2"),
          "message does not list the names: %s", r.err);
    CHECK(r.out[0] == '\0', "stdout not empty");
    cli_free(&r);
    r = cli("plot pendulum --x nope --y phi");
    CHECK(r.status == 2 && strstr(r.err, "t, phi, dphi, energy, height"), "bad --x: %d %s",
          r.status, r.err);
    cli_free(&r);
    r = cli("plot pendulum");
    CHECK(r.status == 2 && strstr(r.err, "missing --y"), "missing --y: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("plot pendulum --y");
    CHECK(r.status == 2, "--y without a value: %d", r.status);
    cli_free(&r);
    r = cli("plot nomodel --y x");
    CHECK(r.status == 2 && strstr(r.err, "unknown model"), "unknown model: %d", r.status);
    cli_free(&r);
}

/* ---- --compare ---- */

static void test_compare_is_validated(void **state)
{
    (void)state;
    static const struct {
        const char *value, *says;
    } bad[] = {
        {"nope", "unknown method 'nope'"},
        {"rk4:0", "the step '0'"},
        {"rk4:-1", "the step '-1'"},
        {"rk4:abc", "the step 'abc'"},
        {":0.1", "give METHOD or METHOD:STEP"},
        {"rk4:", "the step ''"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cli_result r =
            cli("animate vanderpol --compare '%s' --output '%s/x.html'", bad[i].value, cli_tmpdir);
        CHECK(r.status == 2, "--compare %s: exit %d", bad[i].value, r.status);
        CHECK(strstr(r.err, bad[i].says) != NULL, "--compare %s: message '%s'", bad[i].value,
              r.err);
        if (i == 0)
            CHECK(strstr(r.err, "rk4") && strstr(r.err, "euler"),
                  "unknown method: message does not list the methods: %s", r.err);
        cli_free(&r);
    }
    cli_result r = cli("animate vanderpol --compare");
    CHECK(r.status == 2 && strstr(r.err, "--compare needs a value"), "missing value: %d %s",
          r.status, r.err);
    cli_free(&r);
    r = cli("animate vanderpol --final");
    CHECK(r.status == 2, "--final accepted by animate");
    cli_free(&r);
    r = cli("plot vanderpol --y y1 --compare euler --compare rk4:0.001 --compare heun:pi/100");
    CHECK(r.status == 0 && count(r.out, "<polyline") == 4, "good --compare: %d %s", r.status,
          r.err);
    CHECK(strstr(r.out, "heun, h = 0.0314159 s") != NULL, "step pi/100 not read");
    cli_free(&r);
    /* adaptive methods: samples on the output grid of STEP (default the run's step) */
    r = cli("plot vanderpol --y y1 --compare dp45 --compare rodas4:0.05");
    CHECK(r.status == 0 && count(r.out, "<polyline") == 3, "adaptive --compare: %d %s", r.status,
          r.err);
    CHECK(polyline_points(r.out, 1) == 1501 && polyline_points(r.out, 2) == 301,
          "adaptive runs: %ld and %ld points", polyline_points(r.out, 1),
          polyline_points(r.out, 2));
    CHECK(strstr(r.out, "dp45, rtol = 1e-08, atol = 1e-10") != NULL, /* the model's */
          "the adaptive run's label does not give its tolerances");
    cli_free(&r);
}

/* ---- pages ---- */

static void check_self_contained(const char *html, const char *what)
{
    CHECK(strncmp(html, "<!DOCTYPE html>", 15) == 0, "%s: no doctype", what);
    CHECK(strstr(html, "</html>") != NULL, "%s: not complete", what);
    CHECK(!strstr(html, "http://") && !strstr(html, "https://"), "%s: has an http(s) reference",
          what);
    CHECK(!strstr(html, "<link") && !strstr(html, "src=") && !strstr(html, "url("),
          "%s: refers to another file", what);
    CHECK(!strstr(html, "<!--dynkit:"), "%s: a template marker is left", what);
    CHECK(strstr(html, "<style>") && strstr(html, "<script>"), "%s: style or script missing", what);
    CHECK(strstr(html, "<script id=\"dynkit-data\" type=\"application/json\">{") != NULL,
          "%s: no data", what);
    CHECK(count(html, "</script>") == 2, "%s: a script closes early", what);
    CHECK(strstr(html, "default-src 'none'") != NULL, "%s: no content security policy", what);
}

static void test_report_html_is_self_contained(void **state)
{
    (void)state;
    cli_result r = cli("report --html '%s/report.html'", cli_tmpdir);
    CHECK(r.status == 0, "report --html exit %d: %s", r.status, r.err);
    CHECK(r.out[0] == '\0', "report --html also printed to stdout");
    cli_free(&r);
    char *html = file_in_tmp("report.html");
    check_self_contained(html, "report");
    CHECK(strlen(html) < 1000000, "report page of %zu bytes", strlen(html));
    /* the answers as `report --json` gives them, and the runs behind them */
    r = cli("report --json");
    CHECK(r.status == 0, "report --json");
    const char *key = strstr(r.out, "\"plane.distance_m\": ");
    CHECK(key != NULL, "no plane.distance_m");
    char want[128];
    snprintf(want, sizeof want, "%.*s", (int)strcspn(key, ",\n"), key);
    CHECK(strstr(html, want) != NULL, "page lacks '%s'", want);
    cli_free(&r);
    static const char *const series[] = {
        "\"pendulum.nonlinear\":", "\"vanderpol.steps\":", "\"plane.euler\":",
        "\"plane.compare\":",      "\"cart.forward\":",    "\"cart.prescribed\":"};
    for (size_t i = 0; i < sizeof series / sizeof series[0]; i++)
        CHECK(strstr(html, series[i]) != NULL, "page lacks the series %s", series[i]);
    free(html);
    r = cli("report --html");
    CHECK(r.status == 2, "--html without a file: %d", r.status);
    cli_free(&r);
}

static void test_animate_pages(void **state)
{
    (void)state;
    cli_result r =
        cli("animate plane --method rk4 --compare euler --output '%s/plane.html'", cli_tmpdir);
    CHECK(r.status == 0, "animate plane exit %d: %s", r.status, r.err);
    cli_free(&r);
    char *html = file_in_tmp("plane.html");
    check_self_contained(html, "plane");
    CHECK(strstr(html, "\"label\":\"rk4, h = 0.01 s\"") &&
              strstr(html, "\"label\":\"euler, h = 0.01 s\""),
          "the two runs are not in the page");
    CHECK(strstr(html, "\"length_plane\":2") && strstr(html, "\"wingspan\":4") &&
              strstr(html, "\"height_fin\":0.5"),
          "the plane's geometry is not in the page");
    free(html);
    r = cli("animate cart --set length_cart=3 --output '%s/cart.html'", cli_tmpdir);
    CHECK(r.status == 0, "animate cart exit %d: %s", r.status, r.err);
    cli_free(&r);
    html = file_in_tmp("cart.html");
    check_self_contained(html, "cart");
    CHECK(strstr(html, "\"length_cart\":3") != NULL, "--set is not in the page");
    /* --set chooses another run: the cart's forces are then its constant parameters, not
     * the homework's table; the page says so and how to get the homework's run */
    CHECK(strstr(html, "\"shows\":\"Shown: a run with the inputs held constant") &&
              strstr(html, "Fx = -50 N, Fy = ") &&
              strstr(html, "dynkit animate cart without run options plays the homework's run"),
          "the cart's page does not say what it shows");
    free(html);
    /* without run options: the homework's run (problem 4), whose final sX is the report's
     * 4c answer, beside the prescribed path, which ends at -v0 te = -99.8 m */
    r = cli("animate cart --output '%s/cart-default.html'", cli_tmpdir);
    CHECK(r.status == 0, "animate cart exit %d: %s", r.status, r.err);
    cli_free(&r);
    html = file_in_tmp("cart-default.html");
    CHECK(strstr(html, "\"shows\":\"Shown: the homework's run (problem 4)") != NULL,
          "the cart's default page does not say it is the homework's run");
    r = cli("report --json");
    const char *key = r.status == 0 ? strstr(r.out, "\"cart.forward_sX_m\":") : NULL;
    CHECK(key != NULL, "report --json has no cart.forward_sX_m");
    const double report_sX = strtod(key + strlen("\"cart.forward_sX_m\":"), NULL);
    cli_free(&r);
    const double fw_sX = last_series_value(html, "forward run (4c): heun, h = 0.01 s, forces held", 1);
    const double pr_sX = last_series_value(html, "prescribed path (4a)", 1);
    CHECK(fabs(fw_sX - report_sX) <= 1e-5 * fabs(report_sX),
          "the page's forward run ends at sX = %.9g m, the report's 4c at %.9g m", fw_sX,
          report_sX);
    CHECK(fabs(pr_sX - (-20.0 * 4.99)) <= 1e-9,
          "the page's prescribed path ends at sX = %.17g m, not -v0 te = -99.8 m", pr_sX);
    free(html);
    /* the homework's run that the page names: nothing to explain */
    r = cli_in_tmpdir("inverse cart -o forces.csv --quiet");
    CHECK(r.status == 0, "inverse cart: %s", r.err);
    cli_free(&r);
    r = cli_in_tmpdir("animate cart --forces forces.csv --method heun --init dsX=-20 "
                      "--init dsY=4.934802200544679 --init omega=4.934802200544679 "
                      "--output cart-hw.html");
    CHECK(r.status == 0, "animate cart --forces: %d %s", r.status, r.err);
    cli_free(&r);
    html = file_in_tmp("cart-hw.html");
    CHECK(!strstr(html, "\"shows\":"), "a run with --forces needs no explanation");
    free(html);
    r = cli("animate vanderpol -o -");
    CHECK(r.status == 0 && strncmp(r.out, "<!DOCTYPE html>", 15) == 0,
          "--output - writes the page to stdout");
    cli_free(&r);
    /* without --output: MODEL.html in the current directory, then MODEL-2.html, named */
    size_t default_len = 0;
    for (int k = 1; k <= 2; k++) {
        r = cli_in_tmpdir("animate vanderpol");
        const char *name = k == 1 ? "vanderpol.html" : "vanderpol-2.html";
        CHECK(r.status == 0 && r.out_len == 0 && strstr(r.err, name),
              "animate without --output, run %d: exit %d, %zu bytes on stdout, stderr: %s", k,
              r.status, r.out_len, r.err);
        cli_free(&r);
        html = file_in_tmp(name);
        CHECK(strncmp(html, "<!DOCTYPE html>", 15) == 0, "%s is not the page", name);
        default_len = strlen(html);
        free(html);
    }
    /* 100001 samples thinned to the page's budget: the page grows by tens of kB over the
     * default run's (the same scripts, 1501 samples), not by the megabytes of every sample */
    r = cli("animate vanderpol --step 0.001 --tspan 0:100 --output '%s/x.html'", cli_tmpdir);
    CHECK(r.status == 0, "long run");
    cli_free(&r);
    html = file_in_tmp("x.html");
    CHECK(strlen(html) < default_len + 50000,
          "a long run is not thinned: %zu bytes (default run: %zu)", strlen(html), default_len);
    CHECK(strstr(html, "\"samples\":100001") != NULL, "the page does not say how many samples");
    free(html);
}

/* Morris-Lecar (Rinzel and Ermentrout's parameters, i = 100 uA/cm^2: a limit cycle of v
 * between about -60 and 35 mV while w stays within 0 and 0.5) in milliseconds: its time unit
 * (#: t [ms]) is in info, the page, the plot's axis and the labels of runs; the phase plane of
 * mV against a unitless w has no equal scales (they would flatten the cycle into a line) but
 * XPPAUT's window @ xlo, xhi, ylo, yhi; a unitless quantity is labelled without "[]". */
/* --live: the page of plot needs --output FILE.html and refuses sections; without the
 * WebAssembly library (DYNKIT_WASM_DIR naming an empty place) the page is the static one, the
 * status 0 and the warning names the packages (tests/browser/live.mjs runs the live pages). */
static void test_live_options(void **state)
{
    (void)state;
    cli_result r = cli("plot vanderpol --y y2 --live");
    CHECK(r.status == 2 && strstr(r.err, "--output FILE.html"), "plot --live without --output: %d %s",
          r.status, r.err);
    cli_free(&r);
    r = cli("plot vanderpol --y y2 --live --output '%s/p.svg'", cli_tmpdir);
    CHECK(r.status == 2 && strstr(r.err, ".html"), "plot --live to .svg: %d %s", r.status, r.err);
    cli_free(&r);
    r = cli("plot vanderpol --y y2 --section t=1 --live --output '%s/p.html'", cli_tmpdir);
    CHECK(r.status == 2 && strstr(r.err, "--live"), "plot --live --section: %d %s", r.status, r.err);
    cli_free(&r);
    setenv("DYNKIT_WASM_DIR", "/nonexistent-dynkit-wasm", 1);
    r = cli("plot vanderpol --x y1 --y y2 --live --output '%s/p.html'", cli_tmpdir);
    unsetenv("DYNKIT_WASM_DIR");
    CHECK(r.status == 0 && strstr(r.err, "not live") && strstr(r.err, "wasi-libc"),
          "plot --live without the library: %d %s", r.status, r.err);
    cli_free(&r);
    char *html = file_in_tmp("p.html");
    CHECK(strstr(html, "\"plot\":{\"x\":\"y1\",\"y\":[\"y2\"]}") && !strstr(html, "\"live\":{") &&
              !strstr(html, "'wasm-unsafe-eval'") && !strstr(html, "DK.startLive ="),
          "the static page of plot --live");
    free(html);
}

static void test_time_unit_and_phase_window(void **state)
{
    (void)state;
    FILE *f = fopen(cli_path("ml.ode"), "w");
    assert_non_null(f);
    fputs("# Morris-Lecar\n#: t [ms]\n#: v [mV] membrane potential\n"
          "#: w [] fraction of open K channels\n"
          "par i=100,phi=.04,v1=-1.2,v2=18,v3=2,v4=30\n"
          "par gca=4.4,gk=8,gl=2,vk=-84,vl=-60,vca=120,c=20\n"
          "minf(v)=.5*(1+tanh((v-v1)/v2))\nwinf(v)=.5*(1+tanh((v-v3)/v4))\n"
          "tauw(v)=1/cosh((v-v3)/(2*v4))\n"
          "v'=(i-gca*minf(v)*(v-vca)-gk*w*(v-vk)-gl*(v-vl))/c\n"
          "w'=phi*(winf(v)-w)/tauw(v)\ninit v=-60,w=0.01\n"
          "@ total=400, dt=0.5, xp=v, yp=w, xlo=-75, xhi=45, ylo=0, yhi=0.6\ndone\n",
          f);
    fclose(f);
    cli_result r = cli_in_tmpdir("info ml.ode");
    CHECK(r.status == 0 && strstr(r.out, "--tspan 0:400 (times in ms)"), "%s %s", r.out, r.err);
    cli_free(&r);
    r = cli_in_tmpdir("animate ml.ode --method rk4 --step 0.05 --output ml.html");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *html = file_in_tmp("ml.html");
    CHECK(strstr(html, "\"time_unit\":\"ms\"") &&
              strstr(html, "\"phase_window\":[[-75,45],[0,0.6]]") &&
              strstr(html, "\"label\":\"rk4, h = 0.05 ms\""),
          "the page has no time unit or window");
    free(html);
    r = cli_in_tmpdir("plot ml.ode --y w --output ml.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    char *svg = file_in_tmp("ml.svg");
    CHECK(strstr(svg, ">t [ms]<") && !strstr(svg, "[]") && !strstr(svg, "clipPath"),
          "axis labels of ml.svg");
    free(svg);
    /* plot's phase plane xp, yp in the same window: w's axis reaches 0.6 (the cycle's w
     * stays below 0.5), the lines clipped to it */
    r = cli_in_tmpdir("plot ml.ode --x v --y w --output mlw.svg");
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    svg = file_in_tmp("mlw.svg");
    CHECK(strstr(svg, ">0.6<") && strstr(svg, "clip-path=\"url(#window0)\""),
          "plot's phase plane is not in the window @ ylo=0, yhi=0.6");
    free(svg);
    /* unitless states share a panel only when their ranges are within a factor of 10:
     * Morris-Lecar's v (-60 .. 35) and w (0 .. 0.5) without units get one each, Lorenz's x
     * and y (both about -20 .. 20) one together */
    f = fopen(cli_path("ml2.ode"), "w");
    assert_non_null(f);
    fputs("v'=(100-4.4*.5*(1+tanh((v+1.2)/18))*(v-120)-8*w*(v+84)-2*(v+60))/20\n"
          "w'=.04*(.5*(1+tanh((v-2)/30))-w)*cosh((v-2)/60)\ninit v=-60,w=0.01\n"
          "@ total=400\ndone\n",
          f);
    fclose(f);
    static const struct {
        const char *args;
        int panels;
    } plots[] = {{"ml2.ode --y v,w", 2},
                 {DYNKIT_SOURCE_DIR "/examples/models/lorenz.ode --y x,y", 1}};
    for (size_t i = 0; i < sizeof plots / sizeof plots[0]; i++) {
        r = cli_in_tmpdir("plot %s --output p.svg", plots[i].args);
        CHECK(r.status == 0, "%s", r.err);
        cli_free(&r);
        svg = file_in_tmp("p.svg");
        int frames = 0;
        for (const char *q = svg; (q = strstr(q, "<rect class=\"frame\"")) != NULL; q++)
            frames++;
        CHECK(frames == plots[i].panels, "plot %s: %d panels", plots[i].args, frames);
        free(svg);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plot_svg_has_axes_labels_units_and_every_sample),
        cmocka_unit_test(test_plot_several_names_units_and_compare),
        cmocka_unit_test(test_plot_long_run_is_thinned),
        cmocka_unit_test(test_plot_bad_names_exit_2),
        cmocka_unit_test(test_compare_is_validated),
        cmocka_unit_test(test_report_html_is_self_contained),
        cmocka_unit_test(test_animate_pages),
        cmocka_unit_test(test_time_unit_and_phase_window),
        cmocka_unit_test(test_live_options),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
