/* SPDX-License-Identifier: BSD-3-Clause */
/* The XPPAUT animation (.ani) of a model file on the page of `dynkit animate`: finding
 * NAME.ani beside NAME.ode (or NAME.mech, NAME.c), reading it with the model's names
 * (dynkit/ani.h),
 * evaluating every primitive at every sample the page shows, and writing the numbers into
 * the page's data — per run and primitive, one number when a value is the same in every
 * frame (numbers and parameters only, and every value of a `permanent` primitive, which
 * XPPAUT evaluates once, at the start), else an array over the samples. web/js/ani.js draws
 * them; docs/model-files.md, "Animation files (.ani)", describes the format. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "util/escape.h"
#include "pages/pages.h"
#include "util/out_file.h"

enum { ANI_FILE_MAX_BYTES = 16 << 20 };

static const char *const kind_names[DYN_ANI_KIND_COUNT] = {
    [DYN_ANI_LINE] = "line",       [DYN_ANI_RLINE] = "rline",     [DYN_ANI_RECT] = "rect",
    [DYN_ANI_FRECT] = "frect",     [DYN_ANI_CIRCLE] = "circle",   [DYN_ANI_FCIRCLE] = "fcircle",
    [DYN_ANI_ELLIPSE] = "ellipse", [DYN_ANI_FELLIPSE] = "fellipse", [DYN_ANI_TEXT] = "text",
    [DYN_ANI_VTEXT] = "vtext",     [DYN_ANI_COMET] = "comet",     [DYN_ANI_SETTEXT] = "settext",
};

static int is_regular(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The whole file into a malloc'd buffer; NULL with a message printed. */
static char *read_all(const char *what, const char *path, size_t *len)
{
    cli_input_note(path, what[0] == 'm' ? "the model file" : "the animation file");
    FILE *f = fopen(path, "rb");
    if (!f) {
        cli_error("cannot open %s '%s': %s", what, path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(ANI_FILE_MAX_BYTES + 1);
    size_t n = buf ? fread(buf, 1, ANI_FILE_MAX_BYTES + 1, f) : 0;
    const int bad = !buf || ferror(f);
    fclose(f);
    if (bad || n > ANI_FILE_MAX_BYTES) {
        cli_error("cannot read %s '%s': %s", what, path,
                !buf ? "out of memory" : n > ANI_FILE_MAX_BYTES ? "larger than 16 MiB"
                                                               : "read error");
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

static void print_note(const char *path, int line, const char *message, void *ctx)
{
    (void)ctx;
    char where[1024], shown[4096]; /* control bytes of the file escaped */
    if (cli_verbose())
        cli_note("%s:%d: %s", cli_terminal_text(path, 0, where, sizeof where),
                line, cli_terminal_text(message, 0, shown, sizeof shown));
}

static int ends_with(const char *s, const char *suffix)
{
    const size_t ls = strlen(s), lx = strlen(suffix);
    return ls > lx && strcasecmp(s + ls - lx, suffix) == 0;
}

int cli_ani_open(const char *command, const char *model_spec, const char *ani_path,
                 const dyn_model *m, cli_ani *out)
{
    memset(out, 0, sizeof *out);
    /* NAME.ani found beside a C model or mechanism, not named by --ani: XPPAUT's format,
     * perhaps written for another model of that name, so a misfit is a warning */
    int implicit = 0;
    if (!ani_path) {
        /* NAME.ani beside a model file NAME.ode, NAME.mech or NAME.c */
        if (!model_spec || !(ends_with(model_spec, ".ode") || ends_with(model_spec, ".c") ||
                             ends_with(model_spec, ".mech")))
            return CLI_OK;
        const size_t n = strlen(model_spec) - (ends_with(model_spec, ".c")      ? 2
                                               : ends_with(model_spec, ".mech") ? 5
                                                                                : 4);
        if (n + 5 > sizeof out->path)
            return CLI_OK;
        memcpy(out->path, model_spec, n);
        memcpy(out->path + n, ".ani", 5);
        if (!is_regular(out->path)) {
            out->path[0] = '\0';
            return CLI_OK;
        }
        /* NAME.ani beside NAME.ode is the .ode file's (XPPAUT's pair), not NAME.c's */
        char ode[sizeof out->path];
        memcpy(ode, model_spec, n);
        memcpy(ode + n, ".ode", 5);
        if (!ends_with(model_spec, ".ode") && is_regular(ode)) {
            char a[1024], b[1024], c[1024];
            cli_warning("%s belongs to %s, not to %s: the page plays no "
                    "animation (--ani FILE.ani plays one)",
                    cli_terminal_text(out->path, 0, a, sizeof a),
                    cli_terminal_text(ode, 0, b, sizeof b),
                    cli_terminal_text(model_spec, 0, c, sizeof c));
            out->path[0] = '\0';
            return CLI_OK;
        }
        implicit = !ends_with(model_spec, ".ode");
    } else {
        if (strlen(ani_path) + 1 > sizeof out->path)
            return cli_usage_error(command, "--ani: the path is too long");
        struct stat st;
        if (stat(ani_path, &st) != 0)
            return cli_usage_error(command, "--ani '%s': %s", ani_path, strerror(errno));
        if (!S_ISREG(st.st_mode))
            return cli_usage_error(command, "--ani '%s': not a file", ani_path);
        strcpy(out->path, ani_path);
    }
    size_t len = 0, ode_len = 0;
    char *text = read_all("animation file", out->path, &len);
    if (!text)
        return CLI_USAGE;
    const int from_ode = model_spec && ends_with(model_spec, ".ode");
    char *ode_text = from_ode ? read_all("model file", model_spec, &ode_len) : NULL;
    if (from_ode && !ode_text) {
        free(text);
        return CLI_USAGE;
    }
    dyn_ani_model am;
    memset(&am, 0, sizeof am);
    const char **names = NULL;
    if (from_ode) {
        am.ode_path = model_spec;
        am.ode_text = ode_text;
        am.ode_len = ode_len;
    } else {
        const int n = m->n_states + m->n_outputs + m->n_params;
        names = calloc((size_t)n + 1, sizeof *names);
        if (!names) {
            free(text);
            cli_error("out of memory");
            return CLI_FAILED;
        }
        for (int i = 0; i < m->n_states; i++)
            names[i] = m->states[i].name;
        for (int i = 0; i < m->n_outputs; i++)
            names[m->n_states + i] = m->outputs[i].name;
        for (int i = 0; i < m->n_params; i++)
            names[m->n_states + m->n_outputs + i] = m->params[i].name;
        am.n_states = m->n_states;
        am.n_outputs = m->n_outputs;
        am.n_params = m->n_params;
        am.states = names;
        am.outputs = names + m->n_states;
        am.params = names + m->n_states + m->n_outputs;
    }
    dyn_lang_diag diag;
    const int rc = dyn_ani_parse(out->path, text, len, &am, &out->ani, &diag, print_note, NULL);
    free(text);
    free(ode_text);
    free(names);
    if (rc != 0) {
        char shown[2048];
        if (implicit && rc != 1) {
            char a[1024];
            cli_terminal_text(out->path, 0, a, sizeof a);
            cli_warning("%s, found beside the model, does not fit it; the "
                            "page plays no animation (--no-ani leaves it out without this "
                            "warning):",
                    a);
            fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
            out->path[0] = '\0';
            return CLI_OK;
        }
        fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
        return rc == 1 ? CLI_FAILED : CLI_USAGE;
    }
    int ns, no, np;
    dyn_ani_sizes(out->ani, &ns, &no, &np);
    const int fits = ns == m->n_states && no == m->n_outputs &&
                     (from_ode ? (size_t)np * sizeof(double) <= m->par_size : np == m->n_params);
    if (!fits) {
        cli_error("%s: the model file '%s' changed while it was read (its "
                        "quantities are not those of the model that was loaded)",
                out->path, model_spec);
        cli_ani_free(out);
        return CLI_USAGE;
    }
    out->from_ode = from_ode;
    return CLI_OK;
}

void cli_ani_free(cli_ani *a)
{
    dyn_ani_free(a->ani);
    a->ani = NULL;
}

/* The parameter values a frame needs: the model's parameter array of a translated .ode
 * file (parameters, then derived parameters), else the parameters by index. */
static double *frame_params(const cli_ani *a, const dyn_model *m, const void *par)
{
    int np;
    dyn_ani_sizes(a->ani, NULL, NULL, &np);
    double *p = calloc((size_t)np + 1, sizeof *p);
    if (!p)
        return NULL;
    for (int i = 0; i < np; i++)
        p[i] = a->from_ode ? ((const double *)par)[i] : dyn_model_get_param(m, par, i);
    return p;
}

static void write_strings(cli_json *j, const char *text, const double *v, long rows,
                          long stride, int constant)
{
    char buf[DYN_ANI_MAX_TEXT + 64];
    if (constant) {
        cli_json_string(j, dyn_ani_vtext(text, v[0], buf, sizeof buf));
        return;
    }
    cli_json_begin_array(j);
    for (long r = 0; r < rows; r++)
        cli_json_string(j, dyn_ani_vtext(text, v[r * stride], buf, sizeof buf));
    cli_json_end_array(j);
}

int cli_json_ani(cli_json *j, const cli_ani *a, const cli_view *v)
{
    const dyn_ani *ani = a->ani;
    const dyn_model *m = v->run.model;
    const int n = dyn_ani_count(ani), nv = dyn_ani_n_values(ani);
    cli_json_begin_object(j);
    cli_json_key(j, "file");
    const char *base = strrchr(a->path, '/');
    cli_json_string(j, base ? base + 1 : a->path);
    cli_json_key(j, "window");
    double win[4];
    dyn_ani_window(ani, win);
    const int digits = j->digits;
    j->digits = 17;
    cli_json_numbers(j, win, 4, 1);
    j->digits = digits;
    cli_json_key(j, "speed");
    cli_json_number(j, dyn_ani_speed(ani));
    cli_json_key(j, "prims");
    cli_json_begin_array(j);
    for (int i = 0; i < n; i++) {
        const dyn_ani_prim *p = dyn_ani_at(ani, i);
        cli_json_begin_object(j);
        cli_json_key(j, "kind");
        cli_json_string(j, kind_names[p->kind]);
        cli_json_key(j, "line");
        cli_json_number(j, p->line);
        if (p->permanent) {
            cli_json_key(j, "permanent");
            cli_json_bool(j, 1);
        }
        cli_json_key(j, "color");
        if (p->color >= 0)
            cli_json_string(j, dyn_ani_color_name(p->color));
        else
            cli_json_null(j); /* the last value, in [0, 1] */
        if (p->kind == DYN_ANI_SETTEXT) {
            cli_json_key(j, "size");
            cli_json_number(j, p->text_size);
            cli_json_key(j, "font");
            cli_json_string(j, p->text_font ? "symbol" : "roman");
        } else if (p->kind == DYN_ANI_COMET) {
            cli_json_key(j, "type");
            cli_json_number(j, p->comet_type);
            cli_json_key(j, "length");
            cli_json_number(j, p->comet_length);
        } else if (p->kind == DYN_ANI_TEXT || p->kind == DYN_ANI_VTEXT) {
            cli_json_key(j, "text"); /* a vtext's: before its value (a live page's) */
            cli_json_string(j, p->text);
        } else {
            cli_json_key(j, "thickness");
            cli_json_number(j, p->thickness);
        }
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    /* every run's numbers: runs[r][i] = {v: [value or samples, ...], s: vtext's text} */
    cli_json_key(j, "runs");
    cli_json_begin_array(j);
    int rc = 0;
    for (int r = 0; r < v->n_series && !rc; r++) {
        const cli_series *s = &v->series[r];
        const long rows = s->rows;
        double *vals = malloc(((size_t)rows * (size_t)nv + 1) * sizeof *vals);
        double *par = frame_params(a, m, v->run.par);
        if (!vals || !par) {
            free(vals);
            free(par);
            rc = 1;
            break;
        }
        for (long k = 0; k < rows && !rc; k++) {
            const double *row = s->data + k * s->cols;
            dyn_ani_frame fr = {row[0], row + 1, row + 1 + m->n_states, par};
            rc = dyn_ani_eval(ani, &fr, vals + k * nv);
        }
        cli_json_begin_array(j);
        for (int i = 0; i < n && !rc; i++) {
            const dyn_ani_prim *p = dyn_ani_at(ani, i);
            cli_json_begin_object(j);
            cli_json_key(j, "v");
            cli_json_begin_array(j);
            for (int k = 0; k < p->n_values; k++) {
                const double *col = vals + p->offset + k;
                /* a permanent primitive's place is the first frame's; its colour is
                 * evaluated at every frame (XPPAUT's render_ani) */
                const int first = p->permanent && !(p->color < 0 && k == p->n_values - 1);
                if (first || rows < 2 || dyn_ani_value_is_constant(ani, i, k))
                    cli_json_number(j, col[0]);
                else
                    cli_json_numbers(j, col, rows, nv);
            }
            cli_json_end_array(j);
            if (p->kind == DYN_ANI_VTEXT) {
                cli_json_key(j, "s");
                write_strings(j, p->text, vals + p->offset + 2, rows, nv,
                              p->permanent || rows < 2 || dyn_ani_value_is_constant(ani, i, 2));
            }
            cli_json_end_object(j);
        }
        cli_json_end_array(j);
        free(vals);
        free(par);
    }
    cli_json_end_array(j);
    cli_json_end_object(j);
    return rc || j->bad;
}
