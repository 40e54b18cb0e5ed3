/* SPDX-License-Identifier: BSD-3-Clause */
/* The equations of motion of a mechanism by TMT, the virtual power method with generalized
 * coordinates (Vallery & Schwab, "Advanced Dynamics", TU Delft, ch. "TMT"), written into
 * the model as fixed quantities (docs/mechanisms.md, "The method"):
 *   symbolic, by src/lang's derivatives: each body's mass centre x(q,t), rotation R(q,t)
 *   (N->B, a product of elementary rotations), J_v = dx/dq, J_w (omega_B = J_w qd + w_t,
 *   the rotations' rates carried to B), the convective terms g = d(J qd + v_t)/dq qd +
 *   d(J qd + v_t)/dt, and for each constraint its row D = dh/dqd of its velocity form h
 *   with its convective term;
 *   numeric, per evaluation: M = sum m J_v'J_v + J_w' I J_w, F = sum J_v'(m g_N - m g_v) +
 *   J_w'(-I g_w - w x I w) + the loads' J'f, qdd = M^-1 F by L D L', then the
 *   multipliers from the Schur complement (D M^-1 D') lambda = -(D M^-1 F + conv + stab)
 *   and qdd += M^-1 D' lambda (Baumgarte's stab = 2 a h + a^2 f for f(q,t) = 0; none for
 *   a constraint on the speeds, which has no position to drift from). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mbs/mbs_check.h"

typedef struct dctx {
    lang_ctx *c;
    mbs_model *mb;
    int n;        /* coordinates */
    int *q, *u;   /* their state indices, and their speeds' */
    node **qd;    /* the coordinates' rates: their speeds, or the formulas of `rate` lines */
    node **W;     /* (n x n) dqd_k/du_j of declared speeds (row k), NULL: the rates */
    int nfix0;    /* fixed quantities before the derivation */
    int count;    /* fixed quantities written */
    mbs_initial ini; /* the initial state, for the checks */
    double *D0;      /* the constraints' rows there (m x n) */
} dctx;

static int symbolic(const dctx *d) { return d->mb->symbolic; }

static node *num(dctx *d, double v) { return lang_num(d->c, v); }
static node *add(dctx *d, node *a, node *b) { return lang_add(d->c, a, b); }
static node *sub(dctx *d, node *a, node *b) { return lang_sub(d->c, a, b); }
static node *mul(dctx *d, node *a, node *b) { return lang_mul(d->c, a, b); }

static node *ref(dctx *d, node_kind kind, int index)
{
    node *e = lang_node(d->c, kind, (lpos){0, 0});
    e->index = index;
    return e;
}

/* a fixed quantity of value e (simple values stay as they are) */
static node *fix(dctx *d, const char *role, node *e)
{
    if (symbolic(d))
        return e; /* the formulas themselves, to print (dynkit derive) */
    if (e->kind == N_NUM || e->kind == N_STATE || e->kind == N_PARAM || e->kind == N_FIX ||
        e->kind == N_TIME)
        return e;
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    lang_formula *f = lvec_push(c, &c->m.fixes, sizeof *f);
    f->name = lang_printf(c, "mbs%d_%s", d->count++, role);
    f->pos = (lpos){0, 0};
    f->expr = e;
    if (mb->norder >= mb->ordercap) {
        const int cap = mb->ordercap ? 2 * mb->ordercap : 256;
        int *o = lang_alloc(c, (size_t)cap * sizeof *o);
        if (mb->norder)
            memcpy(o, mb->order, (size_t)mb->norder * sizeof *o);
        mb->order = o;
        mb->ordercap = cap;
    }
    mb->order[mb->norder++] = c->m.fixes.n - 1;
    return ref(d, N_FIX, c->m.fixes.n - 1);
}

static node *input_ref(dctx *d, int k)
{
    if (k < 0)
        return num(d, 0.0);
    if (symbolic(d)) /* the formula as written, to print */
        return LVEC_AT(d->c->m.fixes, lang_formula, k).expr;
    return ref(d, N_FIX, k);
}

/* ---- expansion of the inputs (fixed quantities and user functions inlined) ---- */

static node *expand(dctx *d, node *e);

static node *expand_node(dctx *d, node *e)
{
    lang_ctx *c = d->c;
    switch (e->kind) {
    case N_FIX: {
        mbs_model *mb = d->mb;
        if (e->index >= d->nfix0)
            lang_fail(c, e->pos, "internal: a derived quantity in a kinematic formula");
        if (!mb->expanded[e->index])
            mb->expanded[e->index] = expand(d, LVEC_AT(c->m.fixes, lang_formula, e->index).expr);
        return mb->expanded[e->index];
    }
    case N_UFUN: {
        node **args = lang_alloc(c, (size_t)(e->nargs + 1) * sizeof *args);
        for (int i = 0; i < e->nargs; i++)
            args[i] = expand(d, e->args[i]);
        return expand(d, lang_subst(c, LVEC_AT(c->m.funcs, lang_func, e->index).body, args));
    }
    case N_ALG:
        lang_fail(c, e->pos, "an algebraic variable cannot enter the kinematics of a mechanism");
    case N_DFIX:
    case N_UFUN_D:
    case N_SUM:
    case N_SUMIDX:
        lang_fail(c, e->pos, "this formula cannot enter the kinematics of a mechanism");
    default:
        break;
    }
    if (e->kind == N_FUN && e->op == F_SPECIAL)
        lang_fail(c, e->pos, "a network sum cannot enter the kinematics of a mechanism");
    if (e->nargs == 0)
        return e;
    node *r = lang_node(c, e->kind, e->pos);
    *r = *e;
    r->args = lang_alloc(c, (size_t)e->nargs * sizeof *r->args);
    for (int i = 0; i < e->nargs; i++)
        r->args[i] = expand(d, e->args[i]);
    return r;
}

/* e with the fixed quantities and user functions it reads inlined; as deep as the
 * derivatives may go (8 LANG_MAX_DEPTH, a chain of fixed quantities included) */
static node *expand(dctx *d, node *e)
{
    if (++d->c->depth > 8 * LANG_MAX_DEPTH)
        lang_fail(d->c, e->pos, "formula nested too deeply through the fixed quantities it "
                  "reads (more than %d levels)", 8 * LANG_MAX_DEPTH);
    node *r = expand_node(d, e);
    d->c->depth--;
    return r;
}

static node *input(dctx *d, int k) { return k < 0 ? num(d, 0.0) : expand(d, ref(d, N_FIX, k)); }

static int uses(const node *e, node_kind kind, int index)
{
    if ((int)e->kind == (int)kind && (index < 0 || e->index == index))
        return 1;
    for (int i = 0; i < e->nargs; i++)
        if (uses(e->args[i], kind, index))
            return 1;
    return 0;
}

/* ---- symbolic derivatives ---- */

static node *dq(dctx *d, node *e, int state)
{
    const lang_dvar v = {N_STATE, state, NULL, NULL, 0};
    return lang_deriv(d->c, e, &v);
}

static node *time_as_arg(dctx *d, node *e)
{
    if (e->kind == N_TIME)
        return ref(d, N_ARG, 0);
    if (e->nargs == 0)
        return e;
    node *r = lang_node(d->c, e->kind, e->pos);
    *r = *e;
    r->args = lang_alloc(d->c, (size_t)e->nargs * sizeof *r->args);
    for (int i = 0; i < e->nargs; i++)
        r->args[i] = time_as_arg(d, e->args[i]);
    return r;
}

static node *dt(dctx *d, node *e)
{
    if (!uses(e, N_TIME, -1))
        return num(d, 0.0);
    const lang_dvar v = {N_ARG, 0, NULL, NULL, 0};
    node *de = lang_deriv(d->c, time_as_arg(d, e), &v);
    node *t = lang_node(d->c, N_TIME, (lpos){0, 0});
    return lang_subst(d->c, de, &t);
}

