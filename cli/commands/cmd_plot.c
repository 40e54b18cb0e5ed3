/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit plot MODEL: a run (and --compare runs) as a standalone SVG line plot of chosen
 * states or outputs against t or another state. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/out_file.h"
#include "pages/pages.h"

#define MAX_Y 8

static void plot_help(void)
{
    puts("Usage: dynkit plot MODEL [run options] --y NAME[,NAME...] [--x NAME]\n"
         "       dynkit plot MODEL [run options] --phase-plane [--x NAME --y NAME] ...\n"
         "                   [--compare METHOD[:STEP]]... [--title TEXT] [--output FILE.svg]\n"
         "\n"
         "Run MODEL and write a line plot as a standalone SVG file (standard output without\n"
         "--output): axes with ticks, labels with units, a legend.\n"
         "\n"
         "  --y NAMES            what to plot: states or extra outputs of the model, comma-\n"
         "                       separated (see 'dynkit info MODEL'); one panel per unit,\n"
         "                       and unitless ones share a panel when their ranges are\n"
         "                       within a factor of 10\n"
         "  --x NAME             the abscissa: t (default), a state or an output\n"
         "  --compare M[:H]      overlay a run with method M (and step H; default the run's\n"
         "                       step), repeatable, e.g. --compare euler --compare rk4:0.001\n"
         "  --title TEXT         the title (default: the model and the runs)\n"
         "  -o, --output FILE    the SVG file (default: standard output)\n"
         "  --live               a live page (--output FILE.html) instead of the SVG: the\n"
         "                       --y columns against --x, rerun in the page as the sliders\n"
         "                       of the parameters and initial values move (as animate\n"
         "                       --live; static, with a warning, without the WebAssembly\n"
         "                       library)\n"
         "A long run is thinned to at most 2000 samples per line (first and last kept).\n"
         "\n"
         "Examples:\n"
         "  dynkit plot vanderpol --y y1,y2 --output vdp.svg\n"
         "  dynkit plot vanderpol --x y1 --y y2 --compare euler --compare heun --output phase.svg\n"
         "  dynkit plot pendulum --tspan 0:10 --step 0.01 --method rk4 --y energy --output e.svg\n"
         "  dynkit plot vanderpol --x y1 --y y2 --live --output vdp-live.html\n"
         "\n"
         "A Poincare section (--section SPEC, or a model file's @ poimap) draws its crossings\n"
         "as dots; --return-map draws one --y NAME's crossings NAME_n against NAME_n+1 with\n"
         "the diagonal (Lorenz's map of the successive maxima of z):\n"
         "  dynkit plot examples/models/duffing.ode --section t=2pi/1.2 --tspan 0:1000 --x x --y v --output strobe.svg\n"
         "  dynkit plot examples/models/lorenz.ode --section max:z --tspan 0:100 --y z --return-map --output lorenz-map.svg\n"
         "\n"
         "The phase plane of two states (the others held at the initial state):\n"
         "  dynkit plot MODEL --phase-plane [--x NAME --y NAME] [--start NAME=V,NAME=V]...\n"
         "                   [--grid N] [--arrows N] [--output FILE.svg | --html FILE]\n"
         "draws the nullclines (NAME' = 0, by marching squares on N x N cells, default 100),\n"
         "the direction field (N x N arrows of one length, default 20), the equilibria by\n"
         "type (saddle, stable/unstable node or focus, centre) and trajectories of the run's\n"
         "method and span: from the initial state and from each --start (default: a 3 x 3\n"
         "grid at 1/6, 1/2, 5/6 of the window). The plane: --x and --y, else the model's\n"
         "xp, yp, else its two states; the window: the file's @ xlo, xhi, ylo, yhi, else the\n"
         "run's extent widened by a fifth. --html FILE (or --output FILE.html) writes a page\n"
         "with the picture and the table of the equilibria and their eigenvalues. A map, a\n"
         "delay or a Volterra model is refused; noise is taken as 0 and Markov states held\n"
         "in the field, with a note (the trajectories carry them).\n"
         "  dynkit plot examples/models/vanderpol.ode --phase-plane --output vdp-phase.svg\n"
         "  dynkit plot examples/models/lorenz.ode --phase-plane --x x --y y --html lorenz.html\n"
         "\n"
         "A sweep's table (dynkit sweep ... --output TABLE.csv or TABLE.json) in place of MODEL:\n"
         "  dynkit plot TABLE.json [--y NAME[,NAME...]] [--x NAME] [--title TEXT] [--output "
         "FILE.svg] [--html FILE]\n"
         "with one varied name, lines of the reduced columns (--y, default all; max_height or\n"
         "max:height) against it; with two, a heat map of one reduced column (--y, default the\n"
         "first) over their grid with a colour bar (failed runs and nan in grey), or with --x\n"
         "NAME lines against it, one per value of the other. The axes carry the units of a\n"
         "JSON table (a CSV table has names only). --html FILE (or --output FILE.html) writes\n"
         "the same picture into a self-contained page.\n");
    cli_view_options_help(stdout);
}

