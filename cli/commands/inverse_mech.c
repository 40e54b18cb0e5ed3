/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit inverse FILE.mech: the forces of prescribed motions (docs/mechanisms.md, "Inverse
 * dynamics"). The mechanism runs with its `prescribe` lines and those of --prescribe
 * COORD=FORMULA (each a `prescribe Q_COORD: COORD = FORMULA` read after the file), from
 * its initial state moved onto the constraints; at each sample the table holds the
 * multipliers: the generalized forces that drive the prescribed coordinates, then the
 * other constraints' forces. With --inputs A,B,... the drives are instead the values of
 * those parameters (the file's inputs, such as the cart's Fx, Fy) that make the prescribe
 * multipliers zero (dyn_zero_outputs), the other constraints' forces recomputed with them;
 * a table that `dynkit run --forces` reads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dynkit/analysis.h"
#include "dynkit/lang.h"
#include "commands/inverse_mech.h"
#include "models/lin_constrained.h"
#include "util/out_file.h"
#include "run/run_table.h"

enum { MAX_DRIVES = 64 };

typedef struct inv {
    const cli_run *run;
    const dyn_model *m;
    void *par2;         /* the parameters with the inputs found */
    int nd, no;         /* drives, other constraints */
    int drive_out[MAX_DRIVES]; /* the prescribe multipliers among the outputs */
    int other_out[MAX_DRIVES];
    int input_par[MAX_DRIVES]; /* --inputs: their parameters; else -1 */
    int with_inputs;
    double *rows;       /* (count x (1 + nd + no)) */
    long count, cap;
    double *out, *f1, *f2;
    double worst;       /* largest |prescribe multiplier| left by the inputs */
    char err[512];
} inv;

static int prescribed_names(const dyn_model *cm, const dyn_model *m, inv *v)
{
    v->nd = v->no = 0;
    for (int i = 0; i < cm->n_outputs; i++) {
        const char *u = cm->outputs[i].unit, *name = cm->outputs[i].name;
        const int drive = u && strcmp(u, "prescribed") == 0;
        const int other = u && (strcmp(u, "holonomic") == 0 || strcmp(u, "speeds") == 0);
        if (!drive && !other)
            continue;
        const size_t len = drive ? strcspn(name, ":") : strlen(name);
        int k = -1;
        for (int j = 0; j < m->n_outputs && k < 0; j++)
            if (strlen(m->outputs[j].name) == len && strncmp(m->outputs[j].name, name, len) == 0)
                k = j;
        if (k < 0 || v->nd >= MAX_DRIVES || v->no >= MAX_DRIVES)
            return -1;
        if (drive)
            v->drive_out[v->nd++] = k;
        else
            v->other_out[v->no++] = k;
    }
    /* the other constraints are the ones that are not prescribed */
    int n = 0;
    for (int a = 0; a < v->no; a++) {
        int is_drive = 0;
        for (int b = 0; b < v->nd; b++)
            is_drive |= v->other_out[a] == v->drive_out[b];
        if (!is_drive)
            v->other_out[n++] = v->other_out[a];
    }
    v->no = n;
    return 0;
}

static int sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    inv *v = ctx;
    const dyn_model *m = v->m;
    const int cols = 1 + v->nd + v->no;
    if (v->count == v->cap) {
        const long cap = v->cap ? 2 * v->cap : 1024;
        double *r = realloc(v->rows, (size_t)cap * cols * sizeof *r);
        if (!r) {
            snprintf(v->err, sizeof v->err, "out of memory");
            return 1;
        }
        v->rows = r;
        v->cap = cap;
    }
    double *row = v->rows + v->count * cols;
    row[0] = t;
    void *par = v->run->par;
    if (v->with_inputs) {
        par = v->par2;
        double res = 0.0;
        int bad = -1;
        char err[256];
        if (dyn_zero_outputs(m, par, t, y, v->nd, v->input_par, v->drive_out, &res, &bad, err,
                             sizeof err)) {
            snprintf(v->err, sizeof v->err, "--inputs at t = %s: %s%s%s", CLI_NUM(t), err,
                     bad >= 0 ? ": " : "", bad >= 0 ? m->params[v->input_par[bad]].name : "");
            return 1;
        }
        v->worst = fmax(v->worst, res);
        /* the inputs alone must give the motion the prescribed run followed */
        const int N = m->n_states;
        if (m->rhs(t, y, v->f1, v->run->par) || m->rhs(t, y, v->f2, par)) {
            snprintf(v->err, sizeof v->err, "the right-hand side failed at t = %s", CLI_NUM(t));
            return 1;
        }
        for (int i = 0; i < N; i++)
            if (fabs(v->f1[i] - v->f2[i]) > 1e-6 * fmax(1.0, fabs(v->f1[i]))) {
                snprintf(v->err, sizeof v->err,
                         "--inputs: at t = %s the inputs found move %s otherwise than the "
                         "prescribed run (rate %s against %s): they act on a coordinate that "
                         "is not prescribed; prescribe it too, or leave out --inputs for the "
                         "generalized forces",
                         CLI_NUM(t), m->states[i].name, CLI_NUM(v->f2[i]), CLI_NUM(v->f1[i]));
                return 1;
            }
    }
    if (m->compute_outputs(t, y, par, v->out)) {
        snprintf(v->err, sizeof v->err, "the multipliers failed at t = %s", CLI_NUM(t));
        return 1;
    }
    for (int i = 0; i < v->nd; i++)
        row[1 + i] = v->with_inputs ? dyn_model_get_param(m, par, v->input_par[i])
                                    : v->out[v->drive_out[i]];
    for (int i = 0; i < v->no; i++)
        row[1 + v->nd + i] = v->out[v->other_out[i]];
    v->count++;
    return 0;
}

