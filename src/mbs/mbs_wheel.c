/* SPDX-License-Identifier: BSD-3-Clause */
/* A thin disk rolling without slip on the flat ground z = 0 (docs/mechanisms.md, "Wheels";
 * the contact of Neimark and Fufaev, "Dynamics of Nonholonomic Systems", ch. 1, and of
 * Meijaard et al., Proc. R. Soc. A 463 (2007) 1955, appendix A): with a the unit axis of
 * the disk in N and e_z up, the disk's lowest point is P = C - r k with
 *   k = (e_z - a_z a) / s,  s = |e_z - a_z a| = sqrt(a_x^2 + a_y^2)
 * (k the unit vector in the disk's plane that points up), so its height is C_z - r s; the
 * velocity of the body's point at P is v_G + w x (P - G). The disk must not lie flat
 * (s = 0). */
#include "mbs/mbs_internal.h"

static node *add(lang_ctx *c, node *a, node *b) { return lang_add(c, a, b); }
static node *sub(lang_ctx *c, node *a, node *b) { return lang_sub(c, a, b); }
static node *mul(lang_ctx *c, node *a, node *b) { return lang_mul(c, a, b); }

/* R' v: a vector of B in N */
static void to_n(lang_ctx *c, node *const R[9], node *const v[3], node *out[3])
{
    for (int j = 0; j < 3; j++)
        out[j] = add(c, add(c, mul(c, R[j], v[0]), mul(c, R[3 + j], v[1])), mul(c, R[6 + j], v[2]));
}

void mbs_wheel_contact(lang_ctx *c, node *const G[3], node *const R[9], node *const vG[3],
                       node *const wB[3], node *r, node *const a[3], node *const o[3],
                       node **height, node *slip[2])
{
    /* the unit axis in N: R' a / |a| (R is orthogonal) */
    node *len = lang_fun1(c, F_SQRT, add(c, add(c, mul(c, a[0], a[0]), mul(c, a[1], a[1])),
                                         mul(c, a[2], a[2])));
    node *au[3], *an[3];
    for (int j = 0; j < 3; j++)
        au[j] = lang_div(c, a[j], len);
    to_n(c, R, au, an);
    node *s = lang_fun1(c, F_SQRT, add(c, mul(c, an[0], an[0]), mul(c, an[1], an[1])));
    /* P - C = -r k */
    node *rk[3];
    node *azs = lang_div(c, mul(c, r, an[2]), s);
    rk[0] = lang_neg(c, mul(c, azs, an[0]));
    rk[1] = lang_neg(c, mul(c, azs, an[1]));
    rk[2] = mul(c, r, s);
    node *on[3];
    to_n(c, R, o, on); /* C - G */
    *height = sub(c, add(c, G[2], on[2]), rk[2]);
    node *rho[3], *w[3];
    for (int j = 0; j < 3; j++)
        rho[j] = sub(c, on[j], rk[j]); /* P - G */
    to_n(c, R, wB, w);
    slip[0] = add(c, vG[0], sub(c, mul(c, w[1], rho[2]), mul(c, w[2], rho[1])));
    slip[1] = add(c, vG[1], sub(c, mul(c, w[2], rho[0]), mul(c, w[0], rho[2])));
}
