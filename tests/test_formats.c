/* SPDX-License-Identifier: BSD-3-Clause */
/* Data files of `dynkit run --output FILE`, `dynkit inverse --output FILE` and `dynkit sweep
 * --output FILE` (docs/data-files.md, docs/sweeps.md): each format is loaded by the reader
 * people use for it and compared with the CSV of the same run or sweep, bit for bit
 * (float64), names (the CSV header's in every format) and units included:
 * - .json with Python's json, .npy and .npz with numpy.load, .mat with scipy.io.loadmat
 *   (tests/formats/load_table.py, run by /usr/bin/python3) and with Octave's load
 *   (tests/formats/load_table.m, run by octave-cli); each loader prints the values exactly
 *   (float.hex, num2hex) with the names, units and settings the file carries;
 * - a test is skipped, with the reason, only when its loader is not installed
 *   (scripts/install-deps.sh installs python3-numpy, python3-scipy and octave);
 * - CSV's --header units and none; an unknown extension refused (exit 2) naming the accepted
 *   ones, and no file made; --header refused for the binary formats; --output - is stdout;
 *   a failed run keeps its samples in every format. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "test_cli_run.h"
#include "test_util.h"

#define PYTHON "/usr/bin/python3"

/* The runs compared: an adaptive run with outputs (16 columns), a fixed-step one (the
 * streamed .npy), a stiff one sampled at every step (tiny and huge numbers), and a run that
 * fails (its samples up to the failure). */
static const char *const runs[] = {
    "run plane --method dp45 --tspan 0:0.5 --outputs",
    "run pendulum --method rk4 --step 0.01 --tspan 0:2 --outputs",
    "run robertson --tspan 0:1e5",
    "run vanderpol --set mu=1e6 --method euler --step 0.1 --tspan 0:15",
};

/* A table of doubles parsed from CSV (strtod: correctly rounded, so %.17g reads back). */
typedef struct table {
    long rows;
    int cols;
    double v[40000];
    char header[1024]; /* the names, separated by spaces */
} table;

static table csv;

static void parse_csv(const char *text, table *t)
{
    memset(t, 0, sizeof *t);
    const char *nl = strchr(text, '\n');
    assert_non_null(nl);
    size_t hl = (size_t)(nl - text) < sizeof t->header ? (size_t)(nl - text) : 0;
    memcpy(t->header, text, hl);
    for (size_t i = 0; i < hl; i++)
        if (t->header[i] == ',')
            t->header[i] = ' ';
    t->cols = 1;
    for (size_t i = 0; i < hl; i++)
        t->cols += text[i] == ',';
    const char *p = nl + 1;
    long n = 0;
    while (*p) {
        for (int j = 0; j < t->cols; j++) {
            char *end;
            CHECK(n < (long)(sizeof t->v / sizeof t->v[0]), "CSV too long for the test");
            t->v[n++] = strtod(p, &end);
            CHECK(end != p, "CSV: not a number at '%.20s'", p);
            p = end + (*end == ',' || *end == '\n');
        }
        t->rows++;
    }
}

/* One value printed by a loader: float.hex() ("0x1.8p+1", "-0x0.0p+0", "nan", "inf") or
 * the IEEE bits as 16 hex digits (Octave's num2hex). */