/* Split the comma-separated names of --y/--x into columns of the model's runs. */
static int parse_names(const char *option, const char *text, const dyn_model *m, int *cols, int max,
                       int *n)
{
    char buf[512], names[1024];
    if (strlen(text) >= sizeof buf)
        return cli_usage_error("plot", "--%s: the list is too long", option);
    strcpy(buf, text);
    *n = 0;
    for (char *save = buf, *name; (name = save) != NULL;) {
        char *comma = strchr(save, ',');
        if (comma)
            *comma = '\0';
        save = comma ? comma + 1 : NULL;
        int c = cli_series_column(m, name);
        if (c < 0 || *n >= max)
            return c < 0 ? cli_usage_error("plot",
                                           "--%s: model %s has no state or output '%s' "
                                           "(accepted: %s)",
                                           option, m->name, name,
                                           cli_series_column_names(m, names, sizeof names))
                         : cli_usage_error("plot", "--%s: at most %d names", option, max);
        cols[(*n)++] = c;
    }
    return CLI_OK;
}

/* "phi, dphi [rad]" when the units agree, else "phi [rad], dphi [rad/s]". */
static void axis_label(const dyn_model *m, const int *cols, int n, char *buf, size_t size)
{
    size_t used = 0;
    int same = 1;
    buf[0] = '\0';
    for (int i = 1; i < n; i++)
        same &= strcmp(cli_series_column_unit(m, cols[i]), cli_series_column_unit(m, cols[0])) == 0;
    for (int i = 0; i < n && used < size; i++) {
        const int unit_here = !same || i == n - 1;
        used += (size_t)snprintf(buf + used, size - used, "%s%s", i ? ", " : "",
                                 cli_series_column_name(m, cols[i]));
        const char *unit = cli_series_column_unit(m, cols[i]);
        if (unit_here && unit && *unit && used < size) /* no "[]" for a unitless quantity */
            used += (size_t)snprintf(buf + used, size - used, " [%s]", unit);
    }
}

/* The range max - min of column c over every run's samples (0 when constant). */
static double column_span(const cli_view *v, int c)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < v->n_series; k++) {
        const cli_series *s = &v->series[k];
        for (long r = 0; r < s->rows; r++) {
            const double y = s->data[r * s->cols + c];
            if (isfinite(y)) {
                lo = fmin(lo, y);
                hi = fmax(hi, y);
            }
        }
    }
    return hi >= lo ? hi - lo : 0.0;
}