/* the time derivative along the motion: sum_k de/dq_k qd_k + de/dt (u held) */
static node *rate(dctx *d, node *e)
{
    node *r = dt(d, e);
    for (int k = 0; k < d->n; k++)
        r = add(d, r, mul(d, dq(d, e, d->q[k]), d->qd[k]));
    return r;
}

/* columns by coordinate (3 n) into columns by speed: J_u = J_q W */
static void to_speeds(dctx *d, node **J)
{
    if (!d->W)
        return;
    const int n = d->n;
    node **T = lang_alloc(d->c, 3 * (size_t)n * sizeof *T);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < 3; i++) {
            T[3 * j + i] = num(d, 0.0);
            for (int k = 0; k < n; k++)
                T[3 * j + i] = add(d, T[3 * j + i], mul(d, J[3 * k + i], d->W[k * n + j]));
        }
    memcpy(J, T, 3 * (size_t)n * sizeof *J);
}

/* Jacobian columns (3 n, symbolic) and velocity of a point r(q, t) */
static void point_jacobian(dctx *d, node *const r[3], node **J, node *vel[3])
{
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < d->n; k++)
            J[3 * k + j] = dq(d, r[j], d->q[k]);
    to_speeds(d, J);
    for (int j = 0; j < 3; j++) {
        vel[j] = dt(d, r[j]);
        for (int k = 0; k < d->n; k++)
            vel[j] = add(d, vel[j], mul(d, J[3 * k + j], ref(d, N_STATE, d->u[k])));
    }
}

static void fix_vec(dctx *d, const char *role, node **v, int count)
{
    for (int i = 0; i < count; i++)
        v[i] = fix(d, lang_printf(d->c, "%s%d", role, i), v[i]);
}

/* ---- rotations: R (N->B) = E_last ... E_first, passive elementary rotations ---- */

static void elementary(dctx *d, int axis, node *angle, node *E[9])
{
    node *cs, *sn;
    mbs_cos_sin(d->c, angle, &cs, &sn);
    for (int i = 0; i < 9; i++)
        E[i] = num(d, 0.0);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    E[4 * axis] = num(d, 1.0);
    E[3 * a + a] = cs;
    E[3 * b + b] = cs;
    E[3 * a + b] = sn;
    E[3 * b + a] = lang_neg(d->c, sn);
}

static void matmul(dctx *d, node *const A[9], node *const B[9], node *C[9])
{
    node *T[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            node *s = num(d, 0.0);
            for (int k = 0; k < 3; k++)
                s = add(d, s, mul(d, A[3 * i + k], B[3 * k + j]));
            T[3 * i + j] = s;
        }
    memcpy(C, T, sizeof T);
}

static void identity(dctx *d, node *M[9])
{
    for (int i = 0; i < 9; i++)
        M[i] = num(d, i % 4 == 0 ? 1.0 : 0.0);
}

static node *dot(dctx *d, node *const *a, node *const *b);

/* R of Euler parameters (w, x, y, z), divided by their norm (dyn_quat_to_mat's formula,
 * orthogonal for any nonzero q), and the angular velocity in B from skew(w_B) = R dR'/dt,
 * w_B = (S32, S13, S21) with S = R dR'/dq_k for column k of J_w. */
static void quaternion(dctx *d, mbs_body *b, node **Jw, node *w[3])
{
    node *q[4];
    for (int k = 0; k < 4; k++)
        q[k] = input(d, b->quat[k]);
    node *n2 = add(d, add(d, mul(d, q[0], q[0]), mul(d, q[1], q[1])),
                   add(d, mul(d, q[2], q[2]), mul(d, q[3], q[3])));
    node *s = lang_div(d->c, num(d, 2.0), n2);
#define QP(a, b) mul(d, s, mul(d, q[a], q[b]))
    node **R = b->R;
    R[0] = sub(d, num(d, 1.0), add(d, QP(2, 2), QP(3, 3)));
    R[1] = add(d, QP(1, 2), QP(0, 3));
    R[2] = sub(d, QP(1, 3), QP(0, 2));
    R[3] = sub(d, QP(1, 2), QP(0, 3));
    R[4] = sub(d, num(d, 1.0), add(d, QP(1, 1), QP(3, 3)));
    R[5] = add(d, QP(2, 3), QP(0, 1));
    R[6] = add(d, QP(1, 3), QP(0, 2));
    R[7] = sub(d, QP(2, 3), QP(0, 1));
    R[8] = sub(d, num(d, 1.0), add(d, QP(1, 1), QP(2, 2)));
#undef QP
    for (int k = -1; k < d->n; k++) { /* k = -1: the partial derivative in t */
        node *dR[9];
        for (int i = 0; i < 9; i++)
            dR[i] = k < 0 ? dt(d, R[i]) : dq(d, R[i], d->q[k]);
        node *S[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) /* S = R dR' */
                S[3 * i + j] = dot(d, R + 3 * i, dR + 3 * j);
        node *col[3] = {S[7], S[2], S[3]};
        for (int j = 0; j < 3; j++) {
            if (k < 0)
                w[j] = col[j];
            else
                Jw[3 * k + j] = col[j];
        }
    }
    to_speeds(d, Jw);
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < d->n; k++)
            w[j] = add(d, w[j], mul(d, Jw[3 * k + j], ref(d, N_STATE, d->u[k])));
}

/* R, and J_w (3 n symbolic) with the angular velocity in B */
/* a joint's axis (ax, ay, az) divided by its length */
static void unit_axis(dctx *d, const mbs_body *b, node *n[3])
{
    node *v[3];
    for (int j = 0; j < 3; j++)
        v[j] = input(d, b->axisv[j]);
    node *len = lang_fun1(d->c, F_SQRT, dot(d, v, v));
    for (int j = 0; j < 3; j++)
        n[j] = lang_div(d->c, v[j], len);
}

/* rotation i of b: elementary, or about a joint's axis n (axis 3), passive:
 * E = cos(a) I + (1 - cos(a)) n n' - sin(a) [n x] */
static void factor(dctx *d, const mbs_body *b, int axis, node *angle, node *E[9])
{
    if (axis < 3) {
        elementary(d, axis, angle, E);
        return;
    }
    node *n[3], *cs, *sn;
    mbs_cos_sin(d->c, angle, &cs, &sn);
    unit_axis(d, b, n);
    node *vc = sub(d, num(d, 1.0), cs);
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++) {
            node *e = mul(d, vc, mul(d, n[r], n[k]));
            if (r == k)
                e = add(d, cs, e);
            else if ((k - r + 3) % 3 == 1) /* [n x][r][k] = -n[3-r-k] (r, k cyclic) */
                e = add(d, e, mul(d, sn, n[3 - r - k]));
            else
                e = sub(d, e, mul(d, sn, n[3 - r - k]));
            E[3 * r + k] = e;
        }
}

/* b's rotations: its own, after those of its parent's chain when both are elementary (a
 * joint's rotation about the same axis as the last one adds to its angle), so that a chain
 * of joints gives R = E_k ... E_1 as a body placed by rot; into b->caxis, b->cangle */
static int rotation_chain(dctx *d, mbs_body *b)
{
    const mbs_body *p = b->joint && b->parent >= 0
                            ? &LVEC_AT(d->mb->bodies, mbs_body, b->parent) : NULL;
    int n = 0, elementary_only = b->quat[0] < 0;
    b->chained = p && p->frame && p->cn >= 0 && elementary_only && p->cn + b->nrot <= MBS_MAX_CHAIN;
    for (int i = 0; i < b->nrot; i++)
        elementary_only &= b->axis[i] < 3;
    b->chained &= elementary_only;
    if (b->chained) {
        n = p->cn;
        memcpy(b->caxis, p->caxis, (size_t)n * sizeof *b->caxis);
        memcpy(b->cangle, p->cangle, (size_t)n * sizeof *b->cangle);
    }
    for (int i = 0; i < b->nrot; i++) {
        node *a = input(d, b->angle[i]);
        if (b->chained && i == 0 && n > 0 && b->caxis[n - 1] == b->axis[0]) {
            b->cangle[n - 1] = add(d, b->cangle[n - 1], a);
            continue;
        }
        b->caxis[n] = b->axis[i];
        b->cangle[n++] = a;
    }
    /* composed with a parent's matrix (below, joint_pose): no chain to continue */
    b->cn = elementary_only && !(p && p->frame && !b->chained) ? n : -1;
    return n;
}

