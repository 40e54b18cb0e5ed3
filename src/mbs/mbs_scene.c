/* SPDX-License-Identifier: BSD-3-Clause */
/* The picture of a mechanism (dynkit/mbs.h, dyn_mech_scene_*): the file read as for its
 * model (mbs_read, nothing derived), its geometry statements (mbs_geom.c) or, when it has
 * none, a default drawing, and the springs; then, for each frame of a run, every body's
 * pose and every shape's numbers in N, evaluated by walking the formulas (frame_eval.c,
 * the compiled model's meaning). The rotations are those of docs/mechanisms.md: R maps
 * N-coordinates to B-coordinates, R = E_k ... E_1 of the passive elementary rotations
 * (dyn_rot_z of dynkit/mech.h), or R(q) of Euler parameters as dyn_quat_to_mat; a point p
 * of a body is at x + R' p. */
#include <math.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/mbs.h"
#include "mbs/mbs_internal.h"

enum { ON_STACK = 512 };
_Static_assert(DYN_MECH_MAX_ROT == MBS_MAX_ROT, "the plan holds every rotation of a body");

typedef struct item {
    dyn_mech_shape pub;
    mbs_shape s;
} item;

struct dyn_mech_scene {
    lang_ctx *c;
    mbs_model *mb;
    item *items;
    int n_items, n_values;
    double gravity[3];
    double mass; /* of all bodies and point masses */
};

static const int n_values_of[DYN_MECH_SHAPE_COUNT] = {
    [DYN_MECH_BOX] = 6,    [DYN_MECH_CYLINDER] = 8, [DYN_MECH_SPHERE] = 4,
    [DYN_MECH_ROD] = 6,    [DYN_MECH_SPRING] = 6,   [DYN_MECH_FRAME] = 4,
    [DYN_MECH_GROUND] = 7, [DYN_MECH_TRACE] = 3,    [DYN_MECH_ARROW] = 6,
};

static mbs_shape plain(int kind, int body, const char *name)
{
    mbs_shape s = mbs_shape_init(kind);
    s.name = name;
    s.a.body = s.b.body = body;
    return s;
}

static void add_item(dyn_mech_scene *sc, lvec *v, mbs_shape s)
{
    item it;
    memset(&it, 0, sizeof it);
    it.s = s;
    it.pub.kind = (dyn_mech_shape_kind)s.kind;
    it.pub.name = s.name;
    it.pub.line = s.pos.line;
    it.pub.col = s.pos.col;
    it.pub.body = s.a.body;
    it.pub.axis = s.axis;
    it.pub.color = s.color;
    it.pub.constraint = s.con;
    it.pub.offset = sc->n_values;
    it.pub.n_values = n_values_of[s.kind];
    sc->n_values += it.pub.n_values;
    *(item *)lvec_push(sc->c, v, sizeof it) = it;
}

/* the shapes: the file's, or the default drawing (a sphere per point mass; a sphere and the
 * axes per rigid body), then the springs */
static void build(dyn_mech_scene *sc)
{
    mbs_model *mb = sc->mb;
    lvec v = {0};
    for (int i = 0; i < mb->shapes.n; i++)
        add_item(sc, &v, LVEC_AT(mb->shapes, mbs_shape, i));
    if (mb->shapes.n == 0) {
        for (int b = 0; b < mb->bodies.n; b++) {
            const mbs_body *bd = &LVEC_AT(mb->bodies, mbs_body, b);
            add_item(sc, &v, plain(DYN_MECH_SPHERE, b, bd->name));
            if (bd->frame)
                add_item(sc, &v, plain(DYN_MECH_FRAME, b, bd->name));
        }
    }
    for (int i = 0; i < mb->springs.n; i++) {
        const mbs_spring *sp = &LVEC_AT(mb->springs, mbs_spring, i);
        mbs_shape s = plain(DYN_MECH_SPRING, sp->a.body, sp->name);
        s.a = sp->a;
        s.b = sp->b;
        s.pos = sp->pos;
        add_item(sc, &v, s);
    }
    int ground = 0;
    for (int i = 0; i < mb->shapes.n; i++)
        ground |= LVEC_AT(mb->shapes, mbs_shape, i).kind == DYN_MECH_GROUND;
    if (mb->wheels.n && !ground) /* the wheels roll on it */
        add_item(sc, &v, plain(DYN_MECH_GROUND, -1, "ground"));
    for (int w = 0; w < mb->wheels.n; w++) { /* the disk, and its rolling forces */
        const mbs_wheel *wh = &LVEC_AT(mb->wheels, mbs_wheel, w);
        mbs_shape s = plain(DYN_MECH_CYLINDER, wh->body, wh->name);
        s.pos = wh->pos;
        s.wheel = w;
        s.axis = -1;
        s.v[0] = wh->radius;
        memcpy(s.a.p, wh->at, sizeof s.a.p);
        memcpy(s.avec, wh->axis, sizeof s.avec);
        add_item(sc, &v, s);
        for (int k = 0; k < mb->cons.n; k++) {
            const mbs_constraint *con = &LVEC_AT(mb->cons, mbs_constraint, k);
            if (con->wheel != w || con->part > 1)
                continue;
            mbs_shape ar = plain(DYN_MECH_ARROW, wh->body, con->name);
            ar.pos = wh->pos;
            ar.wheel = w;
            ar.con = k;
            ar.axis = con->part; /* along x or y of N */
            add_item(sc, &v, ar);
        }
    }
    sc->items = v.data;
    sc->n_items = v.n;
}

