/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit report: every answer of the homework, as text, JSON, or a self-contained HTML page
 * with the plots and animations behind the answers, and the three studies of many runs
 * (dynkit/report_studies.h: the sweep library on every core). */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "util/out_file.h"
#include "dynkit/report.h"
#include "dynkit/report_studies.h"
#include "pages/pages.h"

static void report_help(void)
{
    puts("Usage: dynkit report [--json] [--html FILE [--live]] [--threads N] [--no-studies]\n\n"
         "Answer every question of the homework (TU Delft Advanced Dynamics, homework 8,\n"
         "problems 1 to 4), computed now: each value with its unit, how it was computed, and\n"
         "the judgements with the numbers behind them; and three studies of many runs\n"
         "(the pendulum's period against its amplitude, the plane's Euler-vs-RK4 answer\n"
         "from 1,000 perturbed starts, where the cart's rear wheels slip over v0 and f),\n"
         "computed by the sweep library on every core (docs/sweeps.md).\n\n"
         "  --json        one flat JSON object with dotted keys (pendulum.max_height_m, ...)\n"
         "  --html FILE   write the report as one self-contained HTML page (no network):\n"
         "                the answers beside the plots and animations that explain them\n"
         "                (FILE '-' is standard output); nothing else is printed unless\n"
         "                --json is given too\n"
         "  --live        with --html: a live part at the end of the page, where the\n"
         "                homework's models (pendulum, van der Pol, plane, cart) run in\n"
         "                the page, compiled to WebAssembly, with a slider for every\n"
         "                parameter and initial value (docs/web.md, \"Live pages\")\n"
         "  --threads N   run the studies on N threads (default: every core); the numbers\n"
         "                are the same bits for any N\n"
         "  --no-studies  the answers only, without the three studies (their values are\n"
         "                then absent from the text, the JSON and the page)");
}

/* What one writer of the library prints, as a NUL-terminated string (malloc'd) or NULL
 * (out of memory): kept in memory, so no temporary file can fail on a full disk. */
static char *capture(int (*write)(const dyn_homework *, FILE *), const dyn_homework *hw,
                     size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f)
        return NULL;
    const int bad = write(hw, f) != 0;
    if (fclose(f) != 0 || bad) {
        free(text);
        return NULL;
    }
    return text;
}

/* The homework's models that `report --html --live` runs in the page (docs/web.md). */
static const char *const live_models[] = {"pendulum", "vanderpol", "plane", "cart"};
enum { N_LIVE_MODELS = sizeof live_models / sizeof live_models[0] };

typedef struct report_page {
    const dyn_homework *hw;
    const dyn_hw_series *series;
    char *json, *text;
    size_t json_len;
    const cli_live *live;  /* the module of every built-in model, or NULL */
    cli_view *views;       /* each live model's default run (N_LIVE_MODELS) */
} report_page;

/* The page's live part: the module once, then per model the data of its live page
 * (`dynkit animate MODEL --live`: the model, the settings of its default run, which the
 * page computes, no run of the tool's) and the index the module's instance runs it by. */
static int live_data(cli_json *j, const report_page *r)
{
    cli_json_key(j, "live_module");
    cli_json_live_module(j, r->live);
    cli_json_key(j, "live_models");
    cli_json_begin_object(j);
    const cli_live shared = {0}; /* the module is the page's */
    int bad = 0;
    for (int k = 0; k < N_LIVE_MODELS && !bad; k++) {
        const cli_view *v = &r->views[k];
        cli_json_key(j, live_models[k]);
        cli_json_begin_object(j);
        cli_json_animate_runs(j, v); /* no run: the section draws the module's first */
        int index = -1;
        for (int i = 0; i < dyn_model_count(); i++)
            if (dyn_model_at(i) == v->run.model)
                index = i;
        cli_json_key(j, "choose");
        cli_json_number(j, index);
        cli_json_key(j, "live");
        bad = cli_json_live(j, &shared, v, live_models[k]);
        cli_json_end_object(j);
    }
    cli_json_end_object(j);
    return bad;
}

/* Each live model's default run's settings, as `dynkit animate MODEL --live` reads them
 * (the page computes the run itself). */