static void rotation(dctx *d, mbs_body *b, node **Jw, node *w[3])
{
    b->cn = -1;
    if (b->quat[0] >= 0) {
        quaternion(d, b, Jw, w);
        return;
    }
    const int nr = rotation_chain(d, b);
    const int *axes = b->caxis;
    node **ang = b->cangle, *P[MBS_MAX_CHAIN][9];
    identity(d, b->R);
    for (int i = 0; i < nr; i++) {
        node *E[9];
        factor(d, b, axes[i], ang[i], E);
        matmul(d, E, b->R, b->R);
    }
    node *Pr[9];
    identity(d, Pr);
    for (int i = nr - 1; i >= 0; i--) { /* P_i = E_last ... E_(i+1) */
        memcpy(P[i], Pr, sizeof Pr);
        node *E[9];
        factor(d, b, axes[i], ang[i], E);
        matmul(d, Pr, E, Pr);
    }
    for (int j = 0; j < 3; j++) {
        w[j] = num(d, 0.0);
        for (int k = 0; k < d->n; k++)
            Jw[3 * k + j] = num(d, 0.0);
    }
    for (int i = 0; i < nr; i++) {
        const int a = axes[i];
        node *dth_t = dt(d, ang[i]), *n[3];
        if (a == 3)
            unit_axis(d, b, n);
        for (int j = 0; j < 3; j++) {
            node *col = a < 3 ? P[i][3 * j + a] : dot(d, P[i] + 3 * j, n);
            w[j] = add(d, w[j], mul(d, col, dth_t));
            for (int k = 0; k < d->n; k++)
                Jw[3 * k + j] = add(d, Jw[3 * k + j], mul(d, col, dq(d, ang[i], d->q[k])));
        }
    }
    to_speeds(d, Jw);
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < d->n; k++)
            w[j] = add(d, w[j], mul(d, Jw[3 * k + j], ref(d, N_STATE, d->u[k])));
}

static node *dot(dctx *d, node *const *a, node *const *b)
{
    return add(d, add(d, mul(d, a[0], b[0]), mul(d, a[1], b[1])), mul(d, a[2], b[2]));
}

/* R^T v (B to N) and R v (N to B) with R's fixed quantities */
static void to_n(dctx *d, node *const R[9], node *const v[3], node *out[3])
{
    for (int j = 0; j < 3; j++)
        out[j] = add(d, add(d, mul(d, R[j], v[0]), mul(d, R[3 + j], v[1])), mul(d, R[6 + j], v[2]));
}

static void to_b(dctx *d, node *const R[9], node *const v[3], node *out[3])
{
    for (int j = 0; j < 3; j++)
        out[j] = dot(d, R + 3 * j, v);
}

/* a body placed by a joint (mbs_joint.c): R = R_joint R_P, w = R_joint w_P + w_joint (in
 * B, each column of J_w likewise), x = x_P + R_P'(jp + shift) - R'(pivot) */
static void joint_pose(dctx *d, mbs_body *b, node **Jw)
{
    const mbs_body *p = b->parent >= 0 ? &LVEC_AT(d->mb->bodies, mbs_body, b->parent) : NULL;
    node *a[3], *r[3], *pv[3];
    node *n[3] = {num(d, 0.0), num(d, 0.0), num(d, 0.0)};
    if (b->slide >= 0 && b->slide_axis == 3)
        unit_axis(d, b, n);
    else if (b->slide >= 0)
        n[b->slide_axis] = num(d, 1.0);
    for (int j = 0; j < 3; j++) {
        a[j] = add(d, input(d, b->jp[j]), input(d, b->shift[j]));
        if (b->slide >= 0)
            a[j] = add(d, a[j], mul(d, n[j], input(d, b->slide)));
        pv[j] = input(d, b->pivot[j]);
    }
    if (p && p->frame && !b->chained) {
        node *Rj[9];
        memcpy(Rj, b->R, sizeof Rj);
        matmul(d, Rj, p->R, b->R);
        for (int k = -1; k < d->n; k++) {
            node *const *src = k < 0 ? p->ws : p->Jws + 3 * k;
            node **dst = k < 0 ? b->w : Jw + 3 * k;
            for (int j = 0; j < 3; j++)
                dst[j] = add(d, dst[j], dot(d, Rj + 3 * j, src));
        }
        to_n(d, p->R, a, r);
    } else if (p && p->frame) {
        to_n(d, p->R, a, r);
    } else {
        memcpy(r, a, sizeof r);
    }
    node *off[3];
    if (b->frame)
        to_n(d, b->R, pv, off);
    else
        memcpy(off, pv, sizeof off);
    for (int j = 0; j < 3; j++)
        b->x[j] = sub(d, add(d, p ? p->x[j] : num(d, 0.0), r[j]), off[j]);
}

static void body_kinematics(dctx *d, mbs_body *b, int bi)
{
    lang_ctx *c = d->c;
    const int n = d->n;
    node **Jv = lang_alloc(c, 3 * (size_t)n * sizeof *Jv);
    node **Jw = NULL;
    if (b->frame) {
        Jw = lang_alloc(c, 3 * (size_t)n * sizeof *Jw);
        rotation(d, b, Jw, b->w);
    }
    if (b->joint)
        joint_pose(d, b, Jw);
    else
        for (int j = 0; j < 3; j++)
            b->x[j] = input(d, b->at[j]);
    if (b->frame) { /* the children's joints compose with these */
        b->Jws = lang_alloc(c, 3 * (size_t)n * sizeof *b->Jws);
        memcpy(b->Jws, Jw, 3 * (size_t)n * sizeof *Jw);
        memcpy(b->ws, b->w, sizeof b->ws);
    }
    point_jacobian(d, b->x, Jv, b->v);
    for (int j = 0; j < 3; j++)
        b->gv[j] = rate(d, b->v[j]);
    memcpy(b->vs, b->v, sizeof b->vs);
    b->Jv = Jv;
    b->Jv0 = lang_alloc(c, 3 * (size_t)n * sizeof *b->Jv0);
    for (int i = 0; i < 3 * n; i++)
        b->Jv0[i] = mbs_value(c, &d->ini, Jv[i]);
    fix_vec(d, lang_printf(c, "b%d_Jv", bi), Jv, 3 * n);
    fix_vec(d, lang_printf(c, "b%d_v", bi), b->v, 3);
    fix_vec(d, lang_printf(c, "b%d_gv", bi), b->gv, 3);
    if (!b->frame)
        return;
    for (int j = 0; j < 3; j++)
        b->gw[j] = rate(d, b->w[j]);
    b->Jw = Jw;
    b->Jw0 = lang_alloc(c, 3 * (size_t)n * sizeof *b->Jw0);
    for (int i = 0; i < 3 * n; i++)
        b->Jw0[i] = mbs_value(c, &d->ini, Jw[i]);
    memcpy(b->Rf, b->R, sizeof b->Rf);
    fix_vec(d, lang_printf(c, "b%d_R", bi), b->Rf, 9);
    fix_vec(d, lang_printf(c, "b%d_Jw", bi), Jw, 3 * n);
    fix_vec(d, lang_printf(c, "b%d_w", bi), b->w, 3);
    fix_vec(d, lang_printf(c, "b%d_gw", bi), b->gw, 3);
}

