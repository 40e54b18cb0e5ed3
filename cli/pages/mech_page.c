/* SPDX-License-Identifier: BSD-3-Clause */
/* The picture of a mechanism file on the page of `dynkit animate` (docs/mechanisms.md,
 * "Geometry to draw"): the file's geometry read by the library (dynkit/mbs.h,
 * dyn_mech_scene_*), evaluated at every sample of every run — each body's mass centre and
 * rotation, each shape's numbers in N — and written into the page's data, one number where
 * a value is the same in every sample, else an array over the samples. web/js/mech.js draws
 * it. Names and colours from the file go out as JSON strings (escape.h). */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dynkit/mbs.h"
#include "pages/pages.h"

static const char *const kind_names[DYN_MECH_SHAPE_COUNT] = {
    [DYN_MECH_BOX] = "box",       [DYN_MECH_CYLINDER] = "cylinder", [DYN_MECH_SPHERE] = "sphere",
    [DYN_MECH_ROD] = "rod",       [DYN_MECH_SPRING] = "spring",     [DYN_MECH_FRAME] = "frame",
    [DYN_MECH_GROUND] = "ground", [DYN_MECH_TRACE] = "trace",       [DYN_MECH_ARROW] = "arrow",
};

static int ends_with_mech(const char *s)
{
    const size_t n = s ? strlen(s) : 0;
    return n > 5 && strcasecmp(s + n - 5, ".mech") == 0;
}

int cli_mech_scene_open(const char *model_spec, const dyn_model *m, dyn_mech_scene **out)
{
    *out = NULL;
    if (!ends_with_mech(model_spec))
        return CLI_OK;
    size_t len = 0;
    char *text = cli_read_model_file(model_spec, &len);
    if (!text)
        return CLI_USAGE;
    dyn_lang_diag diag;
    const int rc = dyn_mech_scene_read(model_spec, text, len, NULL, 0, out, &diag);
    free(text);
    if (rc != 0) {
        char shown[2048];
        fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
        return rc == 1 ? CLI_FAILED : CLI_USAGE;
    }
    if (dyn_mech_scene_n_params(*out) != m->n_params) {
        cli_error("the mechanism file '%s' changed while it was read (its "
                        "parameters are not those of the model that was loaded)",
                model_spec);
        dyn_mech_scene_free(*out);
        *out = NULL;
        return CLI_USAGE;
    }
    return CLI_OK;
}

/* column k of rows x stride values: one number when every row has the same, else all */
static void column(cli_json *j, const double *v, long rows, long stride)
{
    long r = 1;
    while (r < rows && (v[r * stride] == v[0] || (v[r * stride] != v[r * stride] &&
                                                  v[0] != v[0])))
        r++;
    if (r >= rows)
        cli_json_number(j, v[0]);
    else
        cli_json_numbers(j, v, rows, stride);
}

static void write_run(cli_json *j, const dyn_mech_scene *sc, const cli_series *s,
                      const double *pose, const double *vals)
{
    const int nb = dyn_mech_scene_n_bodies(sc), nv = dyn_mech_scene_n_values(sc);
    cli_json_begin_object(j);
    cli_json_key(j, "poses");
    cli_json_begin_array(j);
    for (int b = 0; b < nb; b++) {
        cli_json_begin_array(j);
        const int digits = j->digits;
        for (int k = 0; k < 12; k++) {
            j->digits = k < 3 ? digits : 6; /* the rotation only turns the drawing */
            column(j, pose + 12 * b + k, s->rows, 12L * nb);
        }
        j->digits = digits;
        cli_json_end_array(j);
    }
    cli_json_end_array(j);
    cli_json_key(j, "values");
    cli_json_begin_array(j);
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++) {
        const dyn_mech_shape *sh = dyn_mech_scene_shape(sc, i);
        cli_json_begin_array(j);
        for (int k = 0; k < sh->n_values; k++)
            column(j, vals + sh->offset + k, s->rows, nv);
        cli_json_end_array(j);
    }
    cli_json_end_array(j);
    cli_json_end_object(j);
}