static void scene_front(lang_ctx *c) { c->hook_ctx = mbs_read(c); }

static int evaluate(const dyn_mech_scene *s, double t, const double *y, const double *params,
                    double *pose, double *values, double g[3], double *mass);

static int read_guarded(dyn_mech_scene *sc, dyn_lang_diag *diag)
{
    lang_ctx *c = sc->c;
    jmp_buf fail;
    c->fail = &fail;
    if (setjmp(fail)) {
        const int status = c->status ? c->status : 2;
        if (status == 1)
            snprintf(diag->message, sizeof diag->message,
                     "out of memory while reading the mechanism");
        return status;
    }
    lang_run_front(c, scene_front);
    sc->mb = c->hook_ctx;
    build(sc);
    c->fail = NULL;
    return 0;
}

int dyn_mech_scene_read(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables,
                        dyn_mech_scene **scene, dyn_lang_diag *diag)
{
    dyn_lang_diag scratch;
    dyn_lang_diag *d = diag ? diag : &scratch;
    memset(d, 0, sizeof *d);
    const char *p = path ? path : "<mechanism>";
    strncpy(d->path, p, sizeof d->path - 1);
    if (scene)
        *scene = NULL;
    if (!scene || (!text && len) || n_tables < 0 || (n_tables > 0 && !tables)) {
        strcpy(d->message, "no text or no place for the scene (a NULL argument)");
        return 2;
    }
    dyn_mech_scene *sc = calloc(1, sizeof *sc);
    lang_ctx *c = sc ? lang_ctx_new(p, text, len, tables, n_tables, d) : NULL;
    if (!c) {
        free(sc);
        strcpy(d->message, "out of memory while reading the mechanism");
        return 1;
    }
    sc->c = c;
    const int status = read_guarded(sc, d);
    if (status) {
        lang_ctx_free(c, sc);
        return status;
    }
    c->diag = NULL;
    c->text = NULL;
    c->len = 0;
    c->table_files = NULL;
    c->n_table_files = 0;
    /* gravity and the mass at the default parameters, for the page's "up" and the
     * arrows' weight m g */
    const int np = dyn_mech_scene_n_params(sc);
    double *par = calloc((size_t)np + 1, sizeof *par);
    double *pose = calloc((size_t)12 * (size_t)sc->mb->bodies.n + 1, sizeof *pose);
    double *vals = calloc((size_t)sc->n_values + 1, sizeof *vals);
    if (!par || !pose || !vals) {
        free(par);
        free(pose);
        free(vals);
        dyn_mech_scene_free(sc);
        strcpy(d->message, "out of memory while reading the mechanism");
        return 1;
    }
    for (int i = 0; i < np; i++)
        par[i] = LVEC_AT(c->m.params, lang_param, i).value;
    const int bad = evaluate(sc, c->m.t0, NULL, par, pose, vals, sc->gravity, &sc->mass);
    free(par);
    free(pose);
    free(vals);
    if (bad) {
        dyn_mech_scene_free(sc);
        strcpy(d->message, "out of memory while reading the mechanism");
        return 1;
    }
    *scene = sc;
    return 0;
}

void dyn_mech_scene_free(dyn_mech_scene *scene)
{
    if (scene)
        lang_ctx_free(scene->c, scene);
}

int dyn_mech_scene_n_bodies(const dyn_mech_scene *s) { return s ? s->mb->bodies.n : 0; }