/* a point of a body (p in B; for a point mass and the ground, p in N): symbolic position */
static void attach_position(dctx *d, const mbs_attach *a, node *r[3])
{
    node *p[3];
    for (int j = 0; j < 3; j++)
        p[j] = input(d, a->p[j]);
    if (a->body < 0) {
        memcpy(r, p, sizeof p);
        return;
    }
    const mbs_body *b = &LVEC_AT(d->mb->bodies, mbs_body, a->body);
    for (int j = 0; j < 3; j++) {
        r[j] = b->x[j];
        if (!b->frame) /* a point mass has no frame: the offset is in N */
            r[j] = add(d, r[j], p[j]);
        else
            for (int i = 0; i < 3; i++)
                r[j] = add(d, r[j], mul(d, b->R[3 * i + j], p[i]));
    }
}

/* Q += J' f for a point with symbolic position r; its fixed position and velocity out */
static void point_force(dctx *d, node **Q, node *const J[], node *const f[3])
{
    for (int k = 0; k < d->n; k++)
        Q[k] = add(d, Q[k], dot(d, J + 3 * k, f));
}

static void point_fixes(dctx *d, const char *role, node *r[3], node **J, node *vel[3])
{
    point_jacobian(d, r, J, vel);
    fix_vec(d, lang_printf(d->c, "%s_r", role), r, 3);
    fix_vec(d, lang_printf(d->c, "%s_J", role), J, 3 * d->n);
    fix_vec(d, lang_printf(d->c, "%s_v", role), vel, 3);
}

/* ---- dense L D L' factorization in fixed quantities ---- */

/* A = L D L' (L unit lower triangular, below the diagonal in L; dinv = 1/D): one division
 * per column and no square root (Golub and Van Loan, "Matrix Computations", 4.1.2) */
static void cholesky(dctx *d, const char *tag, node **A, int n, node **L, node **dinv)
{
    node **T = lang_alloc(d->c, (size_t)n * n * sizeof *T); /* T_ij = L_ij D_j */
    for (int j = 0; j < n; j++) {
        node *s = A[j * n + j];
        for (int k = 0; k < j; k++)
            s = sub(d, s, mul(d, T[j * n + k], L[j * n + k]));
        dinv[j] = fix(d, lang_printf(d->c, "%s_inv%d", tag, j), lang_div(d->c, num(d, 1.0), s));
        for (int i = j + 1; i < n; i++) {
            node *t = A[i * n + j];
            for (int k = 0; k < j; k++)
                t = sub(d, t, mul(d, T[i * n + k], L[j * n + k]));
            T[i * n + j] = fix(d, lang_printf(d->c, "%s_T%d_%d", tag, i, j), t);
            L[i * n + j] = fix(d, lang_printf(d->c, "%s_L%d_%d", tag, i, j),
                               mul(d, T[i * n + j], dinv[j]));
        }
    }
}

/* x = A^-1 b with A's factors */
static void chol_solve(dctx *d, const char *tag, node **L, node **dinv, int n, node *const *b,
                       node **x)
{
    node **y = lang_alloc(d->c, (size_t)n * sizeof *y);
    for (int i = 0; i < n; i++) {
        node *s = b[i];
        for (int k = 0; k < i; k++)
            s = sub(d, s, mul(d, L[i * n + k], y[k]));
        y[i] = fix(d, lang_printf(d->c, "%s_y%d", tag, i), s);
    }
    for (int i = n - 1; i >= 0; i--) {
        node *s = mul(d, y[i], dinv[i]);
        for (int k = i + 1; k < n; k++)
            s = sub(d, s, mul(d, L[k * n + i], x[k]));
        x[i] = fix(d, lang_printf(d->c, "%s_x%d", tag, i), s);
    }
}

static node *dot_n(dctx *d, node *const *a, node *const *b, int n)
{
    node *s = num(d, 0.0);
    for (int i = 0; i < n; i++)
        s = add(d, s, mul(d, a[i], b[i]));
    return s;
}

/* ---- units of the multipliers ---- */

static const char *force_unit(lang_ctx *c, const char *unit, int rate)
{
    if (!unit)
        return "N m";
    if (!strcmp(unit, "m") || !strcmp(unit, "m/s"))
        return "N";
    if (!strcmp(unit, "rad") || !strcmp(unit, "rad/s") || !strcmp(unit, "1") ||
        !strcmp(unit, "1/s"))
        return "N m";
    return lang_printf(c, rate ? "W/(%s)" : "J/(%s)", unit);
}

/* The constraints' rows D (m x n) and their terms btot = c + Baumgarte's (m), with the
 * multipliers' units: D q'' + btot = 0. */
static void constraint_rows(dctx *d, node **D, node **btot)
{
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    const int n = d->n, m = mb->cons.n;
    if (symbolic(d)) {
        mb->con_D = D;
        mb->con_c = lang_alloc(c, (size_t)(m + 1) * sizeof *mb->con_c);
        mb->con_speeds = lang_alloc(c, (size_t)(m + 1) * sizeof *mb->con_speeds);
    }
    for (int r = 0; r < m; r++) {
        mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, r);
        node *f = k->sym ? k->sym : input(d, k->expr);
        int on_speeds = 0;
        for (int j = 0; j < n; j++)
            on_speeds |= uses(f, N_STATE, d->u[j]);
        if (on_speeds)
            for (int j = 0; j < n; j++)
                for (int l = j; l < n; l++) {
                    node *d2 = dq(d, dq(d, f, d->u[j]), d->u[l]);
                    if (!lang_is_num(d2, 0.0)) {
                        const mbs_coord *qj = &LVEC_AT(mb->coords, mbs_coord, j);
                        const mbs_coord *ql = &LVEC_AT(mb->coords, mbs_coord, l);
                        lang_fail(c, k->pos, "constraint '%s' is not linear in the speeds (its "
                                  "second derivative in %s and %s is not 0): a constraint is "
                                  "f(q, t) = 0 or linear in the speeds", k->name, qj->speed,
                                  ql->speed);
                    }
                }
        node *h = on_speeds ? f : rate(d, f);
        const char *tag = lang_printf(c, "c%d", r);
        const double f0 = mbs_value(c, &d->ini, f), h0 = mbs_value(c, &d->ini, h);
        double scale = 1.0;
        for (int j = 0; j < n; j++)
            scale = fmax(scale, fabs(d->ini.args[on_speeds ? d->u[j] : d->q[j]]));
        if (!mb->unchecked && !on_speeds && fabs(f0) > 1e-9 * scale)
            lang_fail(c, k->pos, "constraint '%s' does not hold at the initial state: its "
                      "value is %.17g, not 0 (change the initial values, or give "
                      "--project-init to move them onto the constraints)", k->name, f0);
        scale = 1.0;
        for (int j = 0; j < n; j++)
            scale = fmax(scale, fabs(d->ini.args[d->u[j]]));
        if (!mb->unchecked && fabs(h0) > 1e-9 * scale)
            lang_fail(c, k->pos, "constraint '%s' does not hold at the initial state: %s %.17g, "
                      "not 0 (change the initial speeds, or give --project-init to "
                      "move them onto the constraints)", k->name,
                      on_speeds ? "its value is" : "its rate is", h0);
        int first = -1;
        for (int j = 0; j < n; j++) {
            node *dj = dq(d, h, d->u[j]);
            d->D0[r * n + j] = mbs_value(c, &d->ini, dj);
            D[r * n + j] = fix(d, lang_printf(c, "%s_D%d", tag, j), dj);
            if (first < 0 && !lang_is_num(D[r * n + j], 0.0))
                first = j;
        }
        if (first < 0)
            lang_fail(c, k->pos, "constraint '%s' does not involve the %s of any coordinate",
                      k->name, on_speeds ? "speed" : "position");
        node *conv = rate(d, h);
        /* the speeds' terms of rate(h) are D u_dot; rate holds u, so conv is the rest */
        if (symbolic(d)) {
            mb->con_c[r] = conv;
            mb->con_speeds[r] = on_speeds;
            continue;
        }
        node *stab = num(d, 0.0);
        if (mb->alpha > 0 && !on_speeds) { /* Baumgarte on the positions' constraints */
            node *hf = fix(d, lang_printf(c, "%s_h", tag), h);
            stab = add(d, mul(d, num(d, 2.0 * mb->alpha), hf),
                       mul(d, num(d, mb->alpha * mb->alpha), fix(d, lang_printf(c, "%s_f", tag), f)));
        }
        btot[r] = fix(d, lang_printf(c, "%s_c", tag), add(d, conv, stab));
        const char *cu = k->prescribed >= 0
                             ? force_unit(c, LVEC_AT(mb->coords, mbs_coord, k->prescribed).unit, 0)
                         : k->unit ? force_unit(c, k->unit, on_speeds)
                                   : force_unit(c, LVEC_AT(mb->coords, mbs_coord, first).unit, 0);
        lang_formula *out = &LVEC_AT(c->m.auxs, lang_formula, k->aux);
        out->doc.unit = mb->values ? (on_speeds ? "speeds" : "holonomic") : cu;
        if (mb->values)
            out->expr = h;
        if (mb->values && !on_speeds) { /* its value f too, for a projection onto f = 0 */
            lang_formula *pf = lvec_push(c, &c->m.auxs, sizeof *pf);
            memset(pf, 0, sizeof *pf);
            pf->name = lang_printf(c, "%s:f", k->name);
            pf->pos = k->pos;
            pf->expr = f;
            pf->doc.unit = k->prescribed >= 0 ? "prescribed" : "position";
            out = &LVEC_AT(c->m.auxs, lang_formula, k->aux); /* the push may move it */
        }
        if (!out->doc.description)
            out->doc.description = lang_printf(c, "force of the constraint %s (%s)", k->name,
                                               on_speeds ? "on the speeds" : "holonomic");
    }
}

