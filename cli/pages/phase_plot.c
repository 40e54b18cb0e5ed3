/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit plot MODEL --phase-plane: the phase plane of two states (the others held at the
 * initial state) as XPPAUT draws it (its manual, "Nullclines", "Direction fields",
 * "Singular points"): the nullclines and equilibria of dynkit/phase_plane.h, the direction
 * field as arrows of one length (the direction of (f_x, f_y) on the screen), trajectories
 * from several starts, in XPPAUT's window @ xlo..yhi; a standalone SVG, or (--html) a
 * self-contained page with the same picture and the equilibria's table. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/phase_plane.h"
#include "util/out_file.h"
#include "pages/pages.h"
#include "commands/analysis_kinds.h"

#define MAX_STARTS 16
#define MAX_POINTS 64

/* A growing list of points, pieces separated by NaN. */
typedef struct polyline {
    double *xy; /* (n x 2) */
    long n, cap;
    int bad;
} polyline;

static void put(polyline *l, double x, double y)
{
    if (l->n == l->cap) {
        const long cap = l->cap ? 2 * l->cap : 1024;
        double *xy = realloc(l->xy, (size_t)cap * 2 * sizeof *xy);
        if (!xy) {
            l->bad = 1;
            return;
        }
        l->xy = xy;
        l->cap = cap;
    }
    l->xy[2 * l->n] = x;
    l->xy[2 * l->n + 1] = y;
    l->n++;
}

static void on_segment(int which, double x0, double y0, double x1, double y1, void *ctx)
{
    polyline *l = (polyline *)ctx + which;
    put(l, x0, y0);
    put(l, x1, y1);
    put(l, NAN, NAN);
}

static cli_svg_line as_line(const char *label, const polyline *l, int points)
{
    return (cli_svg_line){label, l->xy, l->xy + 1, l->n, 2, points, NULL, NULL};
}

typedef struct phase_opts {
    int on;                     /* --phase-plane */
    const char *starts[MAX_STARTS];
    int n_starts;
    long grid, arrows;
    const char *html;
} phase_opts;

/* Take --phase-plane, --start (repeatable), --grid, --arrows and --html out of argv (into
 * rest, the others in order). */
