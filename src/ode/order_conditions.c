/* SPDX-License-Identifier: BSD-3-Clause */
/* Order conditions of Runge–Kutta tables through the rooted trees up to order 8.
 *
 * Reference: J. C. Butcher, "Numerical Methods for Ordinary Differential Equations", 3rd
 * ed., sec. 31-32 (rooted trees, elementary weights, density); Hairer, Nørsett & Wanner I,
 * sec. II.2, Theorem 2.13: a method has order p iff sum_i b_i Phi_i(t) = 1/gamma(t) for
 * every rooted tree t with |t| <= p. For a tree t = [t_1, ..., t_m] (a root with the
 * subtrees t_k), Phi_i(t) = prod_k (A Phi(t_k))_i with Phi_i(leaf) = 1, and
 * gamma(t) = |t| prod_k gamma(t_k). The trees are generated as multisets of smaller trees
 * (1, 1, 2, 4, 9, 20, 48, 115 trees of orders 1..8: 200 in all). The row-sum condition
 * c_i = sum_j a_ij, which the simplified conditions assume, is checked as well.
 */
#include <math.h>

#include "dynkit/ode.h"

#define MAX_ORDER 8
#define MAX_TREES 200
#define PHI_SIZE (MAX_TREES * 16) /* room for all 200 trees of a table of 16 stages */

typedef struct tree {
    int order;
    double gamma;
    int nchild;
    int child[MAX_ORDER]; /* indices of the subtrees, non-decreasing */
} tree;

typedef struct forest {
    int count;
    int first[MAX_ORDER + 2]; /* trees of order p are first[p] .. first[p + 1] - 1 */
    tree t[MAX_TREES];
} forest;

/* Add every tree of order `order` whose root has the subtrees chosen so far (cur, ncur)
 * plus subtrees of total order `left`, each with index >= min_index. */
static void grow(forest *f, int order, int left, int min_index, int *cur, int ncur)
{
    if (left == 0) {
        if (f->count >= MAX_TREES)
            return;
        tree *t = &f->t[f->count++];
        t->order = order;
        t->nchild = ncur;
        t->gamma = order;
        for (int k = 0; k < ncur; k++) {
            t->child[k] = cur[k];
            t->gamma *= f->t[cur[k]].gamma;
        }
        return;
    }
    if (ncur >= MAX_ORDER)
        return; /* cannot happen: a tree of order <= 8 has at most 7 subtrees */
    for (int i = min_index; i < f->first[order]; i++) {
        if (f->t[i].order > left)
            break; /* trees are sorted by order */
        cur[ncur] = i;
        grow(f, order, left - f->t[i].order, i, cur, ncur + 1);
    }
}

static void plant(forest *f, int pmax)
{
    int cur[MAX_ORDER];
    f->count = 0;
    for (int p = 1; p <= pmax; p++) {
        f->first[p] = f->count;
        grow(f, p, p - 1, 0, cur, 0);
    }
    f->first[pmax + 1] = f->count;
}

static double residual(const dyn_tableau *tab, const double *w, int p)
{
    const int s = tab->stages;
    const double *a = tab->a, *c = tab->c;
    if (s < 1 || !a || !w || !c)
        return INFINITY;
    if (p > MAX_ORDER)
        p = MAX_ORDER;
    static const int trees_up_to[MAX_ORDER + 1] = {0, 1, 2, 4, 8, 17, 37, 85, 200};
    while (p > 1 && trees_up_to[p] * s > PHI_SIZE)
        p--; /* long tables: as many orders as the buffers hold (order 6 for 64 stages) */
    if (trees_up_to[p > 0 ? p : 0] * s > PHI_SIZE)
        return INFINITY;
    double worst = 0.0;
    for (int i = 0; i < s; i++) {
        double row = 0.0;
        for (int j = 0; j < s; j++)
            row += a[i * s + j];
        worst = fmax(worst, fabs(row - c[i]));
    }
    if (p < 1)
        return worst;
    forest f;
    plant(&f, p);
    double phi[PHI_SIZE];  /* Phi_i(t) at [k*s + i] */
    double aphi[PHI_SIZE]; /* (A Phi(t))_i */
    for (int k = 0; k < f.count; k++) {
        const tree *t = &f.t[k];
        double *ph = phi + (size_t)k * (size_t)s, *aph = aphi + (size_t)k * (size_t)s;
        for (int i = 0; i < s; i++) {
            double v = 1.0;
            for (int q = 0; q < t->nchild; q++)
                v *= aphi[(size_t)t->child[q] * (size_t)s + (size_t)i];
            ph[i] = v;
        }
        for (int i = 0; i < s; i++) {
            double v = 0.0;
            for (int j = 0; j < s; j++)
                v += a[i * s + j] * ph[j];
            aph[i] = v;
        }
        double sum = 0.0;
        for (int i = 0; i < s; i++)
            sum += w[i] * ph[i];
        worst = fmax(worst, fabs(sum - 1.0 / t->gamma));
    }
    return worst;
}

double dyn_tableau_order_residual(const dyn_tableau *tab, int p)
{
    if (!tab)
        return INFINITY;
    return residual(tab, tab->b, p);
}

double dyn_tableau_weights_residual(const dyn_tableau *tab, const double *w, int p)
{
    if (!tab)
        return INFINITY;
    return residual(tab, w, p);
}