/* --prescribe COORD=FORMULA into the line "prescribe Q_COORD: COORD = FORMULA" */
static int add_prescribe(const char *text, char **extra, size_t *len)
{
    const char *eq = strchr(text, '=');
    size_t nl = eq ? (size_t)(eq - text) : 0;
    while (nl && text[nl - 1] == ' ')
        nl--;
    int ok = eq && nl > 0 && strchr(text, '\n') == NULL && strchr(text, '#') == NULL;
    for (size_t i = 0; i < nl && ok; i++)
        ok = (text[i] >= 'a' && text[i] <= 'z') || (text[i] >= 'A' && text[i] <= 'Z') ||
             text[i] == '_' || (i > 0 && text[i] >= '0' && text[i] <= '9');
    if (!ok || !eq[1])
        return cli_usage_error("inverse", "--prescribe '%s' is not accepted: give "
                               "COORDINATE=FORMULA, a formula of t and the parameters "
                               "(e.g. --prescribe 'theta=pi/8*sin(4*pi*t)')", text);
    const size_t add = 2 * nl + strlen(eq + 1) + 32;
    char *e = realloc(*extra, *len + add);
    if (!e) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    *len += (size_t)snprintf(e + *len, add, "prescribe Q_%.*s: %.*s = %s\n", (int)nl, text,
                             (int)nl, text, eq + 1);
    *extra = e;
    return CLI_OK;
}

static int write_table(const inv *v, const char *spec)
{
    const cli_run *run = v->run;
    const dyn_model *m = v->m;
    const int cols = 1 + v->nd + v->no;
    cli_format format;
    if (cli_run_format(run, &format) != CLI_OK)
        return CLI_USAGE;
    const char *names[1 + 2 * MAX_DRIVES], *units[1 + 2 * MAX_DRIVES];
    names[0] = "t";
    units[0] = "s";
    for (int i = 0; i < v->nd; i++) {
        const dyn_var *o = &m->outputs[v->drive_out[i]];
        const dyn_param *p = v->with_inputs ? &m->params[v->input_par[i]] : NULL;
        names[1 + i] = p ? p->name : o->name;
        units[1 + i] = (p ? p->unit : o->unit) ? (p ? p->unit : o->unit) : "";
    }
    for (int i = 0; i < v->no; i++) {
        const dyn_var *o = &m->outputs[v->other_out[i]];
        names[1 + v->nd + i] = o->name;
        units[1 + v->nd + i] = o->unit ? o->unit : "";
    }
    const char *path = run->output_path && strcmp(run->output_path, "-") ? run->output_path
                                                                         : NULL;
    cli_out outf;
    const int open_rc = cli_out_open(&outf, "--output", path);
    if (open_rc != CLI_OK)
        return open_rc;
    const cli_table_info info = {.model = m->name,
                                 .method = run->method->name,
                                 .step = run->step,
                                 .rtol = dyn_method_is_adaptive(run->method) ? run->rtol : NAN,
                                 .atol = dyn_method_is_adaptive(run->method) ? run->atol : NAN,
                                 .t0 = run->t0,
                                 .t1 = run->t1,
                                 .cols = cols,
                                 .n_y = v->nd,
                                 .y_name = "forces",
                                 .names = names,
                                 .units = units,
                                 .header = run->header};
    char ferr[512] = "";
    cli_table *tab = cli_table_open(outf.f, format, &info, ferr, sizeof ferr);
    int bad = !tab;
    for (long k = 0; k < v->count && !bad; k++) {
        const double *row = v->rows + k * cols;
        bad = cli_table_row(tab, row[0], row + 1, v->nd, row + 1 + v->nd, v->no) != 0;
    }
    bad |= tab && cli_table_finish(tab, ferr, sizeof ferr) != 0;
    cli_table_free(tab);
    bad |= fflush(outf.f) != 0 || ferror(outf.f);
    if (outf.f != stdout)
        bad |= cli_out_close(&outf, !bad) != CLI_OK;
    else
        clearerr(stdout);
    if (bad) {
        cli_error("writing the forces of %s failed%s%s", spec,
                ferr[0] ? ": " : "", ferr);
        return CLI_FAILED;
    }
    return CLI_OK;
}