static int take_options(int argc, char **argv, phase_opts *o, char **rest, int *n_rest)
{
    *n_rest = 0;
    for (int i = 0; i < argc; i++) {
        const char *v = NULL;
        int r = 0;
        if (i > 0 && cli_flag(argv[i], "phase-plane")) {
            o->on = 1;
            continue;
        }
        if (i > 0 && (r = cli_option(argc, argv, &i, "start", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("plot", "option --start needs a value (x=..,y=..)");
            if (o->n_starts >= MAX_STARTS)
                return cli_usage_error("plot", "at most %d --start are accepted", MAX_STARTS);
            o->starts[o->n_starts++] = v;
            continue;
        }
        for (int g = 0; g < 2 && r == 0; g++)
            if (i > 0 && (r = cli_option(argc, argv, &i, g ? "arrows" : "grid", &v)) != 0) {
                long k = 0;
                if (r < 0 || cli_parse_count(v, 2, &k) || k > 2000)
                    return cli_usage_error("plot", "--%s needs a whole number from 2 to 2000",
                                           g ? "arrows" : "grid");
                *(g ? &o->arrows : &o->grid) = k;
            }
        if (r != 0)
            continue;
        if (i > 0 && (r = cli_option(argc, argv, &i, "html", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("plot", "option --html needs a value (FILE.html)");
            o->html = v;
            continue;
        }
        rest[(*n_rest)++] = argv[i];
    }
    return CLI_OK;
}

/* --start NAME=V[,NAME=V]: values of the plane's two states (the others stay at the initial
 * state). */
static int parse_start(const char *text, const dyn_model *m, int ix, int iy, double *xy)
{
    char buf[256];
    if (strlen(text) >= sizeof buf)
        return cli_usage_error("plot", "--start: too long");
    strcpy(buf, text);
    for (char *save = buf, *item; (item = save) != NULL;) {
        char *comma = strchr(save, ',');
        if (comma)
            *comma = '\0';
        save = comma ? comma + 1 : NULL;
        char *eq = strchr(item, '=');
        if (eq)
            *eq = '\0';
        const int s = dyn_model_state_index(m, item);
        double v;
        if (!eq || (s != ix && s != iy) || cli_parse_number(eq + 1, &v))
            return cli_usage_error("plot",
                                   "--start '%s' is not accepted: give %s=VALUE,%s=VALUE (the "
                                   "states of the plane; a missing one starts at its initial "
                                   "value)",
                                   text, m->states[ix].name, m->states[iy].name);
        xy[s == ix ? 0 : 1] = v;
    }
    return CLI_OK;
}

/* The two states of the plane: --x and --y, else the model's xp and yp, else its only two. */
static int plane_states(const dyn_model *m, const char *xname, const char *yname, int *ix,
                        int *iy)
{
    if (!xname && !yname && m->phase_x && m->phase_y &&
        dyn_model_state_index(m, m->phase_x) >= 0 && dyn_model_state_index(m, m->phase_y) >= 0) {
        xname = m->phase_x;
        yname = m->phase_y;
    }
    if (!xname && !yname && m->n_states == 2) {
        xname = m->states[0].name;
        yname = m->states[1].name;
    }
    if (!xname || !yname)
        return cli_usage_error("plot", "--phase-plane: model %s has %d states: name the plane "
                               "with --x NAME --y NAME", m->name, m->n_states);
    *ix = dyn_model_state_index(m, xname);
    *iy = dyn_model_state_index(m, yname);
    if (*ix < 0 || *iy < 0 || *ix == *iy)
        return cli_usage_error("plot", "--phase-plane: --x and --y must name two different "
                               "states of model %s (got '%s' and '%s')", m->name, xname, yname);
    return CLI_OK;
}

/* The window: the model's (@ xlo, xhi, ylo, yhi) where lo < hi, else the extent of the run
 * from the initial state, widened by a fifth (or by 1 when it is a point). */
static void plane_window(const dyn_model *m, const cli_series *s, int ix, int iy, double w[4])
{
    const int col[2] = {1 + ix, 1 + iy};
    for (int a = 0; a < 2; a++) {
        const double *mw = m->phase_window + 2 * a;
        if (mw[0] < mw[1] && (m->phase_x && m->phase_y &&
                              dyn_model_state_index(m, a ? m->phase_y : m->phase_x) ==
                                  (a ? iy : ix))) {
            w[2 * a] = mw[0];
            w[2 * a + 1] = mw[1];
            continue;
        }
        double lo = INFINITY, hi = -INFINITY;
        for (long r = 0; s && r < s->rows; r++) {
            const double v = s->data[r * s->cols + col[a]];
            if (isfinite(v)) {
                lo = fmin(lo, v);
                hi = fmax(hi, v);
            }
        }
        if (!(hi >= lo))
            lo = hi = 0.0;
        const double pad = hi > lo ? 0.2 * (hi - lo) : fmax(1.0, fabs(lo));
        w[2 * a] = lo - pad;
        w[2 * a + 1] = hi + pad;
    }
}

/* Arrows of one length on an n x n grid: the direction of (f_x, f_y) on the screen (each
 * axis scaled by its window), a shaft and a head of two strokes. */
static void direction_field(const dyn_plane *p, long n, double *work, polyline *l)
{
    const double wx = p->xhi - p->xlo, wy = p->yhi - p->ylo;
    const double len = 0.7 / (double)n; /* of the window */
    for (long j = 0; j < n; j++)
        for (long i = 0; i < n; i++) {
            const double x = p->xlo + (i + 0.5) * wx / (double)n;
            const double y = p->ylo + (j + 0.5) * wy / (double)n;
            double fx, fy;
            if (dyn_plane_rates(p, x, y, work, &fx, &fy) || !isfinite(fx) || !isfinite(fy))
                continue;
            double u = fx / wx, v = fy / wy;
            const double r = hypot(u, v);
            if (!(r > 0))
                continue;
            u /= r;
            v /= r;
            const double x0 = x - 0.5 * len * u * wx, y0 = y - 0.5 * len * v * wy;
            const double x1 = x + 0.5 * len * u * wx, y1 = y + 0.5 * len * v * wy;
            put(l, x0, y0);
            put(l, x1, y1);
            put(l, NAN, NAN);
            for (int side = -1; side <= 1; side += 2) { /* the head: strokes at +-25 degrees */
                const double c = cos(2.7), s = side * sin(2.7);
                const double hu = c * u - s * v, hv = s * u + c * v;
                put(l, x1, y1);
                put(l, x1 + 0.35 * len * hu * wx, y1 + 0.35 * len * hv * wy);
                put(l, NAN, NAN);
            }
        }
}

typedef struct phase_page {
    const char *title, *svg;
    const dyn_model *m;
    int ix, iy;
    const dyn_plane_point *pts;
    int n_pts;
    const double *window;
} phase_page;

static int page_data(cli_json *j, void *ctx)
{
    const phase_page *pg = ctx;
    cli_json_begin_object(j);
    cli_json_key(j, "kind");
    cli_json_string(j, "phase");
    cli_json_key(j, "title");
    cli_json_string(j, pg->title);
    cli_json_key(j, "x");
    cli_json_string(j, pg->m->states[pg->ix].name);
    cli_json_key(j, "y");
    cli_json_string(j, pg->m->states[pg->iy].name);
    cli_json_key(j, "window");
    cli_json_numbers(j, pg->window, 4, 1);
    cli_json_key(j, "equilibria");
    cli_json_begin_array(j);
    for (int k = 0; k < pg->n_pts; k++) {
        const dyn_plane_point *pt = &pg->pts[k];
        cli_json_begin_object(j);
        cli_json_key(j, "state");
        cli_json_begin_object(j);
        cli_json_key(j, pg->m->states[pg->ix].name);
        cli_json_number(j, pt->x);
        cli_json_key(j, pg->m->states[pg->iy].name);
        cli_json_number(j, pt->y);
        cli_json_end_object(j);
        cli_json_key(j, "eigenvalues");
        cli_json_begin_array(j);
        for (int e = 0; e < 2; e++) {
            const double ev[2] = {pt->re[e], pt->im[e]};
            cli_json_numbers(j, ev, 2, 1);
        }
        cli_json_end_array(j);
        cli_json_key(j, "type");
        cli_json_string(j, dyn_plane_point_name(pt->type));
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_key(j, "svg");
    cli_json_string(j, pg->svg);
    cli_json_end_object(j);
    return j->bad;
}

int cli_plot_phase_plane(int argc, char **argv)
{
    phase_opts o = {.grid = 100, .arrows = 20};
    char **rest = calloc((size_t)argc + 1, sizeof *rest);
    if (!rest) {
        fprintf(stderr, "dynkit: error: out of memory\n");
        return CLI_FAILED;
    }
    int n_rest = 0;
    int rc = take_options(argc, argv, &o, rest, &n_rest);
    static const char *const extra[] = {"x", "y", "title", NULL};
    const char *values[3] = {NULL, NULL, NULL};
    cli_view v;
    memset(&v, 0, sizeof v);
    if (rc == CLI_OK)
        rc = cli_view_parse("plot", n_rest, rest, extra, values, &v);
    free(rest);
    if (rc != CLI_OK) {
        cli_view_free(&v);
        return rc;
    }
    const dyn_model *m = v.run.model;
    const char *output = v.run.output_path;
    int ix = -1, iy = -1;
    rc = plane_states(m, values[0], values[1], &ix, &iy);
    if (rc == CLI_OK && v.n_compare > 0)
        rc = cli_usage_error("plot", "--compare is not accepted with --phase-plane: the "
                                     "trajectories run with the run's method (--start adds "
                                     "more)");
    if (rc == CLI_OK && dyn_method_is_map(v.run.method))
        rc = cli_usage_error("plot", "--phase-plane: %s is a discrete map, which has no "
                                     "nullclines or direction field", m->name);
    if (rc == CLI_OK)
        rc = cli_kinds_refuse_history("plot", m, "--phase-plane (its nullclines, direction "
                                      "field and equilibria)", "dynkit plot MODEL --x NAME "
                                      "--y NAME draws its trajectory in a plane");
    if (rc == CLI_OK) {
        cli_kinds_noise_note("plot --phase-plane", m,
                             "the nullclines, direction field and equilibria are those of its "
                             "deterministic part, every noise term taken as 0; the "
                             "trajectories carry the noise");
        cli_kinds_markov_note("plot --phase-plane", m);
    }
    if (rc == CLI_OK && o.html && output)
        rc = cli_usage_error("plot", "give --html FILE or --output FILE, not both");
    static const char *const svg_html[] = {".svg", ".html", ".htm", NULL},
                             *const html_only[] = {".html", ".htm", NULL};
    if (rc == CLI_OK)
        rc = cli_out_check_extension("plot", "--output", output, svg_html);
    if (rc == CLI_OK)
        rc = cli_out_check_extension("plot", "--html", o.html, html_only);
    if (rc == CLI_OK && output &&
        (cli_has_extension(output, ".html") || cli_has_extension(output, ".htm")))
        o.html = output, output = NULL;
    double starts[MAX_STARTS][2];
    for (int k = 0; k < o.n_starts && rc == CLI_OK; k++) {
        starts[k][0] = v.run.y0[ix];
        starts[k][1] = v.run.y0[iy];
        rc = parse_start(o.starts[k], m, ix, iy, starts[k]);
    }
    /* the run from the initial state, then the window; the trajectories are whole (a
     * section of one of the plane's states is drawn as its line) */
    const dyn_poincare section = v.run.section;
    const int section_var = v.run.section_var;
    v.run.section.kind = DYN_POINCARE_NONE;
    int run_rc = rc == CLI_OK ? cli_view_record(&v) : rc;
    if (rc == CLI_OK && (run_rc == CLI_USAGE || v.n_series == 0))
        rc = run_rc;
    if (rc != CLI_OK) {
        cli_view_free(&v);
        return rc;
    }
    double w[4];
    plane_window(m, &v.series[0], ix, iy, w);
    const dyn_plane plane = {m, v.run.par, v.run.t0, v.run.y0, ix, iy, w[0], w[1], w[2], w[3]};
    /* the default starts: a 3 x 3 grid at 1/6, 1/2, 5/6 of the window */
    if (o.n_starts == 0)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                starts[o.n_starts][0] = w[0] + (2 * a + 1) * (w[1] - w[0]) / 6.0;
                starts[o.n_starts][1] = w[2] + (2 * b + 1) * (w[3] - w[2]) / 6.0;
                o.n_starts++;
            }
    double *work = malloc(dyn_plane_work_size(m->n_states, (int)o.grid, (int)o.grid) *
                          sizeof *work);
    double *y0 = malloc((size_t)m->n_states * sizeof *y0);
    polyline lines[5];
    memset(lines, 0, sizeof lines); /* 0, 1 nullclines, 2 field, 3 trajectories, 4 starts */
    static dyn_plane_point pts[MAX_POINTS];
    int n_pts = 0;
    char err[256];
    if (!work || !y0) {
        fprintf(stderr, "dynkit: error: out of memory\n");
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK &&
        dyn_plane_nullclines(&plane, (int)o.grid, (int)o.grid, work, on_segment, lines, err,
                             sizeof err))
        rc = cli_usage_error("plot", "--phase-plane: %s", err);
    if (rc == CLI_OK &&
        (n_pts = dyn_plane_equilibria(&plane, (int)o.grid, (int)o.grid, work, pts, MAX_POINTS,
                                      err, sizeof err)) < 0)
        rc = cli_usage_error("plot", "--phase-plane: %s", err);
    if (rc == CLI_OK)
        direction_field(&plane, o.arrows, work, &lines[2]);
    /* the trajectories: the run from the initial state, then one from each start */
    const cli_series *s0 = &v.series[0];
    for (long r = 0; rc == CLI_OK && r < s0->rows; r++)
        put(&lines[3], s0->data[r * s0->cols + 1 + ix], s0->data[r * s0->cols + 1 + iy]);
    put(&lines[3], NAN, NAN);
    put(&lines[4], v.run.y0[ix], v.run.y0[iy]);
    for (int k = 0; k < o.n_starts && rc == CLI_OK; k++) {
        cli_run one = v.run;
        memcpy(y0, v.run.y0, (size_t)m->n_states * sizeof *y0);
        y0[ix] = starts[k][0];
        y0[iy] = starts[k][1];
        one.y0 = y0;
        cli_series s;
        const int r = cli_series_record(&one, v.run.method, 0.0, CLI_MAX_ROWS, &s);
        if (r == CLI_USAGE) {
            rc = r;
            break;
        }
        for (long q = 0; q < s.rows; q++)
            put(&lines[3], s.data[q * s.cols + 1 + ix], s.data[q * s.cols + 1 + iy]);
        put(&lines[3], NAN, NAN);
        put(&lines[4], y0[ix], y0[iy]);
        cli_series_free(&s);
    }
    polyline cut = {0};
    if (section.kind == DYN_POINCARE_SECTION || section.kind == DYN_POINCARE_PERIOD) {
        if (section_var == ix) {
            put(&cut, section.plane, w[2]);
            put(&cut, section.plane, w[3]);
        } else if (section_var == iy) {
            put(&cut, w[0], section.plane);
            put(&cut, w[1], section.plane);
        }
    }
    for (int k = 0; k < 5; k++)
        if (lines[k].bad && rc == CLI_OK) {
            fprintf(stderr, "dynkit: error: out of memory\n");
            rc = CLI_FAILED;
        }
    /* the picture */
    static cli_svg_plot p;
    static char labels[4][160], kinds[7][64], title[256], xlabel[160], ylabel[160];
    static polyline typed[7];
    if (rc == CLI_OK) {
        memset(&p, 0, sizeof p);
        snprintf(title, sizeof title, "%s: phase plane %s, %s (%s)", m->name,
                 m->states[ix].name, m->states[iy].name, v.series[0].label);
        snprintf(xlabel, sizeof xlabel, "%s%s%s%s", m->states[ix].name,
                 *m->states[ix].unit ? " [" : "", m->states[ix].unit,
                 *m->states[ix].unit ? "]" : "");
        snprintf(ylabel, sizeof ylabel, "%s%s%s%s", m->states[iy].name,
                 *m->states[iy].unit ? " [" : "", m->states[iy].unit,
                 *m->states[iy].unit ? "]" : "");
        p.title = values[2] ? values[2] : title;
        p.xlabel = xlabel;
        p.ylabel = ylabel;
        p.xwin[0] = w[0];
        p.xwin[1] = w[1];
        p.ywin[0] = w[2];
        p.ywin[1] = w[3];
        snprintf(labels[0], sizeof labels[0], "%s' = 0", m->states[ix].name);
        snprintf(labels[1], sizeof labels[1], "%s' = 0", m->states[iy].name);
        snprintf(labels[2], sizeof labels[2], "trajectories (%d)", o.n_starts + 1);
        snprintf(labels[3], sizeof labels[3], "starts");
        p.lines[p.n_lines++] = as_line("direction field", &lines[2], 0);
        p.lines[p.n_lines++] = as_line(labels[0], &lines[0], 0);
        p.lines[p.n_lines++] = as_line(labels[1], &lines[1], 0);
        p.lines[p.n_lines++] = as_line(labels[2], &lines[3], 0);
        p.lines[p.n_lines++] = as_line(labels[3], &lines[4], 1);
        static char cut_label[160];
        if (cut.n) {
            snprintf(cut_label, sizeof cut_label, "section %s = %g",
                     m->states[section_var].name, section.plane);
            p.lines[p.n_lines++] = as_line(cut_label, &cut, 0);
        }
        for (int t = 0; t < 7; t++) {
            typed[t].n = 0;
            for (int k = 0; k < n_pts; k++)
                if ((int)pts[k].type == t)
                    put(&typed[t], pts[k].x, pts[k].y);
            if (typed[t].n > 0) {
                snprintf(kinds[t], sizeof kinds[t], "%s (%ld)",
                         dyn_plane_point_name((dyn_plane_point_type)t), typed[t].n);
                p.lines[p.n_lines++] = as_line(kinds[t], &typed[t], 1);
            }
        }
    }
    cli_out outf = {0};
    if (rc == CLI_OK)
        rc = cli_out_open(&outf, o.html ? "--html" : "--output", o.html ? o.html : output);
    if (rc == CLI_OK && !o.html) {
        rc = cli_svg_write(outf.f, &p);
        const int close_rc = cli_out_close(&outf, rc == CLI_OK);
        rc = rc == CLI_OK ? close_rc : rc;
    } else if (rc == CLI_OK) {
        char *svg = NULL;
        size_t len = 0;
        FILE *mem = open_memstream(&svg, &len);
        rc = mem && cli_svg_write(mem, &p) == CLI_OK ? CLI_OK : CLI_FAILED;
        if (mem)
            fclose(mem);
        if (rc == CLI_OK) {
            phase_page pg = {p.title, svg, m, ix, iy, pts, n_pts, w};
            rc = cli_html_page_write(outf.f, p.title, "phase.html", page_data, &pg);
        }
        free(svg);
        const int close_rc = cli_out_close(&outf, rc == CLI_OK);
        rc = rc == CLI_OK ? close_rc : rc;
    }
    for (int k = 0; k < 5; k++)
        free(lines[k].xy);
    free(cut.xy);
    for (int t = 0; t < 7; t++) {
        free(typed[t].xy);
        typed[t] = (polyline){0};
    }
    free(work);
    free(y0);
    cli_view_free(&v);
    return rc == CLI_OK ? run_rc : rc;
}