/* 1 when f(q, t) is 0 at the initial state and at three other states (the coordinates keep
 * a wheel on the ground by themselves) */
static int vanishes(dctx *d, node *f, double scale)
{
    mbs_initial at = d->ini;
    at.args = lang_alloc(d->c, ((size_t)at.nstates + 1) * sizeof *at.args);
    for (int trial = 0; trial < 4; trial++) {
        memcpy(at.args, d->ini.args, ((size_t)at.nstates + 1) * sizeof *at.args);
        for (int k = 0; k < d->n && trial; k++)
            at.args[d->q[k]] += 0.05 * trial + 0.013 * (k + 1) * trial;
        if (!(fabs(mbs_value(d->c, &at, f)) <= 1e-12 * scale))
            return 0;
    }
    return 1;
}

/* where a formula begins (a binary operation's position is its operator's) */
static lpos input_start(dctx *d, int k)
{
    const node *e = LVEC_AT(d->c->m.fixes, lang_formula, k).expr;
    while ((e->kind == N_BIN || e->kind == N_IF) && e->nargs > 0)
        e = e->args[0];
    return e->pos;
}

/* the length at the initial state of the vector of inputs v (-1: 0) */
static double length_at_start(dctx *d, const int v[3])
{
    double s = 0.0;
    for (int j = 0; j < 3; j++) {
        const double x = mbs_value(d->c, &d->ini, input(d, v[j]));
        s += x * x;
    }
    return sqrt(s);
}

/* a joint's axis (ax, ay, az) has a direction: not of length 0 at the initial state */
static void joint_axes(dctx *d)
{
    for (int bi = 0; bi < d->mb->bodies.n; bi++) {
        const mbs_body *b = &LVEC_AT(d->mb->bodies, mbs_body, bi);
        int given = b->joint != MBS_NO_JOINT && b->axisv[0] >= 0 &&
                    (b->slide_axis == 3 || (b->nrot > 0 && b->axis[0] == 3));
        if (given && !(length_at_start(d, b->axisv) > 0.0))
            lang_fail(d->c, input_start(d, b->axisv[0]), "the axis of the joint of '%s' has "
                      "length 0 at the initial state: give its direction (ax, ay, az), not "
                      "of length 0 (or x, y, z)", b->name);
    }
}

/* a wheel's radius is positive and its axis has a direction, at the initial state */
static void wheel_sizes(dctx *d, const mbs_wheel *wh)
{
    const double r = mbs_value(d->c, &d->ini, input(d, wh->radius));
    if (!(r > 0.0) && isfinite(r))
        lang_fail(d->c, input_start(d, wh->radius), "wheel '%s' has radius %.17g at the initial "
                  "state: a wheel's radius is positive", wh->name, r);
    const double a = length_at_start(d, wh->axis);
    if (!(a > 0.0) && isfinite(a))
        lang_fail(d->c, input_start(d, wh->axis[0]), "wheel '%s' has an axis of length 0 at the "
                  "initial state: give its axle's direction (x, y, z) in the frame of its body",
                  wh->name);
}

/* each wheel's constraints: the velocity of its contact point along x and y, and the height
 * of its lowest point unless the coordinates keep it on the ground */
static void wheels(dctx *d)
{
    mbs_model *mb = d->mb;
    for (int wi = 0; wi < mb->wheels.n; wi++) {
        const mbs_wheel *wh = &LVEC_AT(mb->wheels, mbs_wheel, wi);
        const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, wh->body);
        wheel_sizes(d, wh);
        node *a[3], *o[3], *height, *slip[2];
        for (int j = 0; j < 3; j++) {
            a[j] = input(d, wh->axis[j]);
            o[j] = input(d, wh->at[j]);
        }
        node *r = input(d, wh->radius);
        mbs_wheel_contact(d->c, b->x, b->R, b->vs, b->ws, r, a, o, &height, slip);
        for (int k = 0; k < mb->cons.n; k++) {
            mbs_constraint *con = &LVEC_AT(mb->cons, mbs_constraint, k);
            if (con->wheel == wi && con->part < 2)
                con->sym = slip[con->part];
        }
        if (!vanishes(d, height, fmax(1.0, fabs(mbs_value(d->c, &d->ini, r)))))
            mbs_wheel_normal(d->c, mb, wi, height);
    }
}

/* The multipliers by the Schur complement: with M's factor (L, dinv; of M + D'D when
 * regularized), q'' = a0 + X mu, X = M^-1 D', (D X) mu = -(D a0 + btot); lambda = mu, or
 * mu + btot for M + D'D (whose q'' solves M q'' = F + D' lambda as D q'' = -btot). */
static void multipliers(dctx *d, node **D, node **btot, node **a0, node **L, node **dinv,
                        int regularized, node **qdd)
{
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    const int n = d->n, m = mb->cons.n;
    node **X = lang_alloc(c, (size_t)(m * n + 1) * sizeof *X);
    node **A = lang_alloc(c, (size_t)(m * m + 1) * sizeof *A);
    node **b = lang_alloc(c, (size_t)(m + 1) * sizeof *b);
    for (int r = 0; r < m; r++) {
        b[r] = fix(d, lang_printf(c, "c%d_b", r),
                   lang_neg(c, add(d, dot_n(d, D + r * n, a0, n), btot[r])));
        chol_solve(d, lang_printf(c, "c%d_X", r), L, dinv, n, D + r * n, X + r * n);
    }
    for (int r = 0; r < m; r++)
        for (int s = 0; s <= r; s++) {
            A[r * m + s] = fix(d, lang_printf(c, "A%d_%d", r, s),
                               dot_n(d, D + r * n, X + s * n, n));
            A[s * m + r] = A[r * m + s];
        }
    node **LA = lang_alloc(c, (size_t)(m * m + 1) * sizeof *LA);
    node **dA = lang_alloc(c, (size_t)(m + 1) * sizeof *dA);
    node **lam = lang_alloc(c, (size_t)(m + 1) * sizeof *lam);
    cholesky(d, "A", A, m, LA, dA);
    chol_solve(d, "lam", LA, dA, m, b, lam);
    for (int i = 0; i < n; i++) {
        node *s = a0[i];
        for (int r = 0; r < m; r++)
            s = add(d, s, mul(d, X[r * n + i], lam[r]));
        qdd[i] = fix(d, lang_printf(c, "qdd%d", i), s);
    }
    for (int r = 0; r < m; r++) {
        mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, r);
        if (!mb->values) /* else the value h, set with the rows */
            LVEC_AT(c->m.auxs, lang_formula, k->aux).expr =
                regularized ? fix(d, lang_printf(c, "lam%d", r), add(d, lam[r], btot[r]))
                            : lam[r];
    }
}

