/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared declarations of the commands that draw (animate, plot, report --html): a JSON
 * writer, recorded runs, the self-contained HTML page and standalone SVG plots. */
#ifndef DYNKIT_CLI_PAGES_H
#define DYNKIT_CLI_PAGES_H

#include <stdio.h>

#include "cli.h"
#include "dynkit/ani.h"

/* ---- JSON writer (json_write.c) ---- */

#define CLI_JSON_MAX_DEPTH 32

/* Writes one JSON value to out, placing the commas itself. Strings are escaped so the text
 * can sit inside an HTML <script> element ('<', '>', '&' as \u escapes). */
typedef struct cli_json {
    FILE *out;
    int digits; /* significant digits of numbers (%.*g) */
    int depth;
    int after_key;
    unsigned char has_items[CLI_JSON_MAX_DEPTH];
    int bad; /* a write failed */
} cli_json;

void cli_json_init(cli_json *j, FILE *out, int digits);
void cli_json_begin_object(cli_json *j);
void cli_json_end_object(cli_json *j);
void cli_json_begin_array(cli_json *j);
void cli_json_end_array(cli_json *j);
void cli_json_key(cli_json *j, const char *key);
/* A number with j->digits significant digits; null when not finite. */
void cli_json_number(cli_json *j, double v);
void cli_json_string(cli_json *j, const char *s);
void cli_json_bool(cli_json *j, int v);
void cli_json_null(cli_json *j);
/* A value already in JSON (e.g. an object from another writer), copied as it is. */
void cli_json_raw(cli_json *j, const char *text, size_t len);
/* An array of n numbers v[0], v[stride], v[2 stride], ... */
void cli_json_numbers(cli_json *j, const double *v, long n, long stride);

/* ---- zlib streams (zlib_write.c) ---- */

/* data[0..n) as a zlib stream (RFC 1950): compressed by zlib when the tool is built with it,
 * else stored blocks; a new buffer (free it) of *out_n bytes, or NULL when out of memory. */
unsigned char *cli_zlib_compress(const unsigned char *data, size_t n, size_t *out_n);

/* ---- recorded runs (run_record.c) ---- */

/* One run of a model kept in memory for a picture: t, the states and the extra outputs. */
typedef struct cli_series {
    char label[96]; /* e.g. "rk4, h = 0.01 s" */
    const dyn_tableau *method;
    double step;
    int cols;          /* 1 + n_states + n_outputs */
    long rows;         /* samples kept */
    long samples;      /* samples of the run before thinning */
    double *data;      /* (rows x cols) row-major, owned */
    int status;        /* dyn_status of the solve */
    char message[640]; /* why the run stopped, when status != DYN_OK */
} cli_series;

/* Run run->model (parameters, initial state, span of run) with method at step (0: the run's
 * step, given or the model's), keeping every k-th sample with k the larger of run->every and
 * what keeps at most max_rows samples, and always the first and the last; runs whose sample
 * count is not known beforehand (an adaptive method at every accepted step,
 * cli_run_at_steps) are thinned as they come (every other row dropped when the rows fill
 * up). Warnings of the model go to stderr once each (unless
 * run->quiet). Returns CLI_OK; CLI_USAGE for a bad grid (message printed); CLI_FAILED when
 * out of memory or the solve failed (s->status, s->message; the rows up to there kept). */
int cli_series_record(const cli_run *run, const dyn_tableau *method, double step, long max_rows,
                      cli_series *s);
void cli_series_free(cli_series *s);
/* The columns of a model's recorded run: 0 is t, then the states, then the outputs.
 * Index of the column called name, or -1; name and unit of column j. */
int cli_series_column(const dyn_model *m, const char *name);
const char *cli_series_column_name(const dyn_model *m, int j);
const char *cli_series_column_unit(const dyn_model *m, int j);
/* Accepted column names, comma-separated, into buf (for messages); returns buf. */
char *cli_series_column_names(const dyn_model *m, char *buf, size_t size);

/* ---- run options of the commands that draw (view_args.c) ---- */

#define CLI_MAX_COMPARE 8
#define CLI_MAX_ROWS 2000 /* samples per series that a page or a plot keeps */

/* Another run to overlay: --compare METHOD[:STEP]; step 0 means the main run's step (the
 * given --step or the model's; an adaptive run then samples as the main run would). */
typedef struct cli_compare {
    const dyn_tableau *method;
    double step;
} cli_compare;