const char *dyn_mech_scene_body_name(const dyn_mech_scene *s, int body)
{
    return s && body >= 0 && body < s->mb->bodies.n
               ? LVEC_AT(s->mb->bodies, mbs_body, body).name
               : NULL;
}

int dyn_mech_scene_body_is_point(const dyn_mech_scene *s, int body)
{
    return s && body >= 0 && body < s->mb->bodies.n && !LVEC_AT(s->mb->bodies, mbs_body, body).frame;
}

int dyn_mech_scene_n_shapes(const dyn_mech_scene *s) { return s ? s->n_items : 0; }

const dyn_mech_shape *dyn_mech_scene_shape(const dyn_mech_scene *s, int i)
{
    return s && i >= 0 && i < s->n_items ? &s->items[i].pub : NULL;
}

int dyn_mech_scene_n_values(const dyn_mech_scene *s) { return s ? s->n_values : 0; }

int dyn_mech_scene_n_constraints(const dyn_mech_scene *s) { return s ? s->mb->cons.n : 0; }

const char *dyn_mech_scene_constraint(const dyn_mech_scene *s, int k)
{
    return s && k >= 0 && k < s->mb->cons.n ? LVEC_AT(s->mb->cons, mbs_constraint, k).name : NULL;
}

int dyn_mech_scene_n_params(const dyn_mech_scene *s) { return s ? s->c->m.params.n : 0; }

double dyn_mech_scene_mass(const dyn_mech_scene *s) { return s ? s->mass : 0.0; }

void dyn_mech_scene_gravity(const dyn_mech_scene *s, double g[3])
{
    for (int k = 0; k < 3; k++)
        g[k] = s ? s->gravity[k] : 0.0;
}

/* ---- the plan of a frame (dynkit/mbs.h) ---- */

int dyn_mech_scene_n_inputs(const dyn_mech_scene *s) { return s ? s->c->m.fixes.n : 0; }
int dyn_mech_scene_n_wheels(const dyn_mech_scene *s) { return s ? s->mb->wheels.n : 0; }

int dyn_mech_scene_body_plan(const dyn_mech_scene *s, int body, dyn_mech_body_plan *out)
{
    if (!s || body < 0 || body >= s->mb->bodies.n || !out)
        return -1;
    const mbs_body *b = &LVEC_AT(s->mb->bodies, mbs_body, body);
    memset(out, 0, sizeof *out);
    out->frame = b->frame;
    memcpy(out->quat, b->quat, sizeof out->quat);
    out->nrot = b->nrot;
    memcpy(out->axis, b->axis, sizeof out->axis);
    memcpy(out->angle, b->angle, sizeof out->angle);
    out->joint = b->joint != MBS_NO_JOINT;
    out->parent = b->parent;
    memcpy(out->at, b->at, sizeof out->at);
    memcpy(out->jp, b->jp, sizeof out->jp);
    memcpy(out->shift, b->shift, sizeof out->shift);
    memcpy(out->pivot, b->pivot, sizeof out->pivot);
    memcpy(out->axisv, b->axisv, sizeof out->axisv);
    out->slide = b->slide;
    out->slide_axis = b->slide_axis;
    out->mass = b->mass;
    return 0;
}

int dyn_mech_scene_shape_plan(const dyn_mech_scene *s, int i, dyn_mech_shape_plan *out)
{
    if (!s || i < 0 || i >= s->n_items || !out)
        return -1;
    const mbs_shape *sh = &s->items[i].s;
    out->body = sh->a.body;
    memcpy(out->p, sh->a.p, sizeof out->p);
    out->body_b = sh->b.body;
    memcpy(out->p_b, sh->b.p, sizeof out->p_b);
    memcpy(out->v, sh->v, sizeof out->v);
    out->size = sh->size;
    out->axis = sh->axis;
    memcpy(out->avec, sh->avec, sizeof out->avec);
    out->in_body = sh->in_body;
    out->wheel = sh->wheel;
    return 0;
}

int dyn_mech_scene_wheel_plan(const dyn_mech_scene *s, int w, dyn_mech_wheel_plan *out)
{
    if (!s || w < 0 || w >= s->mb->wheels.n || !out)
        return -1;
    const mbs_wheel *wh = &LVEC_AT(s->mb->wheels, mbs_wheel, w);
    out->body = wh->body;
    out->radius = wh->radius;
    memcpy(out->axis, wh->axis, sizeof out->axis);
    memcpy(out->at, wh->at, sizeof out->at);
    return 0;
}