/* ---- loads: gravity, springs, forces and torques ---- */

/* the function fi of the file at args: the call as written (to print), else its formula
 * with the file's inputs and functions inlined */
static node *call(dctx *d, int fi, node **args, int nargs)
{
    lang_ctx *c = d->c;
    const lang_func *fn = &LVEC_AT(c->m.funcs, lang_func, fi);
    if (symbolic(d)) {
        node *e = lang_node(c, N_UFUN, (lpos){0, 0});
        e->index = fi;
        e->name = fn->name;
        e->nargs = nargs;
        e->args = lang_alloc(c, (size_t)nargs * sizeof *e->args);
        memcpy(e->args, args, (size_t)nargs * sizeof *args);
        return e;
    }
    return lang_subst(c, expand(d, fn->body), args);
}

/* e with the derivation's own fixed quantities replaced by their values at the initial
 * state (each evaluated once, into val; NULL: not yet) and the file's inlined, for
 * mbs_value */
static node *at_initial(dctx *d, node *e, node **val)
{
    if (e->kind == N_FIX && e->index >= d->nfix0) {
        if (!val[e->index]) {
            node *x = at_initial(d, LVEC_AT(d->c->m.fixes, lang_formula, e->index).expr, val);
            val[e->index] = num(d, mbs_value(d->c, &d->ini, x));
        }
        return val[e->index];
    }
    if (e->nargs == 0)
        return expand(d, e);
    node *r = lang_node(d->c, e->kind, e->pos);
    *r = *e;
    r->args = lang_alloc(d->c, (size_t)e->nargs * sizeof *r->args);
    for (int i = 0; i < e->nargs; i++)
        r->args[i] = at_initial(d, e->args[i], val);
    return r->kind == N_UFUN ? expand(d, r) : r;
}

/* G(x) or F(x, 0) of the file's function fi at the number x, at the initial parameters */
static double law_at(dctx *d, int fi, int nargs, double x)
{
    node *args[2] = {num(d, x), num(d, 0.0)};
    return mbs_value(d->c, &d->ini, call(d, fi, args, nargs));
}

/* A spring's energy=G is the integral of its law=F at v = 0: dG/dx by central differences
 * (a step 1e-5 of the length's scale: an error near 1e-10 of it) against F(x, 0) at the
 * initial stretch x0 and at x0 -+ a tenth of the scale, within 1e-6 of the largest of them;
 * else refused at the spring, both values named. l: its length's formula. */
static void check_energy(dctx *d, const mbs_spring *sp, node *l, node *stretch)
{
    node **val = lang_alloc(d->c, ((size_t)d->c->m.fixes.n + 1) * sizeof *val);
    memset(val, 0, ((size_t)d->c->m.fixes.n + 1) * sizeof *val);
    const double len = mbs_value(d->c, &d->ini, at_initial(d, l, val));
    const double x0 = mbs_value(d->c, &d->ini, at_initial(d, stretch, val));
    const double scale = fmax(fmax(fabs(len), fabs(len - x0)), 1e-3);
    const double h = 1e-5 * scale;
    double dg[3], f[3], big = 0.0;
    for (int i = 0; i < 3; i++) {
        const double x = x0 + (i - 1) * 0.1 * scale;
        dg[i] = (law_at(d, sp->energy, 1, x + h) - law_at(d, sp->energy, 1, x - h)) / (2 * h);
        f[i] = law_at(d, sp->law, 2, x);
        big = fmax(big, fmax(fabs(dg[i]), fabs(f[i])));
    }
    for (int k = 0; k < 3; k++) {
        const int i = (k + 1) % 3; /* the initial stretch first */
        if (!(fabs(dg[i] - f[i]) <= 1e-6 * big))
            lang_fail(d->c, sp->pos, "spring '%s': energy=%s is not the integral of law=%s: "
                      "at the stretch x = %.10g m, d%s/dx = %.10g N but %s(x, 0) = %.10g N "
                      "(the energy is G(x) with G' = F(x, 0))", sp->name, sp->energy_name,
                      sp->law_name, x0 + (i - 1) * 0.1 * scale, sp->energy_name, dg[i],
                      sp->law_name, f[i]);
    }
}

/* A body's inertia tensor about its mass centre in B (row-major 3 x 3), its entries by
 * in (input_ref or input): as written, or given about the point r of B (from the mass
 * centre) and moved there by the parallel-axis theorem I_G = I_P - m (|r|^2 E - r r')
 * (Goldstein, Classical Mechanics, 3rd ed., sec. 5.3). */
static void centre_inertia(dctx *d, const mbs_body *b, node *(*in)(dctx *, int), node *I[9])
{
    static const int at[9] = {0, 3, 4, 3, 1, 5, 4, 5, 2}; /* Ixx Ixy Ixz; Ixy Iyy Iyz; ... */
    for (int k = 0; k < 9; k++)
        I[k] = in(d, b->inertia[at[k]]);
    if (b->about[0] < 0)
        return;
    node *m = in(d, b->mass), *r[3];
    for (int j = 0; j < 3; j++)
        r[j] = in(d, b->about[j]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            node *shift = i == j ? add(d, mul(d, r[(i + 1) % 3], r[(i + 1) % 3]),
                                       mul(d, r[(i + 2) % 3], r[(i + 2) % 3]))
                                 : lang_neg(d->c, mul(d, r[i], r[j]));
            I[3 * i + j] = sub(d, I[3 * i + j], mul(d, m, shift));
        }
}

