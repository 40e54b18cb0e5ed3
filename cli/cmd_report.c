/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit report: every answer of the homework, as text, JSON, or a self-contained HTML page
 * with the plots and animations behind the answers. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/report.h"
#include "pages.h"

static void report_help(void)
{
    puts("Usage: dynkit report [--json] [--html FILE]\n\n"
         "Answer every question of the homework (TU Delft Advanced Dynamics, homework 8,\n"
         "problems 1 to 4), computed now: each value with its unit, how it was computed, and\n"
         "the judgements with the numbers behind them.\n\n"
         "  --json        one flat JSON object with dotted keys (pendulum.max_height_m, ...)\n"
         "  --html FILE   write the report as one self-contained HTML page (no network):\n"
         "                the answers beside the plots and animations that explain them\n"
         "                (FILE '-' is standard output); nothing else is printed unless\n"
         "                --json is given too");
}

/* What one writer of the library prints, as a NUL-terminated string (malloc'd) or NULL. */
static char *capture(int (*write)(const dyn_homework *, FILE *), const dyn_homework *hw,
                     size_t *len)
{
    FILE *f = tmpfile();
    char *text = NULL;
    long size;
    if (f && write(hw, f) == 0 && fflush(f) == 0 && (size = ftell(f)) >= 0 &&
        fseek(f, 0, SEEK_SET) == 0 && (text = malloc((size_t)size + 1)) != NULL) {
        *len = fread(text, 1, (size_t)size, f);
        text[*len] = '\0';
    }
    if (f)
        fclose(f);
    return text;
}

typedef struct report_page {
    const dyn_homework *hw;
    const dyn_hw_series *series;
    char *json, *text;
    size_t json_len;
} report_page;

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
    cli_json_end_object(j);
    return j->bad;
}

static int write_html(const dyn_homework *hw, const char *path)
{
    static dyn_hw_series series;
    char err[256] = "";
    report_page page = {hw, &series, NULL, NULL, 0};
    size_t text_len = 0;
    int rc = CLI_OK;
    if (dyn_homework_series(hw, &series, err, sizeof err)) {
        fprintf(stderr, "dynkit: report failed: %s\n", err);
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK) {
        page.json = capture(dyn_homework_write_json, hw, &page.json_len);
        page.text = capture(dyn_homework_write_text, hw, &text_len);
        if (!page.json || !page.text) {
            fprintf(stderr, "dynkit: error: formatting the report failed\n");
            rc = CLI_FAILED;
        }
    }
    FILE *out = stdout;
    if (rc == CLI_OK && strcmp(path, "-") != 0 && !(out = fopen(path, "w"))) {
        rc = cli_usage_error("report", "cannot open --html '%s' for writing: %s", path,
                             strerror(errno));
        out = stdout;
    }
    if (rc == CLI_OK)
        rc = cli_html_page_write(out, "dynkit report: homework 8, Advanced Dynamics", "report.html",
                                 page_data, &page);
    if (out != stdout && fclose(out) != 0 && rc == CLI_OK) {
        fprintf(stderr, "dynkit: error: writing %s failed\n", path);
        rc = CLI_FAILED;
    }
    free(page.json);
    free(page.text);
    dyn_hw_series_free(&series);
    return rc;
}

int cli_cmd_report(int argc, char **argv)
{
    int json = 0;
    const char *html = NULL;
    for (int i = 0; i < argc; i++) {
        const char *value = NULL;
        int r;
        if (cli_is_help(argv[i])) {
            report_help();
            return CLI_OK;
        } else if (cli_flag(argv[i], "json")) {
            json = 1;
        } else if ((r = cli_option(argc, argv, &i, "html", &value)) != 0) {
            if (r < 0)
                return cli_usage_error("report", "option --html needs a value (a file name)");
            html = value;
        } else {
            return cli_usage_error("report", "unknown option '%s' (accepted: --json, --html FILE)",
                                   argv[i]);
        }
    }
    static dyn_homework hw;
    char err[256] = "";
    if (dyn_homework_compute(&hw, err, sizeof err)) {
        fprintf(stderr, "dynkit: report failed: %s\n", err);
        return CLI_FAILED;
    }
    if (html) {
        int rc = write_html(&hw, html);
        if (rc != CLI_OK || !json)
            return rc;
    }
    int bad = json ? dyn_homework_write_json(&hw, stdout) : dyn_homework_write_text(&hw, stdout);
    if (bad || fflush(stdout)) {
        fprintf(stderr, "dynkit: error: writing the report failed\n");
        return CLI_FAILED;
    }
    return CLI_OK;
}
