/* SPDX-License-Identifier: BSD-3-Clause */
/* The self-contained HTML page: the template web/page.html with its markers
 * <!--dynkit:NAME--> replaced by the title, the style sheet, the body template, the data
 * (JSON) and the scripts, all inline, so the page makes no network request. Also the JSON
 * of a model and of a recorded run, shared by the pages. */
#include <string.h>

#include "util/escape.h"
#include "pages/pages.h"
#include "pages/web_assets.h"

static const cli_web_asset *find_asset(const char *name)
{
    for (int i = 0; i < cli_web_asset_count; i++)
        if (strcmp(cli_web_assets[i].name, name) == 0)
            return &cli_web_assets[i];
    return NULL;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

static int allow_wasm;

void cli_html_page_allow_wasm(int on) { allow_wasm = on; }

/* Every asset whose name ends with suffix, in the build's order; the scripts of live pages
 * (js/live*.js) only in them. */
static int write_assets(FILE *out, const char *suffix)
{
    int bad = 0;
    for (int i = 0; i < cli_web_asset_count; i++)
        if (ends_with(cli_web_assets[i].name, suffix) &&
            (allow_wasm || strncmp(cli_web_assets[i].name, "js/live", 7) != 0)) {
            bad |= fprintf(out, "\n/* %s */\n", cli_web_assets[i].name) < 0;
            bad |= fwrite(cli_web_assets[i].data, 1, cli_web_assets[i].size, out) !=
                   cli_web_assets[i].size;
        }
    return bad;
}

int cli_html_page_write(FILE *out, const char *title, const char *body_asset, cli_page_data_fn data,
                        void *ctx)
{
    static const char marker[] = "<!--dynkit:";
    const cli_web_asset *page = find_asset("page.html");
    const cli_web_asset *body = find_asset(body_asset);
    if (!page || !body) {
        cli_error("the page template %s is missing from the build",
                page ? body_asset : "page.html");
        return CLI_FAILED;
    }
    const char *p = (const char *)page->data, *end = p + page->size;
    int bad = 0;
    while (p < end && !bad) {
        const char *m = strstr(p, marker);
        const char *close = m ? strstr(m, "-->") : NULL;
        if (!m || !close) {
            bad |= fwrite(p, 1, (size_t)(end - p), out) != (size_t)(end - p);
            break;
        }
        bad |= fwrite(p, 1, (size_t)(m - p), out) != (size_t)(m - p);
        const char *name = m + sizeof marker - 1;
        const size_t len = (size_t)(close - name);
        if (len == 5 && strncmp(name, "title", 5) == 0) {
            bad |= cli_xml_escaped(out, title);
        } else if (len == 5 && strncmp(name, "style", 5) == 0) {
            bad |= write_assets(out, ".css");
        } else if (len == 6 && strncmp(name, "script", 6) == 0) {
            bad |= write_assets(out, ".js");
        } else if (len == 4 && strncmp(name, "wasm", 4) == 0) {
            if (allow_wasm) /* compiling the module; its runs in a worker of the page's script */
                bad |= fputs(" 'wasm-unsafe-eval'; worker-src blob:", out) < 0;
        } else if (len == 4 && strncmp(name, "body", 4) == 0) {
            bad |= fwrite(body->data, 1, body->size, out) != body->size;
        } else if (len == 4 && strncmp(name, "data", 4) == 0) {
            cli_json j;
            cli_json_init(&j, out, 6);
            bad |= data(&j, ctx) || j.bad;
        } else {
            bad |= fwrite(m, 1, (size_t)(close + 3 - m), out) != (size_t)(close + 3 - m);
        }
        p = close + 3;
    }
    if (bad || fflush(out)) {
        cli_error("writing the page failed");
        return CLI_FAILED;
    }
    return CLI_OK;
}

static void vars(cli_json *j, const dyn_var *v, int n)
{
    cli_json_begin_array(j);
    for (int i = 0; i < n; i++) {
        cli_json_begin_object(j);
        cli_json_key(j, "name");
        cli_json_string(j, v[i].name);
        cli_json_key(j, "unit");
        cli_json_string(j, v[i].unit);
        cli_json_key(j, "description");
        cli_json_string(j, v[i].description);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
}

void cli_json_model(cli_json *j, const dyn_model *m, const void *par)
{
    cli_json_begin_object(j);
    cli_json_key(j, "name");
    cli_json_string(j, m->name);
    cli_json_key(j, "title");
    cli_json_string(j, m->title);
    cli_json_key(j, "states");
    vars(j, m->states, m->n_states);
    cli_json_key(j, "outputs");
    vars(j, m->outputs, m->n_outputs);
    cli_json_key(j, "params");
    cli_json_begin_object(j);
    const int digits = j->digits;
    j->digits = 17; /* parameters exactly */
    for (int i = 0; i < m->n_params; i++) {
        cli_json_key(j, m->params[i].name);
        cli_json_number(j, dyn_model_get_param(m, par, i));
    }
    j->digits = digits;
    cli_json_end_object(j);
    cli_json_key(j, "param_units");
    cli_json_begin_object(j);
    for (int i = 0; i < m->n_params; i++) {
        cli_json_key(j, m->params[i].name);
        cli_json_string(j, m->params[i].unit);
    }
    cli_json_end_object(j);
    /* the phase plane the model asks for (a model file's @ xp=, yp=): t, states, outputs */
    if (m->phase_x && m->phase_y && cli_series_column(m, m->phase_x) >= 0 &&
        cli_series_column(m, m->phase_y) >= 0) {
        cli_json_key(j, "phase");
        cli_json_begin_array(j);
        cli_json_string(j, m->phase_x);
        cli_json_string(j, m->phase_y);
        cli_json_end_array(j);
    }
    cli_json_key(j, "time_unit");
    cli_json_string(j, cli_time_unit(m));
    /* XPPAUT's @ xlo, xhi, ylo, yhi: the window of an axis whose lo < hi, else null */
    const double *w = m->phase_window;
    if (w[0] < w[1] || w[2] < w[3]) {
        cli_json_key(j, "phase_window");
        cli_json_begin_array(j);
        for (int k = 0; k < 4; k += 2) {
            if (w[k] < w[k + 1])
                cli_json_numbers(j, w + k, 2, 1);
            else
                cli_json_null(j);
        }
        cli_json_end_array(j);
    }
    cli_json_end_object(j);
}

void cli_json_series(cli_json *j, const dyn_model *m, const cli_series *s)
{
    cli_json_begin_object(j);
    cli_json_key(j, "label");
    cli_json_string(j, s->label);
    cli_json_key(j, "method");
    /* no method: a series given by a formula (the cart's prescribed path) */
    cli_json_string(j, s->method ? s->method->name : "");
    cli_json_key(j, "method_title");
    cli_json_string(j, s->method ? s->method->title : "");
    cli_json_key(j, "map"); /* a discrete map: its iterates are drawn as dots */
    cli_json_bool(j, s->method && dyn_method_is_map(s->method));
    const int digits = j->digits;
    j->digits = 17; /* exactly */
    cli_json_key(j, "step");
    cli_json_number(j, s->step);
    cli_json_key(j, "samples");
    cli_json_number(j, (double)s->samples);
    j->digits = digits;
    cli_json_key(j, "status");
    cli_json_string(j, dyn_status_name(s->status));
    cli_json_key(j, "message");
    cli_json_string(j, s->message);
    cli_json_key(j, "columns");
    cli_json_begin_array(j);
    for (int c = 0; c < s->cols; c++)
        cli_json_string(j, cli_series_column_name(m, c));
    cli_json_end_array(j);
    cli_json_key(j, "units");
    cli_json_begin_array(j);
    for (int c = 0; c < s->cols; c++)
        cli_json_string(j, cli_series_column_unit(m, c));
    cli_json_end_array(j);
    cli_json_key(j, "data");
    cli_json_begin_array(j);
    for (int c = 0; c < s->cols; c++) {
        j->digits = c == 0 ? 9 : digits; /* times finer than the screen, for stepping */
        cli_json_numbers(j, s->data + c, s->rows, s->cols);
    }
    j->digits = digits;
    cli_json_end_array(j);
    cli_json_end_object(j);
}

void cli_json_animate_runs(cli_json *j, const cli_view *v)
{
    cli_json_key(j, "kind");
    cli_json_string(j, "animate");
    cli_json_key(j, "model");
    cli_json_model(j, v->run.model, v->run.par);
    cli_json_key(j, "span");
    const double span[2] = {v->run.t0, v->run.t1};
    cli_json_numbers(j, span, 2, 1);
    cli_json_key(j, "runs");
    cli_json_begin_array(j);
    for (int k = 0; k < v->n_series; k++)
        cli_json_series(j, v->run.model, &v->series[k]);
    cli_json_end_array(j);
}