static node *loads(dctx *d, node **Q)
{
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    const int n = d->n;
    node *V = num(d, 0.0);
    node *g[3];
    for (int j = 0; j < 3; j++)
        g[j] = input_ref(d, mb->gravity[j]);
    for (int bi = 0; bi < mb->bodies.n; bi++) {
        mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, bi);
        node *x[3];
        memcpy(x, b->x, sizeof x);
        fix_vec(d, lang_printf(c, "b%d_x", bi), x, 3);
        V = sub(d, V, mul(d, input_ref(d, b->mass), dot(d, g, x)));
    }
    for (int si = 0; si < mb->springs.n; si++) {
        const mbs_spring *sp = &LVEC_AT(mb->springs, mbs_spring, si);
        node *ra[3], *rb[3], *va[3], *vb[3], *dd[3], *fa[3], *fb[3];
        node **Ja = lang_alloc(c, 3 * (size_t)n * sizeof *Ja);
        node **Jb = lang_alloc(c, 3 * (size_t)n * sizeof *Jb);
        attach_position(d, &sp->a, ra);
        attach_position(d, &sp->b, rb);
        point_fixes(d, lang_printf(c, "s%da", si), ra, Ja, va);
        point_fixes(d, lang_printf(c, "s%db", si), rb, Jb, vb);
        for (int j = 0; j < 3; j++)
            dd[j] = fix(d, lang_printf(c, "s%d_d%d", si, j), sub(d, rb[j], ra[j]));
        node *l = fix(d, lang_printf(c, "s%d_l", si), lang_fun1(c, F_SQRT, dot(d, dd, dd)));
        node *stretch = sub(d, l, input_ref(d, sp->l0));
        node *fm = sp->k >= 0 ? mul(d, input_ref(d, sp->k), stretch) : num(d, 0.0);
        node *rate = NULL; /* dl/dt = d.(vb - va) / l */
        if (sp->c >= 0 || sp->law >= 0) {
            node *dv[3];
            for (int j = 0; j < 3; j++)
                dv[j] = sub(d, vb[j], va[j]);
            rate = lang_div(c, dot(d, dd, dv), l);
        }
        if (sp->c >= 0)
            fm = add(d, fm, mul(d, input_ref(d, sp->c), rate));
        if (sp->law >= 0 && sp->energy >= 0 && !mb->unchecked)
            check_energy(d, sp, l, stretch);
        if (sp->law >= 0) {
            stretch = fix(d, lang_printf(c, "s%d_x", si), stretch);
            node *args[2] = {stretch, fix(d, lang_printf(c, "s%d_v", si), rate)};
            fm = call(d, sp->law, args, 2);
        }
        fm = fix(d, lang_printf(c, "s%d_f", si), lang_div(c, fm, l));
        for (int j = 0; j < 3; j++) {
            fa[j] = fix(d, lang_printf(c, "s%d_fa%d", si, j), mul(d, fm, dd[j]));
            fb[j] = lang_neg(c, fa[j]);
        }
        point_force(d, Q, Ja, fa);
        point_force(d, Q, Jb, fb);
        if (sp->k >= 0)
            V = add(d, V, mul(d, mul(d, num(d, 0.5), input_ref(d, sp->k)), mul(d, stretch, stretch)));
        if (sp->energy >= 0)
            V = add(d, V, call(d, sp->energy, &stretch, 1));
    }
    for (int li = 0; li < mb->loads.n; li++) {
        const mbs_load *ld = &LVEC_AT(mb->loads, mbs_load, li);
        const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, ld->body);
        node *f[3], *fn[3];
        for (int j = 0; j < 3; j++)
            f[j] = input_ref(d, ld->f[j]);
        if (ld->torque) {
            if (ld->in_body)
                memcpy(fn, f, sizeof f);
            else
                to_b(d, b->Rf, f, fn);
            point_force(d, Q, b->Jw, fn);
            continue;
        }
        if (ld->in_body)
            to_n(d, b->Rf, f, fn);
        else
            memcpy(fn, f, sizeof f);
        const mbs_attach at = {ld->body, {ld->at[0], ld->at[1], ld->at[2]}};
        node *r[3], *v[3];
        node **J = lang_alloc(c, 3 * (size_t)n * sizeof *J);
        attach_position(d, &at, r);
        point_fixes(d, lang_printf(c, "f%d", li), r, J, v);
        point_force(d, Q, J, fn);
    }
    return V;
}

/* the coordinates' rates: their speeds, or with declared speeds the formulas of the rate
 * lines, qd = W(q, t) u + qd_t, which must be linear in the speeds */
#define MBS_MAX_SPEEDS_CHECK 256 /* speeds set to 0 for the check of the rates */
static void kinematic_equations(dctx *d)
{
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    const int n = d->n;
    d->qd = lang_alloc(c, (size_t)n * sizeof *d->qd);
    for (int k = 0; k < n; k++)
        d->qd[k] = ref(d, N_STATE, d->u[k]);
    if (!mb->speeds.n)
        return;
    d->W = lang_alloc(c, (size_t)n * n * sizeof *d->W);
    for (int k = 0; k < n; k++) {
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, k);
        d->qd[k] = input(d, q->kin);
        double *args = d->ini.args, save[MBS_MAX_SPEEDS_CHECK];
        for (int j = 0; j < n && j < MBS_MAX_SPEEDS_CHECK; j++) {
            save[j] = args[d->u[j]];
            args[d->u[j]] = 0.0;
        }
        const double rest = mbs_value(c, &d->ini, d->qd[k]);
        for (int j = 0; j < n && j < MBS_MAX_SPEEDS_CHECK; j++)
            args[d->u[j]] = save[j];
        if (n <= MBS_MAX_SPEEDS_CHECK && rest != 0.0 && !isnan(rest))
            lang_fail(c, q->kin_pos, "the rate of '%s' is %.17g with all speeds 0 at the "
                      "initial state: a rate is W(q) u, a sum of the speeds times formulas of "
                      "the coordinates", q->name, rest);
        for (int j = 0; j < n; j++) {
            d->W[k * n + j] = dq(d, d->qd[k], d->u[j]);
            for (int l = 0; l < n; l++)
                if (!lang_is_num(dq(d, d->W[k * n + j], d->u[l]), 0.0))
                    lang_fail(c, q->kin_pos, "the rate of '%s' is not linear in the speeds (its "
                              "second derivative in %s and %s is not 0)", q->name,
                              LVEC_AT(mb->coords, mbs_coord, j).speed,
                              LVEC_AT(mb->coords, mbs_coord, l).speed);
        }
    }
}

static void describe(dctx *d)
{
    lang_ctx *c = d->c;
    mbs_model *mb = d->mb;
    const char *s = "Mechanism (equations of motion by TMT): coordinates";
    for (int i = 0; i < mb->coords.n; i++) {
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        s = mb->speeds.n ? lang_printf(c, "%s %s%s", s, q->name,
                                       i + 1 < mb->coords.n ? "," : "; speeds")
                         : lang_printf(c, "%s %s (speed %s)%s", s, q->name, q->speed,
                                       i + 1 < mb->coords.n ? "," : ";");
    }
    for (int i = 0; i < mb->speeds.n; i++)
        s = lang_printf(c, "%s %s%s", s, LVEC_AT(mb->speeds, mbs_speed, i).name,
                        i + 1 < mb->speeds.n ? "," : ";");
    for (int i = 0; i < mb->coords.n && mb->speeds.n; i++) {
        const mbs_coord *q = &LVEC_AT(mb->coords, mbs_coord, i);
        s = lang_printf(c, "%s%s %s' = %s%s", s, i ? "" : " kinematic equations", q->name,
                        mbs_formula_text(c, LVEC_AT(c->m.fixes, lang_formula, q->kin).expr),
                        i + 1 < mb->coords.n ? "," : ";");
    }
    s = lang_printf(c, "%s bodies", s);
    for (int i = 0; i < mb->bodies.n; i++) {
        const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, i);
        s = lang_printf(c, "%s %s (%s)%s", s, b->name, b->point ? "point mass" : "rigid body",
                        i + 1 < mb->bodies.n ? "," : ";");
    }
    if (mb->cons.n == 0)
        s = lang_printf(c, "%s no constraints.", s);
    for (int i = 0; i < mb->cons.n; i++) {
        const mbs_constraint *k = &LVEC_AT(mb->cons, mbs_constraint, i);
        s = lang_printf(c, "%s%s %s (multiplier %s)%s", s, i ? "" : " constraints", k->name,
                        k->name, i + 1 < mb->cons.n ? "," : ".");
    }
    lang_model *m = &c->m;
    m->description = m->description && *m->description
                         ? lang_printf(c, "%s\n%s", m->description, s)
                         : s;
}