static double loaded_value(const char *tok, size_t len)
{
    char buf[64];
    CHECK(len < sizeof buf, "token too long");
    memcpy(buf, tok, len);
    buf[len] = '\0';
    if (strchr(buf, 'x') || strchr(buf, 'n') || strchr(buf, 'i'))
        return strtod(buf, NULL);
    uint64_t bits = strtoull(buf, NULL, 16);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

/* The loader's output against the CSV: shape, names (when printed) and every value. */
static void compare(const char *what, const char *out, const table *t)
{
    long rows = -1, cols = -1, row = 0;
    const char *line = out;
    while (line && *line) {
        const char *next = strchr(line, '\n');
        size_t len = next ? (size_t)(next - line) : strlen(line);
        if (strncmp(line, "shape ", 6) == 0) {
            sscanf(line + 6, "%ld %ld", &rows, &cols);
            CHECK(rows == t->rows && cols == t->cols, "%s: shape %ld x %ld, the CSV has %ld x %d",
                  what, rows, cols, t->rows, t->cols);
        } else if (strncmp(line, "names ", 6) == 0) {
            CHECK(len - 6 == strlen(t->header) && strncmp(line + 6, t->header, len - 6) == 0,
                  "%s: names '%.*s', the CSV header '%s'", what, (int)(len - 6), line + 6,
                  t->header);
        } else if (strncmp(line, "row ", 4) == 0) {
            const char *p = line + 4;
            for (int j = 0; j < t->cols; j++) {
                size_t tl = strcspn(p, " \n");
                CHECK(tl > 0, "%s: row %ld has fewer than %d values", what, row, t->cols);
                double v = loaded_value(p, tl), want = t->v[row * t->cols + j];
                CHECK(same_bits(v, want), "%s: row %ld column %d: %.17g, the CSV has %.17g",
                      what, row, j, v, want);
                p += tl + (p[tl] == ' ');
            }
            row++;
        }
        line = next ? next + 1 : NULL;
    }
    CHECK(rows >= 0 && row == t->rows, "%s: %ld rows printed, the CSV has %ld; output:\n%.400s",
          what, row, t->rows, out);
}

static int have(const char *cmd)
{
    char full[512];
    snprintf(full, sizeof full, "%s >/dev/null 2>&1 </dev/null", cmd);
    return system(full) == 0;
}

/* The CSV of run k into csv (written with -o FILE.csv). */
static void run_csv(int k)
{
    cli_result r = cli_in_tmpdir("%s -o x.csv", runs[k]);
    CHECK(r.status == 0 || (k == 3 && r.status == 1), "%s: exit %d: %s", runs[k], r.status,
          r.err);
    cli_free(&r);
    char *text = cli_read_file(cli_path("x.csv"), NULL);
    parse_csv(text, &csv);
    free(text);
    CHECK(csv.rows > 1, "%s: %ld rows", runs[k], csv.rows);
}

/* Every run in format ext, loaded by loader (a command taking the format and the file). */
static void check_format(const char *ext, const char *loader)
{
    for (int k = 0; k < (int)(sizeof runs / sizeof runs[0]); k++) {
        run_csv(k);
        cli_result r = cli_in_tmpdir("%s -o x.%s", runs[k], ext);
        CHECK(r.status == 0 || (k == 3 && r.status == 1), "%s -o x.%s: exit %d: %s", runs[k],
              ext, r.status, r.err);
        cli_free(&r);
        char cmd[1024], what[256];
        snprintf(cmd, sizeof cmd, "cd '%s' && %s x.%s 2>/dev/null", cli_tmpdir, loader, ext);
        int status;
        char *out = cli_capture(cmd, &status);
        snprintf(what, sizeof what, "%s -o x.%s, loaded by %s", runs[k], ext, loader);
        CHECK(status == 0, "%s: exit %d:\n%.600s", what, status, out);
        compare(what, out, &csv);
        if (k == 0 && strcmp(ext, "npy") != 0)
            CHECK(strstr(out, "method=dp45") && strstr(out, "step=0.01"),
                  "%s: the method and step are not in the file:\n%.300s", what, out);
        if (k == 0 && strcmp(ext, "npy") != 0)
            CHECK(strstr(out, "states=12"), "%s: the file does not say which columns are states",
                  what);
        free(out);
    }
}

/* The sweeps compared (docs/sweeps.md): a grid of two varied names with the pendulum's
 * reductions (max:height in m, an event count, an event time in s), and an adaptive Monte
 * Carlo table of van der Pol. Each format holds the CSV's columns under the CSV's names, with
 * their units. */
static const struct {
    const char *args, *units, *meta;
} sweeps[] = {
    {"sweep pendulum --method rk4 --step 0.01 --tspan 0:10 --vary l=1:10:4 --vary "
     "dphi=0.5:1.5:3 --reduce max:height,count:bottom,event:turn --quiet",
     "units 1 m rad/s m 1 s", "states=2 varied=2 reduced=3"},
    {"sweep vanderpol --method dp45 --tspan 0:10 --sample 'mu=uniform(0.5,2)' --sample "
     "'y1=normal(2,0.1)' --runs 40 --seed 7 --reduce final,argmax:y1,mean:y2 --quiet",
     "units 1 1 1 1 1/s s 1/s", "states=2 varied=2 reduced=4"},
};

/* Every sweep in format ext, loaded by loader, against its CSV. */
static void check_sweep_format(const char *ext, const char *loader)
{
    for (size_t k = 0; k < sizeof sweeps / sizeof sweeps[0]; k++) {
        cli_result r = cli_in_tmpdir("%s -o s.csv", sweeps[k].args);
        CHECK(r.status == 0, "%s -o s.csv: exit %d: %s", sweeps[k].args, r.status, r.err);
        cli_free(&r);
        char *text = cli_read_file(cli_path("s.csv"), NULL);
        parse_csv(text, &csv);
        free(text);
        CHECK(csv.rows > 1 && !strchr(csv.header, ':'), "%s: %ld rows, names %s",
              sweeps[k].args, csv.rows, csv.header);
        r = cli_in_tmpdir("%s -o s.%s", sweeps[k].args, ext);
        CHECK(r.status == 0, "%s -o s.%s: exit %d: %s", sweeps[k].args, ext, r.status, r.err);
        cli_free(&r);
        char cmd[1024], what[512];
        snprintf(cmd, sizeof cmd, "cd '%s' && %s s.%s 2>/dev/null", cli_tmpdir, loader, ext);
        int status;
        char *out = cli_capture(cmd, &status);
        snprintf(what, sizeof what, "%s -o s.%s, loaded by %s", sweeps[k].args, ext, loader);
        CHECK(status == 0, "%s: exit %d:\n%.600s", what, status, out);
        compare(what, out, &csv);
        if (strcmp(ext, "npy") != 0)
            CHECK(strstr(out, sweeps[k].units) && strstr(out, "method="),
                  "%s: not the units '%s' and the method:\n%.400s", what, sweeps[k].units, out);
        if (strcmp(ext, "json") == 0)
            CHECK(strstr(out, sweeps[k].meta), "%s: the counts are not '%s':\n%.400s", what,
                  sweeps[k].meta, out);
        free(out);
    }
}

static void python_loader(char *buf, size_t size, const char *module, const char *ext)
{
    char probe[128];
    snprintf(probe, sizeof probe, PYTHON " -c 'import %s'", module);
    if (!have(probe)) {
        print_message("SKIP: %s with %s needs " PYTHON " with %s (scripts/install-deps.sh "
                      "installs it)\n",
                      ext, module, module);
        skip();
    }
    snprintf(buf, size, PYTHON " '%s/tests/formats/load_table.py' %s", DYNKIT_SOURCE_DIR, ext);
}

static void test_json_python(void **state)
{
    (void)state;
    char loader[512];
    python_loader(loader, sizeof loader, "numpy", "json");
    check_format("json", loader);
    check_sweep_format("json", loader);
}

static void test_npy_numpy(void **state)
{
    (void)state;
    char loader[512];
    python_loader(loader, sizeof loader, "numpy", "npy");
    check_format("npy", loader);
    check_sweep_format("npy", loader);
}

static void test_npz_numpy(void **state)
{
    (void)state;
    char loader[512];
    python_loader(loader, sizeof loader, "numpy", "npz");
    check_format("npz", loader);
    check_sweep_format("npz", loader);
}

/* 1 if this dynkit writes .mat (built with matio). */
static int dynkit_writes_mat(void)
{
    cli_result r = cli_in_tmpdir("run pendulum -o probe.mat");
    int ok = r.status == 0;
    if (!ok)
        CHECK(r.status == 2 && strstr(r.err, "libmatio-dev"),
              "without matio, .mat must be refused saying how to get it: %s", r.err);
    cli_free(&r);
    unlink(cli_path("probe.mat"));
    return ok;
}

/* Units beyond ASCII (a model file's `[°]`, `[µm/s²]`) come back as the same characters
 * from the .mat file through loader. */
static void check_mat_units_beyond_ascii(const char *loader)
{
    CHECK(cli_write_file("units.ode", "#: x [\u00b0]\n#: y [\u00b5m/s\u00b2]\nx'=1\ny'=0\n"
                                      "init x=0, y=0\ndone\n") == 0,
          "cannot write units.ode");
    cli_result r = cli_in_tmpdir("run units.ode --method rk4 --step 0.5 --tspan 0:1 -o u.mat");
    CHECK(r.status == 0, "run units.ode -o u.mat: exit %d: %s", r.status, r.err);
    cli_free(&r);
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cd '%s' && %s u.mat 2>/dev/null", cli_tmpdir, loader);
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(status == 0 && strstr(out, "units s \u00b0 \u00b5m/s\u00b2\n"),
          "the units beyond ASCII do not come back from u.mat through %s:\n%.400s", loader, out);
    free(out);
    unlink(cli_path("u.mat"));
    unlink(cli_path("units.ode"));
}

static void test_mat_scipy(void **state)
{
    (void)state;
    if (!dynkit_writes_mat()) {
        print_message("SKIP: dynkit was built without matio (libmatio-dev)\n");
        skip();
    }
    char loader[512];
    python_loader(loader, sizeof loader, "scipy.io", "mat");
    check_format("mat", loader);
    check_sweep_format("mat", loader);
    check_mat_units_beyond_ascii(loader);
}

static void test_mat_octave(void **state)
{
    (void)state;
    if (!dynkit_writes_mat()) {
        print_message("SKIP: dynkit was built without matio (libmatio-dev)\n");
        skip();
    }
    if (!have("octave-cli --version")) {
        print_message("SKIP: .mat with Octave needs octave-cli (Debian's octave; "
                      "scripts/install-deps.sh installs it)\n");
        skip();
    }
    char loader[512];
    snprintf(loader, sizeof loader,
             "octave-cli --norc --quiet --no-window-system '%s/tests/formats/load_table.m'",
             DYNKIT_SOURCE_DIR);
    check_format("mat", loader);
    check_sweep_format("mat", loader);
    check_mat_units_beyond_ascii(loader);
}

/* A table that its file cannot hold: refused before the run when the row count is known
 * (300,000,001 rows of 3 columns; an .npz file without ZIP64 holds (2^32 - 1 - 2^20) / 24
 * rows), no file made; when it is not known (an adaptive run sampled at every step), the
 * run stops at the limit and its rows are written: under a 400,000 KiB address space the
 * table may use a quarter of it, 4,266,666 rows of 3 doubles. */
static void test_table_too_large(void **state)
{
    (void)state;
    cli_result r = cli_in_tmpdir("run vanderpol -m rk4 --step 1e-6 --tspan 0:300 -o big.npz");
    /* the limit is the file's (2^32 - 1 - 2^20) / 24 rows, or a quarter of the memory on a
     * machine of less than about 17 GB; the --every K offered is the smallest that fits:
     * the rows of 300,000,001 samples thinned to every K-th and the last */
    const char *at_most = strstr(r.err, "at most "), *every = strstr(r.err, "--every ");
    const long limit = at_most ? atol(at_most + 8) : 0, k = every ? atol(every + 8) : 0;
#define THINNED(K) ((300000000L) / (K) + 1 + (300000000L % (K) != 0))
    CHECK(r.status == 2 && strstr(r.err, "300000001 rows of 3 columns") && limit > 0 &&
              limit <= (long)floor((4294967295.0 - 1048576.0) / 24.0) && k >= 2 &&
              THINNED(k) <= limit && THINNED(k - 1) > limit,
          "a table too large for .npz: exit %d: %s", r.status, r.err);
#undef THINNED
    cli_free(&r);
    struct stat st;
    CHECK(stat(cli_path("big.npz"), &st) != 0, "a refused run made big.npz");
#if defined(__SANITIZE_ADDRESS__)
    print_message("SKIP: the run under a limit on the address space (AddressSanitizer needs "
                  "a large one)\n");
#else
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && ulimit -v 400000 && '%s' run vanderpol -m dp45 --tspan 0:400000 --quiet "
             "-o big.npz 2>err; echo \"exit $?\"; cat err",
             cli_tmpdir, DYNKIT_CLI);
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(strstr(out, "exit 1") && strstr(out, "4266666 rows of 3 columns fill a quarter of the "
                                                 "memory") &&
              strstr(out, "its rows are written"),
          "a run that fills the table: %s", out);
    free(out);
    char probe[128];
    snprintf(probe, sizeof probe, PYTHON " -c 'import numpy'");
    if (have(probe)) {
        snprintf(cmd, sizeof cmd,
                 "cd '%s' && " PYTHON " -c \"import numpy as np; d = np.load('big.npz'); "
                 "t = d['t']; print(len(t), bool((np.diff(t) > 0).all()), t[-1] < 400000, "
                 "d['y'].shape)\"",
                 cli_tmpdir);
        out = cli_capture(cmd, &status);
        CHECK(status == 0 && strstr(out, "4266666 True True (4266666, 2)"),
              "the rows written when the table filled: %s", out);
        free(out);
    }
#endif
    unlink(cli_path("big.npz"));
}

