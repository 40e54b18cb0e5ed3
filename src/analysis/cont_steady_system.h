/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady_system.h — a branch of steady motions as the system of continuation (private
 * to the library; cont_steady_system.c): the unknowns U and the parameter p, z = (u, p), on
 * the steady equations chosen at the start; the reduced linearization B of each point, the
 * test functions of its special points, and one branch followed into the diagram. Used by
 * dyn_steady_continue (cont_steady.c) and its branch switching (cont_steady_switch.c).
 * docs/analysis.md, "Steady motions in a parameter". */
#ifndef DYN_ANALYSIS_CONT_STEADY_SYSTEM_H
#define DYN_ANALYSIS_CONT_STEADY_SYSTEM_H

#include "cont_equilibrium.h"
#include "dynkit/steady.h"

typedef struct sc_ctx {
    cont_model *cm;
    const dyn_steady_problem *sp;
    const double *y0;
    int n, nu, ne, nf;
    int *sel;           /* the equations used: positions in E (nu) */
    int *upos, *fpos;   /* positions in E of the unknowns (nu) and the held states (nf) */
    int *epos;          /* positions in the kept states of E's states (ne) */
    int *kept, *kept0, k0;
    int *piv;           /* n pivots */
    double *y, *f, *A, *P, *Amin, *lwork, *rwork, *AE, *S, *H, *B, *Bc, *re, *im;
    double tol_b;       /* dyn_stability_tol of B at the last reduction */
    double dropped;     /* the largest |f| of the equations left out, relative */
    double p2;          /* the second parameter's value (NAN: its value in par, or none) */
    dyn_diagram *d;
    int bi;
    char message[256];
    char why[152];      /* the last failure of the model or the reduction, with where */
} sc_ctx;

/* c->y and c->f for z = (u, p) (and c->p2): the parameters prepared, the base state, the unknowns, the
 * dependent states completed; 0 or non-zero (c->message set when the completion failed) */
int sc_state_at(sc_ctx *c, const double *z);
/* B and its sorted eigenvalues (c->B, c->re, c->im) at the state of the last sc_state_at:
 * 0 or non-zero with c->message */
int sc_reduce(sc_ctx *c);
/* det of the n x n matrix a (overwritten, row-major): Gaussian elimination with partial
 * pivoting */
double sc_det_lu(int n, double *a);
/* The Hamiltonian Hopf test on the eigenvalues (re, im: n values) of a steady motion
 * (cont_steady_krein.c): where the spectrum is symmetric under lambda -> -lambda (within
 * 1e-6 of the largest modulus), the discriminant of the mu = lambda^2 (one per pair), each
 * factor scaled to order one: it changes sign where two imaginary pairs collide and leave
 * the axis; *off_axis the eigenvalues whose |real part| is above tol, *omega (NULL: not
 * wanted) the mean |im| of the two nearest mu's eigenvalues. Elsewhere 1, *off_axis -2,
 * *omega NAN. */
double sc_krein_test(int n, const double *re, const double *im, double tol, int *off_axis,
                     double *omega);
/* s: the system of c (residual, Jacobian, tests LP, BP, HB, HH, store) */
void sc_system(cont_system *s, sc_ctx *c);
/* One branch from z along the unit tangent t, appended to c->d as a DYN_BRANCH_STEADY branch
 * (start: the label of z; parent, parent_point: where it was switched from, 0 and -1 for
 * none); z_bp (NULL: none) is stored first, labelled BP: the branch point it leaves. 0; -1 when out of memory or the model failed (c->message), -2 when nothing
 * could be computed from z (the branch is dropped). */
int sc_follow(sc_ctx *c, const cont_system *s, cont_work *w, const dyn_cont_opts *o,
              const double *z_bp, const double *z, const double *t, dyn_cont_label start,
              int parent, long parent_point);

/* With o->ip2 >= 0: from every LP and HB of the branches of c->d from index first on, the
 * curve of folds or of Hopf points in (o->ip, o->ip2) followed both ways
 * (cont_steady_curves.c), appended as DYN_BRANCH_FOLD or DYN_BRANCH_HOPF branches (parent
 * and parent_point set) while c->d has fewer than o->max_branches; s1 the branch's system.
 * A curve that cannot be started, or that ends where the model or the reduction fails (at
 * its last computed point, its stop saying where and why), gets a sentence appended to
 * note. 0, or -1 (out of memory: c->message). */
int sc_curves_all(sc_ctx *c, const cont_system *s1, const dyn_cont_opts *o, int first,
                  char *note, size_t notelen);

#endif /* DYN_ANALYSIS_CONT_STEADY_SYSTEM_H */