void mbs_derive(lang_ctx *c, mbs_model *mb)
{
    lang_model *m = &c->m;
    dctx d = {c, mb, mb->coords.n, NULL, NULL, NULL, NULL, m->fixes.n, 0, {NULL, NULL, 0}, NULL};
    const int n = d.n;
    mbs_initial_values(c, &d.ini);
    d.q = lang_alloc(c, (size_t)n * sizeof *d.q);
    d.u = lang_alloc(c, (size_t)n * sizeof *d.u);
    for (int i = 0; i < n; i++) {
        d.q[i] = LVEC_AT(mb->coords, mbs_coord, i).q;
        d.u[i] = LVEC_AT(mb->coords, mbs_coord, i).u;
    }
    mb->expanded = lang_alloc(c, ((size_t)m->fixes.n + 1) * sizeof *mb->expanded);
    memset(mb->expanded, 0, ((size_t)m->fixes.n + 1) * sizeof *mb->expanded);
    mb->ordercap = m->fixes.n + 256;
    mb->order = lang_alloc(c, (size_t)mb->ordercap * sizeof *mb->order);
    memcpy(mb->order, m->fix_order, (size_t)m->fixes.n * sizeof *mb->order);
    mb->norder = m->fixes.n;
    kinematic_equations(&d);
    joint_axes(&d);
    for (int bi = 0; bi < mb->bodies.n; bi++)
        body_kinematics(&d, &LVEC_AT(mb->bodies, mbs_body, bi), bi);
    wheels(&d);
    /* M and F */
    node **M = lang_alloc(c, (size_t)n * n * sizeof *M);
    node **F = lang_alloc(c, (size_t)n * sizeof *F);
    for (int i = 0; i < n * n; i++)
        M[i] = num(&d, 0.0);
    for (int i = 0; i < n; i++)
        F[i] = num(&d, 0.0);
    node *g[3];
    for (int j = 0; j < 3; j++)
        g[j] = input_ref(&d, mb->gravity[j]);
    node *T = num(&d, 0.0);
    for (int bi = 0; bi < mb->bodies.n; bi++) {
        mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, bi);
        node *ms = input_ref(&d, b->mass);
        node *fv[3], *fw[3], *Iw[3], *Igw[3], *I[9];
        for (int j = 0; j < 3; j++)
            fv[j] = fix(&d, lang_printf(c, "b%d_fv%d", bi, j), mul(&d, ms, sub(&d, g[j], b->gv[j])));
        T = add(&d, T, mul(&d, ms, dot(&d, b->v, b->v)));
        for (int i = 0; i < n; i++) {
            F[i] = add(&d, F[i], dot(&d, b->Jv + 3 * i, fv));
            for (int k = 0; k <= i; k++)
                M[i * n + k] = add(&d, M[i * n + k],
                                   mul(&d, ms, dot(&d, b->Jv + 3 * i, b->Jv + 3 * k)));
        }
        if (b->point)
            continue;
        centre_inertia(&d, b, input_ref, I);
        for (int j = 0; j < 3; j++) {
            Iw[j] = fix(&d, lang_printf(c, "b%d_Iw%d", bi, j), dot(&d, I + 3 * j, b->w));
            Igw[j] = dot(&d, I + 3 * j, b->gw);
        }
        for (int j = 0; j < 3; j++) {
            const int a = (j + 1) % 3, e = (j + 2) % 3;
            node *gyro = sub(&d, mul(&d, b->w[a], Iw[e]), mul(&d, b->w[e], Iw[a]));
            fw[j] = fix(&d, lang_printf(c, "b%d_fw%d", bi, j),
                        lang_neg(c, add(&d, Igw[j], gyro)));
        }
        T = add(&d, T, dot(&d, b->w, Iw));
        for (int i = 0; i < n; i++) {
            F[i] = add(&d, F[i], dot(&d, b->Jw + 3 * i, fw));
            for (int k = 0; k <= i; k++) {
                node *IJ[3];
                for (int j = 0; j < 3; j++)
                    IJ[j] = dot(&d, I + 3 * j, b->Jw + 3 * k);
                M[i * n + k] = add(&d, M[i * n + k], dot(&d, b->Jw + 3 * i, IJ));
            }
        }
    }
    double *M0 = lang_alloc(c, (size_t)n * n * sizeof *M0);
    memset(M0, 0, (size_t)n * n * sizeof *M0);
    for (int bi = 0; bi < mb->bodies.n; bi++) {
        const mbs_body *b = &LVEC_AT(mb->bodies, mbs_body, bi);
        const double ms = mbs_value(c, &d.ini, input(&d, b->mass));
        double I[9] = {0};
        node *Ie[9];
        if (!b->point)
            centre_inertia(&d, b, input, Ie);
        for (int k = 0; k < 9 && !b->point; k++)
            I[k] = mbs_value(c, &d.ini, Ie[k]);
        mbs_check_body(c, b, ms, b->point ? NULL : I);
        for (int i = 0; i < n; i++)
            for (int k = 0; k < n; k++) {
                double v = 0.0;
                for (int j = 0; j < 3; j++) {
                    v += ms * b->Jv0[3 * i + j] * b->Jv0[3 * k + j];
                    for (int l = 0; l < 3 && !b->point; l++)
                        v += b->Jw0[3 * i + j] * I[3 * j + l] * b->Jw0[3 * k + l];
                }
                M0[i * n + k] += v;
            }
    }
    node *V = loads(&d, F);
    for (int i = 0; i < n; i++) {
        F[i] = fix(&d, lang_printf(c, "F%d", i), F[i]);
        for (int k = 0; k <= i; k++) {
            M[i * n + k] = fix(&d, lang_printf(c, "M%d_%d", i, k), M[i * n + k]);
            M[k * n + i] = M[i * n + k];
        }
    }
    const int nc = mb->cons.n;
    node **D = lang_alloc(c, ((size_t)nc * n + 1) * sizeof *D);
    node **btot = lang_alloc(c, ((size_t)nc + 1) * sizeof *btot);
    d.D0 = lang_alloc(c, ((size_t)nc * n + 1) * sizeof *d.D0);
    if (nc)
        constraint_rows(&d, D, btot);
    /* M singular where the constraints fix the motion (the radial direction of Euler
     * parameters): M + D'D instead, positive definite when [M; D] has full rank; derive
     * prints M and D and says so (mbs_text.c) */
    const int regularized = nc && !mbs_positive_definite(c, M0, n);
    for (int i = 0; i < n && regularized; i++)
        for (int k = 0; k <= i; k++) {
            if (!symbolic(&d)) {
                node *s = M[i * n + k];
                for (int r = 0; r < nc; r++)
                    s = add(&d, s, mul(&d, D[r * n + i], D[r * n + k]));
                M[i * n + k] = M[k * n + i] = fix(&d, lang_printf(c, "Mr%d_%d", i, k), s);
            }
            for (int r = 0; r < nc; r++)
                M0[i * n + k] += d.D0[r * n + i] * d.D0[r * n + k];
            M0[k * n + i] = M0[i * n + k];
        }
    mbs_check_initial(c, mb, M0, d.D0);
    if (symbolic(&d)) { /* dynkit derive: the formulas of M, F and the constraints */
        mb->M = M;
        mb->F = F;
        mb->regularized = regularized;
        return;
    }
    node **L = lang_alloc(c, (size_t)n * n * sizeof *L);
    node **dinv = lang_alloc(c, (size_t)n * sizeof *dinv);
    node **a0 = lang_alloc(c, (size_t)n * sizeof *a0);
    node **qdd = lang_alloc(c, (size_t)n * sizeof *qdd);
    cholesky(&d, "M", M, n, L, dinv);
    chol_solve(&d, "a0", L, dinv, n, F, a0);
    if (nc)
        multipliers(&d, D, btot, a0, L, dinv, regularized, qdd);
    else
        memcpy(qdd, a0, (size_t)n * sizeof *qdd);
    for (int i = 0; i < n; i++) {
        LVEC_AT(m->states, lang_state, d.q[i]).rhs =
            d.W ? input_ref(&d, LVEC_AT(mb->coords, mbs_coord, i).kin) : ref(&d, N_STATE, d.u[i]);
        LVEC_AT(m->states, lang_state, d.u[i]).rhs = qdd[i];
    }
    T = fix(&d, "T", mul(&d, num(&d, 0.5), T));
    V = fix(&d, "V", V);
    if (mb->aux_kinetic >= 0)
        LVEC_AT(m->auxs, lang_formula, mb->aux_kinetic).expr = T;
    if (mb->aux_potential >= 0)
        LVEC_AT(m->auxs, lang_formula, mb->aux_potential).expr = V;
    if (mb->aux_energy >= 0)
        LVEC_AT(m->auxs, lang_formula, mb->aux_energy).expr = add(&d, T, V);
    mbs_cse(c, mb, d.nfix0);
    m->fix_order = mb->order;
    describe(&d);
}
