/* SPDX-License-Identifier: BSD-3-Clause */
/* eq_type.c — the type of an equilibrium from its eigenvalues, or of a map's fixed point
 * from its multipliers (Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., secs.
 * 2.1-2.2 and 3.1): each eigenvalue counts as stable (re < -tol; a multiplier |mu| < 1 -
 * tol), unstable (re > tol; |mu| > 1 + tol) or central; hyperbolic points are nodes
 * (all on one side, all real), foci (one side, a complex pair), saddles or saddle-foci
 * (both sides); a centre has every eigenvalue central and in complex pairs, a
 * saddle-centre such pairs beside stable and unstable ones; anything else with a central
 * eigenvalue is non-hyperbolic. */
#include <math.h>

#include "dynkit/equilibria.h"

const char *dyn_eq_type_name(dyn_eq_type t)
{
    switch (t) {
    case DYN_EQ_STABLE_NODE: return "stable node";
    case DYN_EQ_UNSTABLE_NODE: return "unstable node";
    case DYN_EQ_STABLE_FOCUS: return "stable focus";
    case DYN_EQ_UNSTABLE_FOCUS: return "unstable focus";
    case DYN_EQ_SADDLE: return "saddle";
    case DYN_EQ_SADDLE_FOCUS: return "saddle-focus";
    case DYN_EQ_CENTRE: return "centre";
    case DYN_EQ_SADDLE_CENTRE: return "saddle-centre";
    case DYN_EQ_NONHYPERBOLIC: return "non-hyperbolic";
    default: return "unclassified";
    }
}

dyn_eq_type dyn_eq_classify(int k, const double *re, const double *im, int map, double tol,
                            int dims[3])
{
    int s = 0, u = 0, c = 0, complex_hyp = 0, real_central = 0;
    for (int i = 0; i < k; i++) {
        const double x = map ? hypot(re[i], im[i]) - 1.0 : re[i];
        if (x < -tol || x > tol) {
            s += x < -tol;
            u += x > tol;
            complex_hyp |= im[i] != 0.0;
        } else {
            c++;
            real_central |= im[i] == 0.0;
        }
    }
    if (dims) {
        dims[0] = s;
        dims[1] = u;
        dims[2] = c;
    }
    if (k == 0)
        return DYN_EQ_UNCLASSIFIED;
    if (c > 0 && !real_central && s == 0 && u == 0)
        return DYN_EQ_CENTRE;
    if (c > 0 && !real_central && s > 0 && u > 0)
        return DYN_EQ_SADDLE_CENTRE;
    if (c > 0)
        return DYN_EQ_NONHYPERBOLIC;
    if (u == 0)
        return complex_hyp ? DYN_EQ_STABLE_FOCUS : DYN_EQ_STABLE_NODE;
    if (s == 0)
        return complex_hyp ? DYN_EQ_UNSTABLE_FOCUS : DYN_EQ_UNSTABLE_NODE;
    return complex_hyp ? DYN_EQ_SADDLE_FOCUS : DYN_EQ_SADDLE;
}