/* inverse cart's force table as .npz: t, forces, names t Fx Fy. */
static void test_inverse_npz(void **state)
{
    (void)state;
    char loader[512];
    python_loader(loader, sizeof loader, "numpy", "npz");
    cli_result r = cli_in_tmpdir("inverse cart --quiet -o x.csv");
    CHECK(r.status == 0, "inverse -o x.csv: %s", r.err);
    cli_free(&r);
    char *text = cli_read_file(cli_path("x.csv"), NULL);
    parse_csv(text, &csv);
    free(text);
    r = cli_in_tmpdir("inverse cart --quiet -o x.npz");
    CHECK(r.status == 0, "inverse -o x.npz: %s", r.err);
    cli_free(&r);
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cd '%s' && %s x.npz 2>&1", cli_tmpdir, loader);
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(status == 0, "loading the force table: %s", out);
    compare("inverse cart -o x.npz", out, &csv);
    free(out);
}

static void test_csv_header(void **state)
{
    (void)state;
    cli_result r = cli("run pendulum --tspan 0:0.2 --outputs --header units");
    CHECK(r.status == 0 && strncmp(r.out, "t [s],phi [rad],dphi [rad/s],energy [J],height [m]\n",
                                   51) == 0,
          "--header units: %.80s", r.out);
    cli_free(&r);
    r = cli("run pendulum --tspan 0:0.2 --header none");
    CHECK(r.status == 0 && strncmp(r.out, "0,0,", 4) == 0, "--header none: %.80s", r.out);
    cli_free(&r);
    r = cli("run pendulum --tspan 0:0.2 --header names -o -");
    CHECK(r.status == 0 && strncmp(r.out, "t,phi,dphi\n0,", 13) == 0,
          "--header names, -o -: %.80s", r.out);
    cli_free(&r);
    r = cli("run pendulum --header unit");
    CHECK(r.status == 2 && strstr(r.err, "names, units, none"), "--header unit: %s", r.err);
    cli_free(&r);
    r = cli_in_tmpdir("run pendulum --header units -o h.npz");
    CHECK(r.status == 2 && strstr(r.err, "--header applies to CSV"), "--header with npz: %s",
          r.err);
    cli_free(&r);
    struct stat st;
    CHECK(stat(cli_path("h.npz"), &st) != 0, "a refused run made h.npz");
}