int cli_cmd_plot(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            plot_help();
            return CLI_OK;
        }
    for (int i = 1; i < argc; i++)
        if (cli_flag(argv[i], "phase-plane"))
            return cli_plot_phase_plane(argc, argv);
    /* a sweep's table (dynkit sweep --output FILE.csv) rather than a model */
    const char *dot = argc > 0 ? strrchr(argv[0], '.') : NULL;
    if (dot && (strcmp(dot, ".csv") == 0 || strcmp(dot, ".json") == 0))
        return cli_plot_sweep_table(argc, argv);
    static const char *const extra[] = {"y", "x", "title", NULL};
    const char *values[3];
    cli_view v;
    /* --return-map: NAME_n against NAME_n+1 of a section's crossings */
    int return_map = 0, n_args = 0;
    char **args = calloc((size_t)argc + 1, sizeof *args);
    if (!args) {
        fprintf(stderr, "dynkit: error: out of memory\n");
        return CLI_FAILED;
    }
    int live = 0;
    for (int i = 0; i < argc; i++)
        if (i > 0 && cli_flag(argv[i], "return-map"))
            return_map = 1;
        else if (i > 0 && cli_flag(argv[i], "live"))
            live = 1;
        else
            args[n_args++] = argv[i];
    int rc = cli_view_parse("plot", n_args, args, extra, values, &v);
    free(args);
    const int section = rc == CLI_OK && v.run.section.kind != DYN_POINCARE_NONE;
    if (rc == CLI_OK && return_map && (!section || values[1]))
        rc = cli_usage_error("plot", "--return-map draws a section's crossings NAME_n against "
                                     "NAME_n+1: give --section SPEC (or a file with @ poimap) "
                                     "and one --y NAME, without --x");
    const dyn_model *m = v.run.model;
    int ycols[MAX_Y], n_y = 0, xcol = 0, n_x = 1;
    char names[1024];
    if (rc == CLI_OK && !values[0])
        rc = cli_usage_error("plot", "missing --y NAME[,NAME...] (what to plot; accepted: %s)",
                             cli_series_column_names(m, names, sizeof names));
    if (rc == CLI_OK)
        rc = parse_names("y", values[0], m, ycols, MAX_Y, &n_y);
    if (rc == CLI_OK && return_map && n_y != 1)
        rc = cli_usage_error("plot", "--return-map takes one --y NAME, not %d", n_y);
    if (rc == CLI_OK && values[1])
        rc = parse_names("x", values[1], m, &xcol, 1, &n_x);
    if (rc == CLI_OK && live && (section || return_map))
        rc = cli_usage_error("plot", "--live draws the run's samples: not with --section or "
                                     "--return-map");
    static const char *const svg[] = {".svg", NULL}, *const html[] = {".html", ".htm", NULL};
    if (rc == CLI_OK && live && !v.run.output_path)
        rc = cli_usage_error("plot", "--live writes a page: give --output FILE.html (or "
                                     "--output - for standard output)");
    if (rc == CLI_OK)
        rc = cli_out_check_extension("plot", "--output", v.run.output_path, live ? html : svg);
    int run_rc = rc == CLI_OK ? cli_view_record(&v) : rc;
    if (rc == CLI_OK && (run_rc == CLI_USAGE || v.n_series == 0))
        rc = run_rc;
    if (live && rc == CLI_OK) {
        rc = cli_live_plot_page("plot", argv[0], &v, xcol, ycols, n_y, run_rc);
        cli_view_free(&v);
        return rc;
    }
    /* written to a temporary file renamed over --output at the end (out_file.h) */
    cli_out outf = {0};
    if (rc == CLI_OK)
        rc = cli_out_open(&outf, "--output", v.run.output_path);
    FILE *out = outf.f;
    if (rc == CLI_OK) {
        /* one panel per unit of the --y columns (energy in J and height in m are not
         * squashed onto one axis), in the order the units first appear; unitless columns
         * share a panel only when their ranges are within a factor of 10 */
        static cli_svg_plot panels[MAX_Y];
        static char ylabels[MAX_Y][512];
        static char labels[CLI_SVG_MAX_LINES][160];
        const cli_svg_plot *order[MAX_Y];
        char title[256], xlabel[256];
        int n_panels = 0, n_labels = 0;
        snprintf(title, sizeof title, "%s: %s", m->name, v.series[0].label);
        for (int k = 1; k < v.n_series; k++)
            snprintf(title + strlen(title), sizeof title - strlen(title), " | %s",
                     v.series[k].label);
        axis_label(m, &xcol, 1, xlabel, sizeof xlabel);
        if (section) {
            const dyn_poincare *sec = &v.run.section;
            snprintf(title + strlen(title), sizeof title - strlen(title), "; %s %s%s%s",
                     sec->kind == DYN_POINCARE_EXTREMUM
                         ? (sec->sign > 0 ? "maxima of" : sec->sign < 0 ? "minima of"
                                                                        : "extrema of")
                         : sec->kind == DYN_POINCARE_PERIOD ? "periods at" : "section",
                     sec->var, sec->kind == DYN_POINCARE_EXTREMUM ? "" : " = ",
                     sec->kind == DYN_POINCARE_EXTREMUM ? "" : CLI_NUM(sec->plane));
        }
        if (return_map) {
            /* NAME_n against NAME_n+1: the same column, one row apart; and the diagonal */
            static cli_svg_plot rm;
            static char rx[256], ry[256];
            static double diag[4];
            memset(&rm, 0, sizeof rm);
            const char *name = cli_series_column_name(m, ycols[0]);
            snprintf(rx, sizeof rx, "%s_n", name);
            snprintf(ry, sizeof ry, "%s_n+1", name);
            rm.title = values[2] ? values[2] : title;
            rm.xlabel = rx;
            rm.ylabel = ry;
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < v.n_series; k++) {
                const cli_series *s = &v.series[k];
                for (long r = 0; r < s->rows; r++) {
                    const double val = s->data[r * s->cols + ycols[0]];
                    if (isfinite(val)) {
                        lo = fmin(lo, val);
                        hi = fmax(hi, val);
                    }
                }
                if (s->rows > 1 && rm.n_lines < CLI_SVG_MAX_LINES - 1)
                    rm.lines[rm.n_lines++] =
                        (cli_svg_line){v.n_series == 1 ? "crossings" : s->label,
                                       s->data + ycols[0], s->data + s->cols + ycols[0],
                                       s->rows - 1, s->cols, 1, NULL, NULL};
            }
            diag[0] = diag[1] = lo;
            diag[2] = diag[3] = hi;
            if (hi > lo)
                rm.lines[rm.n_lines++] = (cli_svg_line){"diagonal", diag, diag + 1, 2, 2, 0,
                                                        NULL, NULL};
            rc = cli_svg_write(out, &rm);
            int close_rc = cli_out_close(&outf, rc == CLI_OK);
            if (rc == CLI_OK)
                rc = close_rc != CLI_OK ? close_rc : run_rc;
            cli_view_free(&v);
            return rc;
        }
        int done[MAX_Y] = {0};
        for (int first = 0; first < n_y; first++) {
            if (done[first])
                continue;
            const char *unit = cli_series_column_unit(m, ycols[first]);
            const double span = column_span(&v, ycols[first]);
            int cols[MAX_Y], n_cols = 0;
            for (int i = first; i < n_y; i++)
                if (!done[i] && strcmp(cli_series_column_unit(m, ycols[i]), unit) == 0 &&
                    cli_svg_share_axis(unit, span, column_span(&v, ycols[i]))) {
                    cols[n_cols++] = ycols[i];
                    done[i] = 1;
                }
            cli_svg_plot *p = &panels[n_panels];
            memset(p, 0, sizeof *p);
            axis_label(m, cols, n_cols, ylabels[n_panels], sizeof ylabels[0]);
            p->title = n_panels > 0 ? "" : values[2] ? values[2] : title;
            p->xlabel = xlabel;
            p->ylabel = ylabels[n_panels];
            for (int k = 0; k < v.n_series; k++)
                for (int i = 0; i < n_cols && n_labels < CLI_SVG_MAX_LINES; i++) {
                    const cli_series *s = &v.series[k];
                    char *label = labels[n_labels++];
                    if (v.n_series == 1)
                        snprintf(label, sizeof labels[0], "%s", cli_series_column_name(m, cols[i]));
                    else if (n_y == 1)
                        snprintf(label, sizeof labels[0], "%s", s->label);
                    else
                        snprintf(label, sizeof labels[0], "%s (%s)",
                                 cli_series_column_name(m, cols[i]), s->label);
                    p->lines[p->n_lines++] =
                        (cli_svg_line){label, s->data + xcol, s->data + cols[i], s->rows, s->cols,
                                       dyn_method_is_map(s->method) || section, NULL, NULL};
                }
            /* the model's phase plane (xp, yp) in XPPAUT's window @ xlo, xhi, ylo, yhi */
            if (n_y == 1 && m->phase_x && m->phase_y && xcol == cli_series_column(m, m->phase_x) &&
                cols[0] == cli_series_column(m, m->phase_y)) {
                memcpy(p->xwin, m->phase_window, sizeof p->xwin);
                memcpy(p->ywin, m->phase_window + 2, sizeof p->ywin);
            }
            order[n_panels] = p;
            n_panels++;
        }
        rc = cli_svg_write_panels(out, order, n_panels);
        int close_rc = cli_out_close(&outf, rc == CLI_OK);
        if (rc == CLI_OK)
            rc = close_rc != CLI_OK ? close_rc : run_rc;
    }
    cli_view_free(&v);
    return rc;
}