int cli_json_mech(cli_json *j, const dyn_mech_scene *sc, const cli_view *v)
{
    const dyn_model *m = v->run.model;
    const int nb = dyn_mech_scene_n_bodies(sc), nv = dyn_mech_scene_n_values(sc);
    cli_json_begin_object(j);
    cli_json_key(j, "bodies");
    cli_json_begin_array(j);
    for (int b = 0; b < nb; b++) {
        cli_json_begin_object(j);
        cli_json_key(j, "name");
        cli_json_string(j, dyn_mech_scene_body_name(sc, b));
        cli_json_key(j, "point");
        cli_json_bool(j, dyn_mech_scene_body_is_point(sc, b));
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    double g[3];
    dyn_mech_scene_gravity(sc, g);
    cli_json_key(j, "gravity");
    cli_json_numbers(j, g, 3, 1);
    cli_json_key(j, "mass");
    cli_json_number(j, dyn_mech_scene_mass(sc));
    cli_json_key(j, "constraints");
    cli_json_begin_array(j);
    for (int k = 0; k < dyn_mech_scene_n_constraints(sc); k++)
        cli_json_string(j, dyn_mech_scene_constraint(sc, k));
    cli_json_end_array(j);
    cli_json_key(j, "shapes");
    cli_json_begin_array(j);
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++) {
        const dyn_mech_shape *sh = dyn_mech_scene_shape(sc, i);
        cli_json_begin_object(j);
        cli_json_key(j, "kind");
        cli_json_string(j, kind_names[sh->kind]);
        cli_json_key(j, "name");
        cli_json_string(j, sh->name);
        cli_json_key(j, "body");
        cli_json_number(j, sh->body);
        if (sh->kind == DYN_MECH_CYLINDER) {
            cli_json_key(j, "axis");
            cli_json_number(j, sh->axis);
        }
        if (sh->color) {
            cli_json_key(j, "color");
            cli_json_string(j, sh->color);
        }
        if (sh->kind == DYN_MECH_ARROW) {
            cli_json_key(j, "force");
            cli_json_string(j, dyn_mech_scene_constraint(sc, sh->constraint));
        }
        if (sh->line) {
            cli_json_key(j, "line");
            cli_json_number(j, sh->line);
        }
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    /* every run's samples: poses[body][k] and values[shape][k], a number or an array */
    cli_json_key(j, "runs");
    cli_json_begin_array(j);
    const int np = m->n_params;
    double *par = malloc(((size_t)np + 1) * sizeof *par);
    int rc = !par;
    for (int i = 0; i < np && par; i++)
        par[i] = dyn_model_get_param(m, v->run.par, i);
    const int digits = j->digits;
    j->digits = 9; /* positions to a few micrometres of a metre-sized mechanism */
    for (int r = 0; r < v->n_series && !rc; r++) {
        const cli_series *s = &v->series[r];
        double *pose = malloc(((size_t)s->rows * 12 * (size_t)nb + 1) * sizeof *pose);
        double *vals = malloc(((size_t)s->rows * (size_t)nv + 1) * sizeof *vals);
        if (!pose || !vals) {
            free(pose);
            free(vals);
            rc = 1;
            break;
        }
        for (long k = 0; k < s->rows && !rc; k++) {
            const double *row = s->data + k * s->cols;
            rc = dyn_mech_scene_eval(sc, row[0], row + 1, par, pose + k * 12 * nb,
                                     vals + k * nv);
        }
        if (!rc)
            write_run(j, sc, s, pose, vals);
        free(pose);
        free(vals);
    }
    j->digits = digits;
    free(par);
    cli_json_end_array(j);
    cli_json_end_object(j);
    return rc || j->bad;
}

static void json_ints(cli_json *j, const int *v, int n)
{
    cli_json_begin_array(j);
    for (int k = 0; k < n; k++)
        cli_json_number(j, v[k]);
    cli_json_end_array(j);
}

static void json_int(cli_json *j, const char *key, int v)
{
    cli_json_key(j, key);
    cli_json_number(j, v);
}

static void json_int3(cli_json *j, const char *key, const int v[3])
{
    cli_json_key(j, key);
    json_ints(j, v, 3);
}

void cli_json_mech_plan(cli_json *j, const dyn_mech_scene *sc)
{
    cli_json_begin_object(j);
    json_int(j, "inputs", dyn_mech_scene_n_inputs(sc));
    int g[3];
    dyn_mech_scene_gravity_inputs(sc, g);
    json_int3(j, "gravity", g);
    cli_json_key(j, "bodies");
    cli_json_begin_array(j);
    for (int b = 0; b < dyn_mech_scene_n_bodies(sc); b++) {
        dyn_mech_body_plan p;
        dyn_mech_scene_body_plan(sc, b, &p);
        cli_json_begin_object(j);
        json_int(j, "frame", p.frame);
        cli_json_key(j, "quat");
        json_ints(j, p.quat, 4);
        cli_json_key(j, "axis");
        json_ints(j, p.axis, p.nrot);
        cli_json_key(j, "angle");
        json_ints(j, p.angle, p.nrot);
        json_int(j, "joint", p.joint);
        json_int(j, "parent", p.parent);
        json_int3(j, "at", p.at);
        json_int3(j, "jp", p.jp);
        json_int3(j, "shift", p.shift);
        json_int3(j, "pivot", p.pivot);
        json_int3(j, "axisv", p.axisv);
        json_int(j, "slide", p.slide);
        json_int(j, "slide_axis", p.slide_axis);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_key(j, "shapes");
    cli_json_begin_array(j);
    for (int i = 0; i < dyn_mech_scene_n_shapes(sc); i++) {
        dyn_mech_shape_plan p;
        dyn_mech_scene_shape_plan(sc, i, &p);
        cli_json_begin_object(j);
        json_int(j, "body", p.body);
        json_int3(j, "p", p.p);
        json_int(j, "body_b", p.body_b);
        json_int3(j, "p_b", p.p_b);
        json_int3(j, "v", p.v);
        json_int(j, "size", p.size);
        json_int(j, "axis", p.axis);
        json_int3(j, "avec", p.avec);
        json_int(j, "in_body", p.in_body);
        json_int(j, "wheel", p.wheel);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_key(j, "wheels");
    cli_json_begin_array(j);
    for (int w = 0; w < dyn_mech_scene_n_wheels(sc); w++) {
        dyn_mech_wheel_plan p;
        dyn_mech_scene_wheel_plan(sc, w, &p);
        cli_json_begin_object(j);
        json_int(j, "body", p.body);
        json_int(j, "radius", p.radius);
        json_int3(j, "axis", p.axis);
        json_int3(j, "at", p.at);
        cli_json_end_object(j);
    }
    cli_json_end_array(j);
    cli_json_end_object(j);
}