void dyn_mech_scene_gravity_inputs(const dyn_mech_scene *s, int g[3])
{
    for (int k = 0; k < 3; k++)
        g[k] = s ? s->mb->gravity[k] : -1;
}

/* ---- one frame ---- */

typedef struct frame {
    const mbs_model *mb;
    const double *fix;
    double *pose;
    double g[3]; /* gravity */
} frame;

static double in(const frame *f, int input, double none)
{
    return input >= 0 ? f->fix[input] : none;
}

/* the unit axis of a joint's rotation or slide about (ax, ay, az) */
static void unit_axis(const frame *f, const mbs_body *b, double n[3])
{
    double len = 0.0;
    for (int k = 0; k < 3; k++) {
        n[k] = in(f, b->axisv[k], 0.0);
        len += n[k] * n[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; k++)
        n[k] /= len;
}

/* R = E R for the passive rotation E by angle a about axis 0..2 (elementary, dyn_rot_z's
 * [c s; -s c] on the other two axes) or 3 (the joint's axis n: E = cos a I + (1 - cos a)
 * n n' - sin a [n x], as mbs_derive.c) */
static void turn(const frame *f, const mbs_body *b, double R[9], int axis, double a)
{
    const double co = cos(a), si = sin(a);
    double E[9] = {0}, n[3] = {0, 0, 0};
    if (axis < 3)
        n[axis] = 1.0;
    else
        unit_axis(f, b, n);
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++) {
            E[3 * r + k] = (1.0 - co) * n[r] * n[k] + (r == k ? co : 0.0);
            if (r != k)
                E[3 * r + k] += ((k - r + 3) % 3 == 1 ? si : -si) * n[3 - r - k];
        }
    double T[9];
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            T[3 * r + k] = E[3 * r] * R[k] + E[3 * r + 1] * R[3 + k] + E[3 * r + 2] * R[6 + k];
    memcpy(R, T, sizeof T);
}

/* the pose of body b into f->pose (its parent's first): R = E_k ... E_1 or R(q), composed
 * with the parent's for a joint, x = x_P + R_P'(jp + shift + n s) - R'(pivot) with a
 * prismatic joint's slide s along n (mbs_derive.c) */
static void body_pose(const frame *f, const mbs_model *mb, int bi)
{
    const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, bi);
    double *x = f->pose + 12 * bi, *R = x + 3;
    memset(R, 0, 9 * sizeof *R);
    R[0] = R[4] = R[8] = 1.0;
    if (b->frame && b->quat[0] >= 0) {
        const double w = in(f, b->quat[0], 1.0), v[3] = {in(f, b->quat[1], 0.0),
                                                         in(f, b->quat[2], 0.0),
                                                         in(f, b->quat[3], 0.0)};
        const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2], n2 = w * w + vv;
        const double sk[9] = {0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0};
        for (int r = 0; r < 3; r++)
            for (int col = 0; col < 3; col++)
                R[3 * r + col] = ((r == col ? w * w - vv : 0.0) + 2.0 * v[r] * v[col] -
                                  2.0 * w * sk[3 * r + col]) / n2;
    } else if (b->frame) {
        for (int k = 0; k < b->nrot; k++)
            turn(f, b, R, b->axis[k], in(f, b->angle[k], 0.0));
    }
    if (!b->joint) {
        for (int k = 0; k < 3; k++)
            x[k] = in(f, b->at[k], 0.0);
        return;
    }
    const mbs_body *p = b->parent >= 0 ? &LVEC_AT(mb->bodies, mbs_body, b->parent) : NULL;
    const double *xp = p ? f->pose + 12 * b->parent : NULL, *Rp = p ? xp + 3 : NULL;
    double a[3], r[3], pv[3], off[3];
    double n[3] = {0, 0, 0}; /* a prismatic joint's axis */
    if (b->slide >= 0 && b->slide_axis == 3)
        unit_axis(f, b, n);
    else if (b->slide >= 0)
        n[b->slide_axis] = 1.0;
    const double slide = in(f, b->slide, 0.0);
    for (int k = 0; k < 3; k++) {
        a[k] = in(f, b->jp[k], 0.0) + in(f, b->shift[k], 0.0) + n[k] * slide;
        pv[k] = in(f, b->pivot[k], 0.0);
    }
    memcpy(r, a, sizeof r);
    if (p && p->frame) {
        double Rj[9];
        memcpy(Rj, R, sizeof Rj);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                R[3 * i + j] = Rj[3 * i] * Rp[j] + Rj[3 * i + 1] * Rp[3 + j] +
                               Rj[3 * i + 2] * Rp[6 + j];
        for (int k = 0; k < 3; k++)
            r[k] = Rp[k] * a[0] + Rp[3 + k] * a[1] + Rp[6 + k] * a[2];
    }
    for (int k = 0; k < 3; k++)
        off[k] = b->frame ? R[k] * pv[0] + R[3 + k] * pv[1] + R[6 + k] * pv[2] : pv[k];
    for (int k = 0; k < 3; k++)
        x[k] = (xp ? xp[k] : 0.0) + r[k] - off[k];
}