int cli_inverse_mech(int argc, char **argv)
{
    const char *spec = argv[0];
    char **pass = calloc((size_t)argc + 2, sizeof *pass);
    char *extra = NULL;
    size_t extra_len = 0;
    const char *inputs = NULL;
    int n_pass = 0, rc = pass ? CLI_OK : CLI_FAILED;
    if (pass)
        pass[n_pass++] = argv[0];
    for (int i = 1; i < argc && rc == CLI_OK; i++) {
        const char *v = NULL;
        int r;
        if ((r = cli_option(argc, argv, &i, "prescribe", &v)) != 0)
            rc = r < 0 ? cli_usage_error("inverse", "option --prescribe needs "
                                                    "COORDINATE=FORMULA")
                       : add_prescribe(v, &extra, &extra_len);
        else if ((r = cli_option(argc, argv, &i, "inputs", &v)) != 0)
            rc = r < 0 ? cli_usage_error("inverse", "option --inputs needs a list of "
                                                    "parameters, e.g. Fx,Fy")
                       : ((inputs = v), CLI_OK);
        else if (cli_flag(argv[i], "forces"))
            rc = cli_usage_error("inverse", "--forces is not accepted: the inverse dynamics "
                                 "finds the forces (give --inputs NAMES for the inputs)");
        else
            pass[n_pass++] = argv[i];
    }
    if (rc != CLI_OK) {
        free(pass);
        free(extra);
        return rc;
    }
    pass[n_pass++] = "--project-init";
    cli_model_set_mech_extra(extra);
    cli_run run;
    rc = cli_run_parse("inverse", n_pass, pass, &run);
    cli_lin_constraints cc = {0};
    if (rc == CLI_OK)
        rc = cli_lin_constraints_open(spec, run.model, &cc);
    cli_model_set_mech_extra(NULL);
    free(pass);
    inv v;
    memset(&v, 0, sizeof v);
    v.run = &run;
    v.m = run.model;
    if (rc == CLI_OK && (!cc.loaded || prescribed_names(cc.jm.model, run.model, &v) != 0))
        rc = cli_usage_error("inverse", "the constraints of %s do not match its model", spec);
    if (rc == CLI_OK && v.nd == 0)
        rc = cli_usage_error("inverse", "%s prescribes no motion: give --prescribe "
                             "COORDINATE=FORMULA (a formula of t), or a line 'prescribe "
                             "NAME: COORDINATE = FORMULA' in the file", spec);
    if (rc == CLI_OK && inputs) {
        v.with_inputs = 1;
        int k = 0;
        for (const char *s = inputs; rc == CLI_OK && *s;) {
            const size_t len = strcspn(s, ",");
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(len < 127 ? len : 127), s);
            const int p = dyn_model_param_index(run.model, name);
            if (p < 0)
                rc = cli_usage_error("inverse", "--inputs: '%s' is not a parameter of %s "
                                     "(see 'dynkit info %s')", name, spec, spec);
            else if (k >= v.nd)
                rc = cli_usage_error("inverse", "--inputs names more parameters than the %d "
                                     "prescribed motion%s: give one for each", v.nd,
                                     v.nd == 1 ? "" : "s");
            else
                v.input_par[k++] = p;
            s += len + (s[len] == ',');
        }
        if (rc == CLI_OK && k != v.nd)
            rc = cli_usage_error("inverse", "--inputs names %d parameter%s for %d prescribed "
                                 "motions: give one for each", k, k == 1 ? "" : "s", v.nd);
    }
    if (rc == CLI_OK) {
        const size_t no = (size_t)run.model->n_outputs + 1, N = (size_t)run.model->n_states;
        v.par2 = malloc(run.model->par_size);
        v.out = malloc((no + 2 * N) * sizeof *v.out);
        if (!v.par2 || !v.out) {
            cli_error("out of memory");
            rc = CLI_FAILED;
        } else {
            memcpy(v.par2, run.par, run.model->par_size);
            v.f1 = v.out + no;
            v.f2 = v.f1 + N;
        }
    }
    if (rc == CLI_OK) {
        double *y = malloc((size_t)run.model->n_states * sizeof *y);
        dyn_result res;
        memset(&res, 0, sizeof res);
        const int st = y ? cli_run_solve(&run, 1, sample, &v, NULL, NULL, NULL, NULL, y, &res)
                         : -1;
        free(y);
        if (v.err[0]) {
            cli_error("inverse %s: %s", spec, v.err);
            rc = CLI_FAILED;
        } else if (st != 0) {
            cli_error("inverse %s: the prescribed run failed: %s", spec,
                    st < 0 ? "out of memory" : res.message);
            rc = CLI_FAILED;
        }
    }
    if (rc == CLI_OK)
        rc = write_table(&v, spec);
    if (rc == CLI_OK && !run.quiet && v.with_inputs)
        cli_stderr("dynkit: inverse %s: %ld samples; the inputs leave the prescribed "
                   "motions' forces within %s\n",
                   spec, v.count, CLI_NUM(v.worst));
    cli_lin_constraints_close(&cc);
    free(v.rows);
    free(v.out);
    free(v.par2);
    free(extra);
    if (run.model)
        cli_run_free(&run);
    return rc;
}
