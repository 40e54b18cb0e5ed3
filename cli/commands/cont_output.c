/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_output.c — dynkit continue's tables (cont_output.h): a CSV row per point (branch,
 * kind, label, the parameters, the states, their minima, period, stable), the same as JSON
 * with each point's eigenvalues or Floquet multipliers, and a text summary of the branches
 * and their special points. Numbers are the shortest decimals that read back exactly. */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "cont_output.h"
#include "pages/pages.h"
#include "util/out_file.h"

static double par_value(const cont_view *v, const dyn_branch *b, long k, int q)
{
    const double x = b->pts[k].par[q];
    if (q == 1 && b->n_par == 1 && v->s->opts.ip2 >= 0)
        return dyn_model_get_param(v->m, v->par, v->s->opts.ip2);
    return x;
}

static void num(FILE *f, double x)
{
    if (isfinite(x))
        fputs(CLI_NUM(x), f);
}

void cont_write_csv(FILE *f, const cont_view *v)
{
    const dyn_model *m = v->m;
    const int two = v->s->opts.ip2 >= 0;
    fprintf(f, "branch,kind,label,%s", m->params[v->s->opts.ip].name);
    if (two)
        fprintf(f, ",%s", m->params[v->s->opts.ip2].name);
    for (int i = 0; i < m->n_states; i++)
        fprintf(f, ",%s", m->states[i].name);
    for (int i = 0; i < m->n_states; i++)
        fprintf(f, ",min_%s", m->states[i].name);
    fputs(",period,stable\n", f);
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        for (long k = 0; k < b->count; k++) {
            const dyn_branch_point *p = &b->pts[k];
            fprintf(f, "%d,%s,%s,", b->id, dyn_branch_kind_name(b->kind),
                    dyn_cont_label_name(p->label));
            num(f, par_value(v, b, k, 0));
            if (two) {
                fputc(',', f);
                num(f, par_value(v, b, k, 1));
            }
            const double *x = b->x + (size_t)k * (size_t)b->n;
            const double *xm = b->xmin ? b->xmin + (size_t)k * (size_t)b->n : x;
            for (int i = 0; i < b->n; i++) {
                fputc(',', f);
                num(f, x[i]);
            }
            for (int i = 0; i < b->n; i++) {
                fputc(',', f);
                num(f, xm[i]);
            }
            fputc(',', f);
            num(f, p->period);
            fprintf(f, ",%s\n", p->stable < 0 ? "" : p->stable ? "1" : "0");
        }
    }
}

static void json_states(cli_json *j, const dyn_model *m, const double *x, int n)
{
    cli_json_begin_object(j);
    for (int i = 0; i < n; i++) {
        cli_json_key(j, m->states[i].name);
        cli_json_number(j, x[i]);
    }
    cli_json_end_object(j);
}

void cont_write_json(FILE *f, const cont_view *v)
{
    const dyn_model *m = v->m;
    const dyn_cont_opts *o = &v->s->opts;
    cli_json j;
    cli_json_init(&j, f, 17);
    cli_json_begin_object(&j);
    cli_json_key(&j, "model");
    cli_json_string(&j, m->name);
    cli_json_key(&j, "map"); /* true: fixed points of a map, with their multipliers */
    cli_json_bool(&j, o->map);
    cli_json_key(&j, "parameters");
    cli_json_begin_array(&j);
    cli_json_string(&j, m->params[o->ip].name);
    if (o->ip2 >= 0)
        cli_json_string(&j, m->params[o->ip2].name);
    cli_json_end_array(&j);
    cli_json_key(&j, "settings");
    cli_json_begin_object(&j);
    const char *names[] = {"ds", "dsmin", "dsmax", "parmin", "parmax"};
    const double vals[] = {o->ds, o->dsmin, o->dsmax, o->parmin, o->parmax};
    for (int k = 0; k < 5; k++) {
        cli_json_key(&j, names[k]);
        cli_json_number(&j, vals[k]);
    }
    cli_json_key(&j, "nmax");
    cli_json_number(&j, (double)o->nmax);
    cli_json_key(&j, "ntst");
    cli_json_number(&j, o->ntst);
    cli_json_key(&j, "ncol");
    cli_json_number(&j, o->ncol);
    cli_json_end_object(&j);
    cli_json_key(&j, "branches");
    cli_json_begin_array(&j);
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        cli_json_begin_object(&j);
        cli_json_key(&j, "branch");
        cli_json_number(&j, b->id);
        cli_json_key(&j, "kind");
        cli_json_string(&j, dyn_branch_kind_name(b->kind));
        cli_json_key(&j, "parent");
        if (b->parent > 0)
            cli_json_number(&j, b->parent);
        else
            cli_json_null(&j);
        cli_json_key(&j, "parent_point");
        if (b->parent_point >= 0)
            cli_json_number(&j, (double)b->parent_point);
        else
            cli_json_null(&j);
        cli_json_key(&j, "stop");
        cli_json_string(&j, b->stop);
        cli_json_key(&j, "points");
        cli_json_begin_array(&j);
        for (long k = 0; k < b->count; k++) {
            const dyn_branch_point *p = &b->pts[k];
            cli_json_begin_object(&j);
            cli_json_key(&j, "label");
            cli_json_string(&j, dyn_cont_label_name(p->label));
            for (int q = 0; q < (o->ip2 >= 0 ? 2 : 1); q++) {
                cli_json_key(&j, m->params[q == 0 ? o->ip : o->ip2].name);
                cli_json_number(&j, par_value(v, b, k, q));
            }
            const double *x = b->x + (size_t)k * (size_t)b->n;
            if (b->xmin) {
                cli_json_key(&j, "max");
                json_states(&j, m, x, b->n);
                cli_json_key(&j, "min");
                json_states(&j, m, b->xmin + (size_t)k * (size_t)b->n, b->n);
            } else {
                cli_json_key(&j, "state");
                json_states(&j, m, x, b->n);
            }
            cli_json_key(&j, "period");
            cli_json_number(&j, p->period);
            cli_json_key(&j, "stable");
            if (p->stable < 0)
                cli_json_null(&j);
            else
                cli_json_bool(&j, p->stable);
            cli_json_key(&j, b->kind == DYN_BRANCH_PERIODIC || o->map ? "multipliers"
                                                                       : "eigenvalues");
            cli_json_begin_array(&j);
            const double *e = b->eig + (size_t)k * 2 * (size_t)b->n_eig;
            for (int i = 0; i < b->n_eig; i++)
                cli_json_numbers(&j, e + 2 * i, 2, 1);
            cli_json_end_array(&j);
            if (isfinite(p->l1)) {
                cli_json_key(&j, "l1");
                cli_json_number(&j, p->l1);
            }
            if (isfinite(p->omega)) {
                cli_json_key(&j, b->kind == DYN_BRANCH_HOPF ? "omega2"
                                 : o->map                  ? "angle"
                                                           : "omega");
                cli_json_number(&j, p->omega);
            }
            cli_json_end_object(&j);
        }
        cli_json_end_array(&j);
        cli_json_end_object(&j);
    }
    cli_json_end_array(&j);
    cli_json_end_object(&j);
    fputc('\n', f);
}