static int parse_live_views(cli_view *views)
{
    int rc = CLI_OK;
    for (int k = 0; k < N_LIVE_MODELS && rc == CLI_OK; k++) {
        char *args[] = {(char *)live_models[k], NULL};
        rc = cli_view_parse("report", 1, args, NULL, NULL, &views[k]);
    }
    return rc;
}

static void table_json(cli_json *j, const dyn_hw_table *t)
{
    cli_json_begin_object(j);
    cli_json_key(j, "title");
    cli_json_string(j, t->title);
    cli_json_key(j, "method");
    if (t->method)
        cli_json_string(j, t->method);
    else
        cli_json_null(j);
    const int digits = j->digits;
    j->digits = 17; /* the step exactly */
    cli_json_key(j, "step");
    cli_json_number(j, t->step);
    j->digits = digits;
    cli_json_key(j, "columns");
    cli_json_begin_array(j);
    for (int c = 0; c < t->cols; c++)
        cli_json_string(j, t->names[c]);
    cli_json_end_array(j);
    cli_json_key(j, "units");
    cli_json_begin_array(j);
    for (int c = 0; c < t->cols; c++)
        cli_json_string(j, t->units[c]);
    cli_json_end_array(j);
    /* thinned to what a screen shows: every k-th row, always the first and the last */
    const long every =
        t->rows > CLI_MAX_ROWS ? (t->rows - 1 + CLI_MAX_ROWS - 2) / (CLI_MAX_ROWS - 1) : 1;
    cli_json_key(j, "data");
    cli_json_begin_array(j);
    for (int c = 0; c < t->cols; c++) {
        j->digits = c == 0 ? 9 : digits; /* times finer than the screen, for stepping */
        cli_json_begin_array(j);
        for (long k = 0; k < t->rows; k++)
            if (k % every == 0 || k == t->rows - 1)
                cli_json_number(j, t->data[k * t->cols + c]);
        cli_json_end_array(j);
    }
    j->digits = digits;
    cli_json_end_array(j);
    cli_json_end_object(j);
}

static void number_array(cli_json *j, const double *v, long n)
{
    cli_json_begin_array(j);
    for (long i = 0; i < n; i++)
        cli_json_number(j, v[i]);
    cli_json_end_array(j);
}

static int page_data(cli_json *j, void *ctx)
{
    const report_page *r = ctx;
    cli_json_begin_object(j);
    cli_json_key(j, "kind");
    cli_json_string(j, "report");
    cli_json_key(j, "report");
    cli_json_raw(j, r->json, r->json_len);
    cli_json_key(j, "text");
    cli_json_string(j, r->text);
    cli_json_key(j, "series");
    cli_json_begin_object(j);
    for (int i = 0; i < r->series->count; i++) {
        cli_json_key(j, r->series->table[i].id);
        table_json(j, &r->series->table[i]);
    }
    cli_json_end_object(j);
    const dyn_hw_studies *st = &r->hw->studies;
    if (st->computed) {
        const dyn_study_plane *pl = &st->plane;
        const dyn_study_cart *c = &st->cart;
        cli_json_key(j, "studies");
        cli_json_begin_object(j);
        cli_json_key(j, "plane_distance_m");
        number_array(j, pl->distance_m, pl->n_runs);
        cli_json_key(j, "plane_angle_rad");
        number_array(j, pl->angle_rad, pl->n_runs);
        cli_json_key(j, "cart_ratio");
        number_array(j, c->ratio, (long)c->n_v0 * c->n_f);
        cli_json_end_object(j);
    }
    cli_json_key(j, "models");
    cli_json_begin_object(j);
    for (int i = 0; i < dyn_model_count(); i++) {
        const dyn_model *m = dyn_model_at(i);
        void *par = calloc(1, m->par_size);
        char err[256];
        if (par && dyn_model_default_params(m, par, err, sizeof err) == 0) {
            cli_json_key(j, m->name);
            cli_json_model(j, m, par);
        }
        free(par);
    }
    cli_json_end_object(j);
    int bad = r->live ? live_data(j, r) : 0;
    cli_json_end_object(j);
    return bad || j->bad;
}

