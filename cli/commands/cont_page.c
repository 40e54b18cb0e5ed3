/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_page.c — the page of dynkit continue's diagram (cont_output.h): the SVG of
 * cont_svg.c with a dot on each periodic point whose orbit the page holds, and those orbits
 * (each at the nodes of its collocation mesh: the time over the period and the states,
 * AUTO's representation) in the page's data, shown by web/js/diagram.js when a dot is
 * clicked. Every orbit while they fit in CONT_PAGE_NUMBERS numbers; else the labelled
 * points' and every k-th other point's, k the smallest that fits. The page is the
 * self-contained one of cli/pages/html_page.c. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cont_output.h"
#include "pages/pages.h"

/* 1 when point k of b holds an orbit */
static int has_orbit(const dyn_branch *b, long k)
{
    return b->orbit && b->orbit_nodes > 0 &&
           isfinite(b->orbit[(size_t)k * (size_t)b->orbit_nodes * (size_t)(1 + b->n)]);
}

/* the points kept with every stride-th unlabelled point of each branch (labelled ones
 * always); the numbers they take */
static long pick(const dyn_diagram *d, long stride, cont_orbit_ref *refs, long *count)
{
    long numbers = 0, c = 0;
    for (int bi = 0; bi < d->count; bi++) {
        const dyn_branch *b = &d->branches[bi];
        long seen = 0;
        for (long k = 0; k < b->count; k++) {
            if (!has_orbit(b, k))
                continue;
            const int keep = b->pts[k].label != DYN_LABEL_NONE || seen % stride == 0;
            seen++;
            if (!keep)
                continue;
            if (refs)
                refs[c] = (cont_orbit_ref){bi, k};
            c++;
            numbers += (long)b->orbit_nodes * (1 + b->n) + 2 * b->n_eig + 4;
        }
    }
    *count = c;
    return numbers;
}

int cont_orbits_pick(const dyn_diagram *d, long budget, cont_orbit_set *out)
{
    memset(out, 0, sizeof *out);
    long total = 0;
    pick(d, 1, NULL, &total);
    out->computed = total;
    if (total == 0)
        return 0;
    long stride = 1, count = 0;
    while (pick(d, stride, NULL, &count) > budget && stride < total)
        stride++;
    out->refs = malloc((size_t)count * sizeof *out->refs);
    if (!out->refs)
        return -1;
    pick(d, stride, out->refs, &out->count);
    return 0;
}

typedef struct page_ctx {
    const cont_view *v;
    const cont_orbit_set *orbits;
    const char *svg;
    const char *title;
} page_ctx;

static void var(cli_json *j, const char *name, const char *unit)
{
    cli_json_begin_object(j);
    cli_json_key(j, "name");
    cli_json_string(j, name);
    cli_json_key(j, "unit");
    cli_json_string(j, unit ? unit : "");
    cli_json_end_object(j);
}

static void orbit_json(cli_json *j, const dyn_diagram *d, const cont_orbit_ref *r)
{
    const dyn_branch *b = &d->branches[r->branch];
    const dyn_branch_point *p = &b->pts[r->point];
    const size_t cols = (size_t)(1 + b->n);
    const double *o = b->orbit + (size_t)r->point * (size_t)b->orbit_nodes * cols;
    cli_json_begin_object(j);
    cli_json_key(j, "branch");
    cli_json_number(j, b->id);
    cli_json_key(j, "point");
    cli_json_number(j, (double)(r->point + 1));
    cli_json_key(j, "label");
    cli_json_string(j, dyn_cont_label_name(p->label));
    const int digits = j->digits;
    j->digits = 17; /* the parameter and the period exactly */
    cli_json_key(j, "par");
    cli_json_number(j, p->par[0]);
    cli_json_key(j, "period");
    cli_json_number(j, p->period);
    j->digits = digits;
    cli_json_key(j, "stable");
    if (p->stable < 0)
        cli_json_null(j);
    else
        cli_json_bool(j, p->stable);
    cli_json_key(j, "multipliers");
    cli_json_begin_array(j);
    const double *e = b->eig + (size_t)r->point * 2 * (size_t)b->n_eig;
    for (int i = 0; i < b->n_eig; i++)
        cli_json_numbers(j, e + 2 * i, 2, 1);
    cli_json_end_array(j);
    j->digits = 5; /* the orbit to be drawn: 5 significant digits, a third of exact ones */
    cli_json_key(j, "s");
    cli_json_numbers(j, o, b->orbit_nodes, (long)cols);
    cli_json_key(j, "u");
    cli_json_begin_array(j);
    for (int i = 0; i < b->n; i++)
        cli_json_numbers(j, o + 1 + i, b->orbit_nodes, (long)cols);
    cli_json_end_array(j);
    j->digits = digits;
    cli_json_end_object(j);
}

static int page_data(cli_json *j, void *ctx)
{
    const page_ctx *pc = ctx;
    const cont_view *v = pc->v;
    const dyn_model *m = v->m;
    const dyn_cont_opts *o = &v->s->opts;
    cli_json_begin_object(j);
    cli_json_key(j, "kind");
    cli_json_string(j, "diagram");
    cli_json_key(j, "title");
    cli_json_string(j, pc->title);
    cli_json_key(j, "model");
    cli_json_string(j, m->name);
    cli_json_key(j, "model_title");
    cli_json_string(j, m->title ? m->title : "");
    cli_json_key(j, "parameter");
    var(j, m->params[o->ip].name, m->params[o->ip].unit);
    cli_json_key(j, "y");
    cli_json_string(j, m->states[v->iy].name);
    cli_json_key(j, "time_unit");
    cli_json_string(j, cli_time_unit(m));
    cli_json_key(j, "states");
    cli_json_begin_array(j);
    for (int i = 0; i < m->n_states; i++)
        var(j, m->states[i].name, m->states[i].unit);
    cli_json_end_array(j);
    cli_json_key(j, "branches");
    cli_json_begin_array(j);
    for (int bi = 0; bi < v->d->count; bi++) {
        const dyn_branch *b = &v->d->branches[bi];
        cli_json_begin_object(j);
        cli_json_key(j, "branch");
        cli_json_number(j, b->id);
        cli_json_key(j, "kind");
        cli_json_string(j, dyn_branch_kind_name(b->kind));
        cli_json_key(j, "points");
        cli_json_number(j, (double)b->count);
        cli_json_key(j, "stop");
        cli_json_string(j, b->stop);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_key(j, "orbits_computed");
    cli_json_number(j, (double)pc->orbits->computed);
    cli_json_key(j, "orbits");
    cli_json_begin_array(j);
    for (long q = 0; q < pc->orbits->count; q++)
        orbit_json(j, v->d, &pc->orbits->refs[q]);
    cli_json_end_array(j);
    cli_json_key(j, "svg");
    cli_json_string(j, pc->svg);
    cli_json_end_object(j);
    return j->bad;
}

int cont_write_page(FILE *f, const cont_view *v)
{
    cont_orbit_set orbits;
    if (cont_orbits_pick(v->d, CONT_PAGE_NUMBERS, &orbits)) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    char *svg = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&svg, &len);
    int rc = mem && cont_write_svg(mem, v, &orbits) == 0 ? CLI_OK : CLI_FAILED;
    if (mem)
        fclose(mem);
    if (rc != CLI_OK)
        cli_error("out of memory");
    char title[512];
    snprintf(title, sizeof title, "dynkit continue %s: %s", v->m->name,
             v->m->params[v->s->opts.ip].name);
    if (rc == CLI_OK) {
        page_ctx pc = {v, &orbits, svg, title};
        rc = cli_html_page_write(f, title, "diagram.html", page_data, &pc);
    }
    free(svg);
    free(orbits.refs);
    return rc;
}