/* The Hopf point's kind by the sign of l1; an l1 of zero to its accuracy (the Richardson
 * differences give it to about 1e-13) leaves the kind to higher-order terms, as van der
 * Pol's centre at mu = 0 does. */
static const char *hopf_kind(double l1)
{
    if (fabs(l1) <= 1e-10)
        return "degenerate: l1 is zero to its accuracy";
    return l1 < 0.0 ? "supercritical" : "subcritical";
}

/* "stable", "unstable", or "marginal" for an equilibrium or steady motion that is not
 * asymptotically stable only because its rightmost eigenvalues lie on the imaginary axis
 * (within 1e-8 of the largest modulus, as `linearize` allows 1e-8 of the matrix's norm): a Hopf point, a
 * fold, a conservative system's centre; for a periodic orbit, because its largest
 * non-trivial Floquet multiplier lies on the unit circle within 1e-8 (an orbit of a linear
 * centre's family) or it is a located LPC, PD, TR or BP (whose computed multiplier is on the
 * circle only to its accuracy). The CSV's `stable` column stays 0 there. */
static const char *stability_word(const dyn_branch *b, long k, int map)
{
    const dyn_branch_point *p = &b->pts[k];
    if (p->stable)
        return "stable";
    if (b->n_eig <= 0)
        return "unstable";
    const double *e = b->eig + (size_t)k * 2u * (size_t)b->n_eig;
    if (map) { /* a map's fixed point: its multipliers */
        double mod_max = 0.0;
        for (int i = 0; i < b->n_eig; i++)
            mod_max = fmax(mod_max, hypot(e[2 * i], e[2 * i + 1]));
        return isfinite(mod_max) && mod_max <= 1.0 + 1e-8 ? "marginal" : "unstable";
    }
    if (b->kind == DYN_BRANCH_PERIODIC) { /* the trivial multiplier first (colloc_po.c) */
        if (p->label == DYN_LABEL_LPC || p->label == DYN_LABEL_PD || p->label == DYN_LABEL_TR ||
            p->label == DYN_LABEL_BP)
            return "marginal"; /* located there: a multiplier on the circle to its accuracy */
        double mod_max = 0.0;
        for (int i = 1; i < b->n_eig; i++)
            mod_max = fmax(mod_max, hypot(e[2 * i], e[2 * i + 1]));
        return isfinite(mod_max) && mod_max <= 1.0 + 1e-8 ? "marginal" : "unstable";
    }
    if (b->kind != DYN_BRANCH_EQUILIBRIUM && b->kind != DYN_BRANCH_STEADY)
        return "unstable";
    double re_max = -INFINITY, mod_max = 0.0;
    for (int i = 0; i < b->n_eig; i++) {
        if (!isfinite(e[2 * i]) || !isfinite(e[2 * i + 1]))
            return "unstable";
        re_max = fmax(re_max, e[2 * i]);
        mod_max = fmax(mod_max, hypot(e[2 * i], e[2 * i + 1]));
    }
    return re_max <= 1e-8 * mod_max ? "marginal" : "unstable";
}

