/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit plot MODEL --live: the page of `animate` for the runs of a plot, showing the --y
 * columns against --x (a time series per column, or the x-y picture of the first column
 * when --x is not t), live (live_page.c, web/js/live.js) when the model compiles to
 * WebAssembly, else static with a warning. docs/web.md, "Live pages". */
#include <string.h>

#include "util/out_file.h"
#include "pages/pages.h"

typedef struct plot_page {
    const cli_view *v;
    const cli_live *live;
    const char *spec;
    int xcol;
    const int *ycols;
    int n_y;
} plot_page;

static int page_data(cli_json *j, void *ctx)
{
    const plot_page *pg = ctx;
    const cli_view *v = pg->v;
    const dyn_model *m = v->run.model;
    cli_json_begin_object(j);
    cli_json_animate_runs(j, v);
    cli_json_key(j, "plot"); /* what the page draws: x, and the columns y */
    cli_json_begin_object(j);
    cli_json_key(j, "x");
    cli_json_string(j, cli_series_column_name(m, pg->xcol));
    cli_json_key(j, "y");
    cli_json_begin_array(j);
    for (int i = 0; i < pg->n_y; i++)
        cli_json_string(j, cli_series_column_name(m, pg->ycols[i]));
    cli_json_end_array(j);
    cli_json_end_object(j);
    int bad = 0;
    if (pg->live->module) {
        cli_json_key(j, "live");
        bad = cli_json_live(j, pg->live, v, pg->spec);
    }
    cli_json_end_object(j);
    return bad || j->bad;
}

int cli_live_plot_page(const char *command, const char *spec, cli_view *v, int xcol,
                       const int *ycols, int n_y, int run_rc)
{
    (void)command;
    cli_live live;
    if (cli_live_build(v->run.model, &live) != 0)
        cli_warning("the page is not live, it shows the run it was written with: %s", live.why);
    cli_out outf = {0};
    int rc = cli_out_open(&outf, "--output", v->run.output_path);
    if (rc == CLI_OK) {
        char title[160];
        snprintf(title, sizeof title, "dynkit plot %s", v->run.model->name);
        plot_page pg = {v, &live, spec, xcol, ycols, n_y};
        cli_html_page_allow_wasm(live.module != NULL);
        rc = cli_html_page_write(outf.f, title, "animate.html", page_data, &pg);
        cli_html_page_allow_wasm(0);
        /* the page of a run that failed part-way is kept: it shows what was computed */
        const int close_rc = cli_out_close(&outf, rc == CLI_OK);
        if (rc == CLI_OK)
            rc = close_rc != CLI_OK ? close_rc : run_rc;
    }
    cli_live_free(&live);
    return rc;
}
