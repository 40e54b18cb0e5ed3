/* SPDX-License-Identifier: BSD-3-Clause */
/* The cosine and sine of a rotation's angle, with whole quarter turns taken out exactly:
 * an angle written j pi/2 + x or j pi/2 - x (j an integer, |j| <= 8; `rot y:pi-a`) gives
 * cos and sin of x by the reduction formulas cos(j pi/2 + x) = cos(x), -sin(x), -cos(x),
 * sin(x) for j = 0, 1, 2, 3 mod 4 (and sin likewise), not cos and sin of the rounded sum:
 * sin(fl(pi) - 0) is 1.2e-16, not 0, which would tilt a hanging body by rounding and
 * make its symmetric equilibria imperfect (a pitchfork seen as two folds). */
#include <float.h>
#include <math.h>

#include "mbs/mbs_internal.h"

#define HALF_PI 1.57079632679489661923

/* j when v is the double nearest j pi/2 (within 4 ulp), |j| <= 8; else -100 */
static int quarter_turns(double v)
{
    const double j = nearbyint(v / HALF_PI);
    if (fabs(j) > 8.0 || fabs(v - j * HALF_PI) > 4.0 * DBL_EPSILON * fmax(fabs(v), 1.0))
        return -100;
    return (int)j;
}

/* whether e is made of numbers alone (pi/2, -pi), its value into v */
static int constant(const node *e, double *v)
{
    double a, b;
    switch (e->kind) {
    case N_NUM:
        *v = e->num;
        return 1;
    case N_NEG:
        if (!constant(e->args[0], &a))
            return 0;
        *v = -a;
        return 1;
    case N_BIN:
        if (!constant(e->args[0], &a) || !constant(e->args[1], &b))
            return 0;
        *v = lang_apply_bin(e->op, a, b);
        return 1;
    default:
        return 0;
    }
}

/* j when e is the number j pi/2, else -100 */
static int constant_turns(const node *e)
{
    double v;
    return constant(e, &v) ? quarter_turns(v) : -100;
}

/* angle = j pi/2 + sign * rest (rest NULL: 0): j, or -100 when it is not of that form */
static int split_angle(node *angle, node **rest, int *sign)
{
    *rest = NULL;
    *sign = 1;
    const int whole = constant_turns(angle);
    if (whole != -100 || angle->kind != N_BIN || (angle->op != OP_ADD && angle->op != OP_SUB))
        return whole;
    node *a = angle->args[0], *b = angle->args[1];
    const int ja = constant_turns(a), jb = constant_turns(b);
    if (ja != -100) {
        *rest = b;
        *sign = angle->op == OP_ADD ? 1 : -1;
        return ja;
    }
    if (jb != -100) {
        *rest = a;
        return angle->op == OP_ADD ? jb : -jb;
    }
    return -100;
}

void mbs_cos_sin(lang_ctx *c, node *angle, node **cs, node **sn)
{
    node *rest;
    int sign;
    const int j = split_angle(angle, &rest, &sign);
    if (j == -100) {
        *cs = lang_fun1(c, F_COS, angle);
        *sn = lang_fun1(c, F_SIN, angle);
        return;
    }
    /* cos and sin of x = sign * rest */
    node *cx = rest ? lang_fun1(c, F_COS, rest) : lang_num(c, 1.0);
    node *sx = rest ? lang_fun1(c, F_SIN, rest) : lang_num(c, 0.0);
    if (sign < 0)
        sx = lang_neg(c, sx);
    switch (((j % 4) + 4) % 4) {
    case 0: *cs = cx; *sn = sx; break;
    case 1: *cs = lang_neg(c, sx); *sn = cx; break;
    case 2: *cs = lang_neg(c, cx); *sn = lang_neg(c, sx); break;
    default: *cs = sx; *sn = lang_neg(c, cx); break;
    }
}