/* Parse "METHOD[:STEP]"; CLI_OK, or CLI_USAGE with a message naming what is accepted. */
int cli_compare_parse(const char *command, const char *text, cli_compare *c);

/* Runs of one picture: the main run (options of cli_run_parse) and the --compare runs. */
typedef struct cli_view {
    cli_run run;
    int n_compare;
    cli_compare compare[CLI_MAX_COMPARE];
    int n_series;
    cli_series series[1 + CLI_MAX_COMPARE];
} cli_view;

/* Parse the run options of argv, taking out --compare (repeatable) and each option named in
 * extra (NULL-terminated, e.g. {"y", "x", NULL}; their values into extra_values, NULL when
 * absent). --final and --trace are refused. Returns CLI_OK or CLI_USAGE (message printed).
 * Release with cli_view_free. */
int cli_view_parse(const char *command, int argc, char **argv, const char *const *extra,
                   const char **extra_values, cli_view *v);
/* Record the main run and every --compare run. CLI_OK, or the first failure's status (a
 * failed solve keeps its rows and its message, and the other runs are still made). */
int cli_view_record(cli_view *v);
void cli_view_free(cli_view *v);

/* ---- the self-contained HTML page (html_page.c) ---- */

/* Writes the data of a page as one JSON value; returns 0 or non-zero. */
typedef int (*cli_page_data_fn)(cli_json *j, void *ctx);

/* Write the page: the template web/page.html with the title (HTML-escaped), the style, the
 * body template body_asset (e.g. "report.html"), the data written by data() and every
 * script, all inline: the page makes no request. Returns CLI_OK or CLI_FAILED. */
int cli_html_page_write(FILE *out, const char *title, const char *body_asset, cli_page_data_fn data,
                        void *ctx);
/* The model's description for a page: name, title, states, outputs (name, unit,
 * description) and the values of the parameters in par. */
void cli_json_model(cli_json *j, const dyn_model *m, const void *par);
/* A recorded run: label, method, step, status, message, columns, units and the samples,
 * column by column. */
void cli_json_series(cli_json *j, const dyn_model *m, const cli_series *s);

/* Let the next pages compile WebAssembly ('wasm-unsafe-eval' in their Content Security
 * Policy: a live page's module; no other code is evaluated). */
void cli_html_page_allow_wasm(int on);

/* ---- live pages (live_page.c; docs/web.md, "Live pages") ---- */

/* The model compiled to WebAssembly for a page, or why not. */
typedef struct cli_live {
    unsigned char *module; /* the .wasm (size bytes), NULL when the page cannot be live */
    size_t size;
    char why[1024];        /* when module is NULL: why, and what to install */
    int scene_inputs;      /* 1: a mechanism's outputs end with its scene's inputs
                              (DYN_MECH_SCENE_INPUTS), from which the page draws its runs */
    int ani_outputs;       /* 1: an .ode model's outputs end with its animation's numbers
                              (dyn_ani_ode_to_c) */
} cli_live;
/* Compile model m (its C, with the core library for wasm32) into out: 0, or -1 with
 * out->why. Nothing is printed. */
int cli_live_build(const dyn_model *m, cli_live *out);
/* One module for every built-in model (report --html --live): an instance runs model
 * dyn_model_at(i) once its export dk_live_choose(i) was called. 0, or -1 with out->why. */
int cli_live_build_builtins(cli_live *out);
/* cli_live_build for an .ode model with the XPPAUT animation ani_path: the module's outputs
 * end with the animation's numbers (out->ani_outputs), from which the page draws its runs;
 * else (another model, or the animation cannot be compiled so) as cli_live_build. */
int cli_live_build_ani(const dyn_model *m, const char *ani_path, cli_live *out);
/* The module as a JSON string (base64). */
void cli_json_live_module(cli_json *j, const cli_live *live);
void cli_live_free(cli_live *live);
/* The page's "live" object: the module (base64), the model as given on the command line
 * (spec), the run's settings, the parameters and initial values with their defaults, the
 * methods offered and the --compare runs (without the module when live->module is NULL:
 * a page whose models share one). 0 or non-zero. */
int cli_json_live(cli_json *j, const cli_live *live, const cli_view *v, const char *spec);
/* dynkit plot MODEL --live: the animate page of v's runs with the plots of the columns
 * ycols (n_y) against xcol (0: t; else an x-y picture), live when the model compiles
 * (cli_live_build; else static, with a warning), written to v->run.output_path. run_rc:
 * the status of the runs, returned when the page was written. */