/* a periodic branch of several points along which the parameter does not move (within
 * 1e-9 relative): the branch is vertical, its folds are not labelled (DYN_CONT_FOLD_NOISE) */
static int branch_is_vertical(const dyn_branch *b)
{
    if (b->kind != DYN_BRANCH_PERIODIC || b->count < 3)
        return 0;
    const double p0 = b->pts[0].par[0];
    for (long k = 1; k < b->count; k++)
        if (!(fabs(b->pts[k].par[0] - p0) <= 1e-9 * fmax(1.0, fabs(p0))))
            return 0;
    return 1;
}

void cont_write_text(FILE *f, const cont_view *v)
{
    const dyn_model *m = v->m;
    const dyn_cont_opts *o = &v->s->opts;
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        fprintf(f, "branch %d: %s", b->id, dyn_branch_kind_name(b->kind));
        if (b->parent > 0)
            fprintf(f, " from point %ld of branch %d", b->parent_point + 1, b->parent);
        fprintf(f, ", %ld points; stopped: %s\n", b->count, b->stop);
        if (branch_is_vertical(b))
            fprintf(f, "  note: %s stays at %s along this branch (within 1e-9): a family of "
                    "solutions at one parameter value, as from a linear centre's Hopf point\n",
                    m->params[o->ip].name, CLI_NUM(b->pts[0].par[0]));
        for (long k = 0; k < b->count; k++) {
            const dyn_branch_point *p = &b->pts[k];
            if (p->label == DYN_LABEL_NONE)
                continue;
            fprintf(f, "  %-3s %s = %s", dyn_cont_label_name(p->label), m->params[o->ip].name,
                    CLI_NUM(p->par[0]));
            if (b->n_par == 2)
                fprintf(f, ", %s = %s", m->params[o->ip2].name, CLI_NUM(p->par[1]));
            const double *x = b->x + (size_t)k * (size_t)b->n;
            for (int i = 0; i < b->n && i < 6; i++)
                fprintf(f, "%s%s = %s", i ? ", " : "  ", m->states[i].name, CLI_NUM(x[i]));
            if (b->n > 6)
                fputs(", ...", f);
            if (isfinite(p->period))
                fprintf(f, "  period = %s", CLI_NUM(p->period));
            if ((p->label == DYN_LABEL_HB || p->label == DYN_LABEL_HH) &&
                (b->kind == DYN_BRANCH_EQUILIBRIUM || b->kind == DYN_BRANCH_STEADY)) {
                fprintf(f, "  omega = %s", CLI_NUM(p->omega));
                if (isfinite(p->l1))
                    fprintf(f, ", l1 = %s (%s)", CLI_NUM(p->l1), hopf_kind(p->l1));
            }
            if (p->label == DYN_LABEL_TR && o->map && isfinite(p->omega))
                fprintf(f, "  angle = %s (Neimark-Sacker)", CLI_NUM(p->omega));
            if (p->stable >= 0)
                fprintf(f, "  %s", stability_word(b, k, o->map));
            fputc('\n', f);
        }
    }
}

enum { OUT_CSV, OUT_JSON, OUT_SVG, OUT_HTML };

static int write_to(const char *what, const char *path, const cont_view *v, int kind)
{
    cli_out out;
    int rc = cli_out_open(&out, what, path);
    if (rc != CLI_OK)
        return rc;
    int bad = 0;
    if (kind == OUT_CSV)
        cont_write_csv(out.f, v);
    else if (kind == OUT_JSON)
        cont_write_json(out.f, v);
    else if (kind == OUT_SVG)
        bad = cont_write_svg(out.f, v, NULL);
    else
        bad = cont_write_page(out.f, v) != CLI_OK;
    bad |= fflush(out.f) != 0 || ferror(out.f);
    if (out.f != stdout)
        return cli_out_close(&out, !bad);
    return bad ? CLI_FAILED : CLI_OK;
}

static int kind_of(const char *path)
{
    if (cli_has_extension(path, ".json"))
        return OUT_JSON;
    if (cli_has_extension(path, ".svg"))
        return OUT_SVG;
    if (cli_has_extension(path, ".html") || cli_has_extension(path, ".htm"))
        return OUT_HTML;
    return OUT_CSV;
}

int cont_write_outputs(const cont_view *v, const char *output, int json, const char *svg,
                       const char *html)
{
    int rc = CLI_OK;
    /* the summary only when nothing else is asked for, as the other commands print their
     * table only without --output */
    if (json)
        rc = write_to("--json", NULL, v, OUT_JSON);
    else if (!output && !svg && !html) {
        cont_write_text(stdout, v);
        if (fflush(stdout))
            rc = CLI_FAILED;
    }
    if (rc == CLI_OK && output)
        rc = write_to("--output", output, v, kind_of(output));
    if (rc == CLI_OK && svg)
        rc = write_to("--svg", svg, v, OUT_SVG);
    if (rc == CLI_OK && html)
        rc = write_to("--html", html, v, OUT_HTML);
    return rc;
}