static void test_unknown_extension(void **state)
{
    (void)state;
    static const char *const bad[] = {"x.txt", "x", "x.csv.bak", "dir.d/x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cli_result r = cli_in_tmpdir("run pendulum -o %s", bad[i]);
        CHECK(r.status == 2 && strstr(r.err, ".csv, .json, .mat, .npy, .npz"),
              "-o %s: exit %d: %s", bad[i], r.status, r.err);
        cli_free(&r);
        struct stat st;
        CHECK(stat(cli_path(bad[i]), &st) != 0, "a refused run made %s", bad[i]);
    }
    /* the events are CSV: another extension is refused too */
    cli_result r = cli_in_tmpdir("run pendulum -m dp45 --event turn --events-output ev.json");
    CHECK(r.status == 2 && strstr(r.err, "give FILE.csv"), "--events-output ev.json: %s", r.err);
    cli_free(&r);
    r = cli_in_tmpdir("inverse cart -o forces.dat");
    CHECK(r.status == 2 && strstr(r.err, ".npz"), "inverse -o forces.dat: %s", r.err);
    cli_free(&r);
    /* the pictures and pages: an SVG picture, an HTML page, nothing else (no SVG written
     * under a .png name) */
    static const struct {
        const char *args, *file, *accepted;
    } pictures[] = {
        {"plot pendulum --y phi -o x.png", "x.png", "plot writes FILE.svg"},
        {"plot pendulum --y phi -o x.html", "x.html", "plot writes FILE.svg"},
        {"animate pendulum -o x.svg", "x.svg", "animate writes FILE.html or FILE.htm"},
        {"animate pendulum -o x", "x", "animate writes FILE.html or FILE.htm"},
    };
    for (size_t i = 0; i < sizeof pictures / sizeof pictures[0]; i++) {
        cli_free(&r);
        r = cli_in_tmpdir("%s", pictures[i].args);
        CHECK(r.status == 2 && strstr(r.err, pictures[i].accepted), "%s: exit %d: %s",
              pictures[i].args, r.status, r.err);
        struct stat st;
        CHECK(stat(cli_path(pictures[i].file), &st) != 0, "%s made %s", pictures[i].args,
              pictures[i].file);
    }
    cli_free(&r);
    /* the extension is matched without regard to case */
    r = cli_in_tmpdir("run pendulum --tspan 0:0.2 -o UPPER.JSON");
    CHECK(r.status == 0, "-o UPPER.JSON: %s", r.err);
    cli_free(&r);
    char *text = cli_read_file(cli_path("UPPER.JSON"), NULL);
    CHECK(text[0] == '{', "UPPER.JSON is not JSON: %.40s", text);
    free(text);
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"x.csv", "x.json", "x.npy", "x.npz", "x.mat",
                                        "s.csv", "s.json", "s.npy", "s.npz", "s.mat",
                                        "UPPER.JSON", NULL};
    return cli_teardown_files(files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_csv_header),
        cmocka_unit_test(test_unknown_extension),
        cmocka_unit_test(test_json_python),
        cmocka_unit_test(test_npy_numpy),
        cmocka_unit_test(test_npz_numpy),
        cmocka_unit_test(test_mat_scipy),
        cmocka_unit_test(test_mat_octave),
        cmocka_unit_test(test_inverse_npz),
        cmocka_unit_test(test_table_too_large),
    };
    return cmocka_run_group_tests(tests, cli_setup, teardown);
}