static int write_html(const dyn_homework *hw, const char *path, int live_asked)
{
    static dyn_hw_series series;
    char err[256] = "";
    report_page page = {hw, &series, NULL, NULL, 0, NULL, NULL};
    size_t text_len = 0;
    int rc = CLI_OK;
    cli_live live;
    memset(&live, 0, sizeof live);
    static cli_view views[N_LIVE_MODELS];
    if (live_asked && cli_live_build_builtins(&live) != 0)
        cli_warning("the page is not live, it shows the homework's runs: %s", live.why);
    if (live.module) {
        rc = parse_live_views(views);
        page.live = &live;
        page.views = views;
    }
    if (dyn_homework_series(hw, &series, err, sizeof err)) {
        cli_stderr("dynkit: report failed: %s\n", err);
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK) {
        page.json = capture(dyn_homework_write_json, hw, &page.json_len);
        page.text = capture(dyn_homework_write_text, hw, &text_len);
        if (!page.json || !page.text) {
            cli_error("formatting the report failed: out of memory");
            rc = CLI_FAILED;
        }
    }
    /* written to a temporary file renamed over --html at the end: a failure keeps the old
     * page (out_file.h) */
    cli_out out = {0};
    if (rc == CLI_OK)
        rc = cli_out_open(&out, "--html", path);
    if (rc == CLI_OK) {
        cli_html_page_allow_wasm(live.module != NULL);
        rc = cli_html_page_write(out.f, "dynkit report: homework 8, Advanced Dynamics",
                                 "report.html", page_data, &page);
        cli_html_page_allow_wasm(0);
        int close_rc = cli_out_close(&out, rc == CLI_OK);
        if (rc == CLI_OK)
            rc = close_rc;
    }
    free(page.json);
    free(page.text);
    dyn_hw_series_free(&series);
    if (page.views)
        for (int k = 0; k < N_LIVE_MODELS; k++)
            cli_view_free(&views[k]);
    cli_live_free(&live);
    return rc;
}

int cli_cmd_report(int argc, char **argv)
{
    int json = 0, studies = 1, live = 0;
    const char *html = NULL, *threads_text = NULL;
    for (int i = 0; i < argc; i++) {
        const char *value = NULL;
        int r;
        if (cli_is_help(argv[i])) {
            report_help();
            return CLI_OK;
        } else if (cli_flag(argv[i], "json")) {
            json = 1;
        } else if (cli_flag(argv[i], "no-studies")) {
            studies = 0;
        } else if (cli_flag(argv[i], "live")) {
            live = 1;
        } else if ((r = cli_option(argc, argv, &i, "html", &value)) != 0) {
            if (r < 0)
                return cli_usage_error("report", "option --html needs a value (a file name)");
            html = value;
        } else if ((r = cli_option(argc, argv, &i, "threads", &value)) != 0) {
            if (r < 0)
                return cli_usage_error("report", "option --threads needs a value (a whole "
                                                 "number from 1 to 4096)");
            threads_text = value;
        } else {
            return cli_usage_error("report",
                                   "unknown option '%s' (accepted: --json, --html FILE, "
                                   "--live, --threads N, --no-studies)",
                                   argv[i]);
        }
    }
    if (live && !html)
        return cli_usage_error("report", "--live makes the page of --html FILE live: give "
                                         "--html FILE too");
    long threads = 0;
    if (threads_text && (cli_parse_count(threads_text, 1, &threads) || threads > 4096))
        return cli_usage_error("report", "--threads '%s': give a whole number from 1 to 4096",
                               threads_text);
    static dyn_homework hw;
    char err[256] = "";
    if (dyn_homework_compute(&hw, err, sizeof err) ||
        (studies && dyn_homework_studies(&hw, (int)threads, err, sizeof err))) {
        cli_stderr("dynkit: report failed: %s\n", err);
        return CLI_FAILED;
    }
    if (html) {
        int rc = write_html(&hw, html, live);
        if (rc != CLI_OK || !json)
            return rc;
    }
    int bad = json ? dyn_homework_write_json(&hw, stdout) : dyn_homework_write_text(&hw, stdout);
    if (bad || fflush(stdout)) {
        cli_error("writing the report failed");
        return CLI_FAILED;
    }
    return CLI_OK;
}