int cli_live_plot_page(const char *command, const char *spec, cli_view *v, int xcol,
                       const int *ycols, int n_y, int run_rc);

/* The members of an animate page's data that every such page has: its kind, the model, the
 * span and the recorded runs of v (the caller opens and closes the object). */
void cli_json_animate_runs(cli_json *j, const cli_view *v);

/* ---- standalone SVG plots (svg_plot.c) ---- */

#define CLI_SVG_MAX_LINES 32

/* One line of a plot: n points (x[k stride], y[k stride]). */
typedef struct cli_svg_line {
    const char *label;
    const double *x, *y;
    long n, stride;
    int points; /* 1: a dot per point, unjoined (the iterates of a discrete map) */
    const double *lo, *hi; /* a band shaded between lo and hi at each x (same stride), e.g.
                            * percentiles over runs; NULL: none */
} cli_svg_line;

typedef struct cli_svg_plot {
    const char *title;
    const char *xlabel, *ylabel; /* with their units, e.g. "t [s]" */
    int n_lines;
    cli_svg_line lines[CLI_SVG_MAX_LINES];
    /* a fixed window of an axis when lo < hi (XPPAUT's @ xlo, xhi, ylo, yhi), the lines
     * clipped to it; else (zeros) the axis spans the data */
    double xwin[2], ywin[2];
} cli_svg_plot;

/* Write the plot as a standalone SVG document: axes with ticks and numbers, the axis labels,
 * a legend, one polyline per line (a line with non-finite points is split there). Returns
 * CLI_OK or CLI_FAILED (write error). */
int cli_svg_write(FILE *out, const cli_svg_plot *p);
/* n plots stacked top to bottom in one document (e.g. one per unit of the y axis), the
 * lines' colours continuing from panel to panel. */
int cli_svg_write_panels(FILE *out, const cli_svg_plot *const *plots, int n);
/* 1 when two quantities of the same unit, whose ranges (max - min) are span_a and span_b,
 * share a panel: always with a unit; without one (or the unit 1) only when their ranges
 * are within a factor of 10 (a gate within 0..1 beside a potential over 100 would be a
 * flat line). */
int cli_svg_share_axis(const char *unit, double span_a, double span_b);

/* ---- an XPPAUT animation file on the animate page (ani_page.c) ---- */

typedef struct cli_ani {
    dyn_ani *ani;    /* NULL: none */
    char path[1024];
    int from_ode;    /* the names come from the model's .ode file */
} cli_ani;

/* The animation of the model MODEL_SPEC (m loaded from it): ani_path, or else NAME.ani
 * beside a model file NAME.ode or NAME.c when there is one. CLI_OK (out->ani NULL when
 * there is none), or CLI_USAGE with the diagnostic (FILE:LINE:COL) printed. */
int cli_ani_open(const char *command, const char *model_spec, const char *ani_path,
                 const dyn_model *m, cli_ani *out);
void cli_ani_free(cli_ani *a);
/* The animation evaluated at every sample of every run of v, as the page's JSON; 0 or
 * non-zero (out of memory, write error). */
int cli_json_ani(cli_json *j, const cli_ani *a, const cli_view *v);

/* ---- the picture of a mechanism file (mech_page.c) ---- */

typedef struct dyn_mech_scene dyn_mech_scene;
/* The geometry of MODEL_SPEC when it is a mechanism file NAME.mech (m loaded from it):
 * CLI_OK with *out (NULL for another model), or CLI_USAGE with the diagnostic printed. */
int cli_mech_scene_open(const char *model_spec, const dyn_model *m, dyn_mech_scene **out);
/* The bodies' poses and the shapes' numbers at every sample of every run of v, as the
 * page's JSON; 0 or non-zero (out of memory, write error). */
int cli_json_mech(cli_json *j, const dyn_mech_scene *sc, const cli_view *v);
/* The plan of the scene's frames (the dyn_mech_*_plan of dynkit/mbs.h) as an object, for a
 * live page that draws its own runs (web/js/live_scene.js). */
void cli_json_mech_plan(cli_json *j, const dyn_mech_scene *sc);

/* dynkit plot MODEL --phase-plane (phase_plot.c). */
int cli_plot_phase_plane(int argc, char **argv);

/* Subcommands. */
int cli_cmd_animate(int argc, char **argv);
int cli_cmd_plot(int argc, char **argv);

#endif