/* a point of a body (in its frame; in N for a point mass and the ground) in N */
static void point_of(const frame *f, const mbs_attach *a, double out[3])
{
    double p[3];
    for (int k = 0; k < 3; k++)
        p[k] = in(f, a->p[k], 0.0);
    if (a->body < 0) {
        memcpy(out, p, sizeof p);
        return;
    }
    const double *x = f->pose + 12 * a->body, *R = x + 3; /* identity without a frame */
    for (int k = 0; k < 3; k++)
        out[k] = x[k] + R[k] * p[0] + R[3 + k] * p[1] + R[6 + k] * p[2];
}

/* a cylinder's unit axis in N: R' of the wheel's vector or of the body's axis */
static void axis_n(const frame *f, const mbs_shape *s, const double *pose, double out[3])
{
    double a[3] = {0, 0, 0}, len = 0.0;
    if (s->avec[0] >= 0)
        for (int k = 0; k < 3; k++)
            a[k] = in(f, s->avec[k], 0.0);
    else
        a[s->axis] = 1.0;
    for (int k = 0; k < 3; k++) {
        out[k] = pose ? pose[3 + k] * a[0] + pose[6 + k] * a[1] + pose[9 + k] * a[2] : a[k];
        len += out[k] * out[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; k++)
        out[k] = len > 0.0 ? out[k] / len : NAN;
}

/* a wheel's lowest point P = C - r k, k = (e_z - a_z a) / |e_z - a_z a| (mbs_wheel.c) */
static void contact(const frame *f, const mbs_wheel *wh, double out[3])
{
    mbs_shape s;
    memset(&s, 0, sizeof s);
    s.a.body = wh->body;
    memcpy(s.a.p, wh->at, sizeof s.a.p);
    memcpy(s.avec, wh->axis, sizeof s.avec);
    double c[3], a[3];
    point_of(f, &s.a, c);
    axis_n(f, &s, f->pose + 12 * wh->body, a);
    const double r = in(f, wh->radius, 0.0);
    double k[3] = {-a[2] * a[0], -a[2] * a[1], 1.0 - a[2] * a[2]};
    const double n = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    for (int j = 0; j < 3; j++)
        out[j] = c[j] - (n > 0.0 ? r * k[j] / n : NAN);
}

static void shape_values(const frame *f, const item *it, double *v)
{
    const mbs_shape *s = &it->s;
    const double *pose = s->a.body >= 0 ? f->pose + 12 * s->a.body : NULL;
    switch (s->kind) {
    case DYN_MECH_BOX:
        point_of(f, &s->a, v);
        for (int k = 0; k < 3; k++)
            v[3 + k] = 0.5 * fabs(in(f, s->v[k], NAN));
        break;
    case DYN_MECH_CYLINDER:
        point_of(f, &s->a, v);
        v[3] = in(f, s->v[0], NAN);
        v[4] = 0.5 * in(f, s->v[1], 0.0);
        axis_n(f, s, pose, v + 5);
        break;
    case DYN_MECH_SPHERE:
        point_of(f, &s->a, v);
        v[3] = in(f, s->v[0], NAN);
        break;
    case DYN_MECH_FRAME:
        point_of(f, &s->a, v);
        v[3] = in(f, s->size, NAN);
        break;
    case DYN_MECH_ROD:
    case DYN_MECH_SPRING:
        point_of(f, &s->a, v);
        point_of(f, &s->b, v + 3);
        break;
    case DYN_MECH_GROUND: {
        point_of(f, &s->a, v);
        double n[3], len = 0.0;
        const double *g = f->g;
        const int has_g = g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0;
        for (int k = 0; k < 3; k++) {
            n[k] = s->v[0] >= 0 ? in(f, s->v[k], 0.0) : has_g ? -g[k] : k == 2;
            len += n[k] * n[k];
        }
        len = sqrt(len);
        for (int k = 0; k < 3; k++)
            v[3 + k] = len > 0.0 ? n[k] / len : NAN;
        v[6] = 0.5 * in(f, s->size, NAN);
        break;
    }
    case DYN_MECH_TRACE: point_of(f, &s->a, v); break;
    case DYN_MECH_ARROW: {
        if (s->wheel >= 0) { /* at the wheel's contact, along x or y of N */
            contact(f, &LVEC_AT(f->mb->wheels, mbs_wheel, s->wheel), v);
            for (int k = 0; k < 3; k++)
                v[3 + k] = k == s->axis;
            break;
        }
        point_of(f, &s->a, v);
        double d[3], len = 0.0;
        for (int k = 0; k < 3; k++)
            d[k] = in(f, s->v[k], 0.0);
        if (s->in_body && pose) { /* B to N: R' d */
            const double *R = pose + 3;
            const double b[3] = {d[0], d[1], d[2]};
            for (int k = 0; k < 3; k++)
                d[k] = R[k] * b[0] + R[3 + k] * b[1] + R[6 + k] * b[2];
        }
        for (int k = 0; k < 3; k++)
            len += d[k] * d[k];
        len = sqrt(len);
        for (int k = 0; k < 3; k++)
            v[3 + k] = len > 0.0 ? d[k] / len : 0.0;
        break;
    }
    default: break;
    }
}

/* one frame (y NULL: the default initial state), gravity into g and the total mass into
 * *mass */
static int evaluate(const dyn_mech_scene *s, double t, const double *y, const double *params,
                    double *pose, double *values, double g[3], double *mass)
{
    const lang_model *m = &s->c->m;
    const int np = m->params.n, nd = m->derived.n, nfix = m->fixes.n;
    double pv_stack[ON_STACK], fix_stack[ON_STACK];
    double *pv = np + nd < ON_STACK ? pv_stack : malloc(((size_t)np + nd + 1) * sizeof *pv);
    double *fix = nfix < ON_STACK ? fix_stack : malloc(((size_t)nfix + 1) * sizeof *fix);
    double *y0 = NULL;
    if (!y) /* the default initial state */
        y0 = calloc((size_t)m->states.n + 1, sizeof *y0);
    if (!pv || !fix || (!y && !y0)) {
        if (pv != pv_stack)
            free(pv);
        if (fix != fix_stack)
            free(fix);
        free(y0);
        return 1;
    }
    memcpy(pv, params, (size_t)np * sizeof *pv);
    lang_frame x = {m, t, y ? y : y0, NULL, pv, fix, 0};
    for (int i = 0; i < nd; i++) {
        const int k = m->derived_order[i];
        pv[np + k] = lang_eval_frame(&x, LVEC_AT(m->derived, lang_formula, k).expr, NULL);
    }
    if (y0)
        for (int i = 0; i < m->states.n; i++) {
            const node *e = LVEC_AT(m->states, lang_state, i).init;
            y0[i] = e ? lang_eval_frame(&x, e, NULL) : 0.0;
        }
    for (int i = 0; i < nfix; i++)
        fix[i] = NAN;
    for (int i = 0; i < nfix; i++) {
        const int k = m->fix_order[i];
        fix[k] = lang_eval_frame(&x, LVEC_AT(m->fixes, lang_formula, k).expr, NULL);
    }
    frame f = {s->mb, fix, pose, {0, 0, 0}};
    const mbs_model *mb = s->mb;
    for (int k = 0; k < 3; k++)
        f.g[k] = g[k] = in(&f, mb->gravity[k], 0.0);
    *mass = 0.0;
    for (int b = 0; b < mb->bodies.n; b++) {
        body_pose(&f, mb, b);
        *mass += in(&f, LVEC_AT(mb->bodies, mbs_body, b).mass, 0.0);
    }
    for (int i = 0; i < s->n_items; i++)
        shape_values(&f, &s->items[i], values + s->items[i].pub.offset);
    if (pv != pv_stack)
        free(pv);
    if (fix != fix_stack)
        free(fix);
    free(y0);
    return 0;
}

int dyn_mech_scene_eval(const dyn_mech_scene *s, double t, const double *y,
                        const double *params, double *pose, double *values)
{
    double g[3], mass;
    if (!s || !y || !params || !pose || !values)
        return 0;
    return evaluate(s, t, y, params, pose, values, g, &mass);
}
