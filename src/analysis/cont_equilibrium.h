/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_equilibrium.h — a model's f(x, p) as the system of continuation (private): the
 * parameter struct kept prepared for the parameter values last asked for, f and its
 * Jacobian in x (dyn_linearize: exact for model files) and in the parameters (central
 * differences), and the eigenvalues of a point. Used by equilibrium branches
 * (cont_equilibrium.c) and by the curves of folds and Hopf points (cont_curves.c). */
#ifndef DYN_ANALYSIS_CONT_EQUILIBRIUM_H
#define DYN_ANALYSIS_CONT_EQUILIBRIUM_H

#include "cont_core.h"

/* a map's cycles born at period doublings are followed up to this period */
#define CONT_MAP_MAX_PERIOD 16

typedef struct cont_model {
    const dyn_model *m;
    int n;
    double t;
    dyn_jac_scheme jac;
    int ip, ip2;          /* the parameters (ip2 -1: one) */
    int map;              /* 1: a discrete map: f is F^period(x) - x, J is its Jacobian
                           * and the eigenvalues are the multipliers (of dF^period/dx) */
    int period;           /* a map's iterations: 1 (fixed points), 2, 4, ... (cycles) */
    double *map_work;     /* a map's iterates and Jacobians (cont_map.c) */
    void *par;            /* (par_size bytes) the working copy */
    double p_set[2];      /* the values par is prepared for */
    double p2_base;       /* ip2's value in the caller's par (NAN p2: this one) */
    double *f, *fp, *fm, *J, *lin_work, *eig_a, *re, *im; /* workspace */
    long rhs_calls;
    cont_missed missed;   /* special points detected but not located, on every branch */
    char message[256];
} cont_model;

int cont_model_init(cont_model *cm, const dyn_model *m, const void *par, const dyn_cont_opts *o);
void cont_model_free(cont_model *cm);
/* par prepared for p (p2 ignored when ip2 < 0): 0 or non-zero (message set) */
int cont_model_set(cont_model *cm, double p, double p2);
/* f(x) at the prepared parameters into f: 0 or non-zero */
int cont_model_f(cont_model *cm, const double *x, double *f);
/* J = df/dx (n x n, row stride ld) at the prepared parameters: 0 or non-zero */
int cont_model_jx(cont_model *cm, const double *x, double *J, int ld);
/* df/dp of parameter q (0: ip, 1: ip2) into col (stride ld) at (x, p, p2): central
 * differences; par is left prepared for (p, p2). 0 or non-zero */
int cont_model_fp(cont_model *cm, const double *x, double p, double p2, int q, double *col,
                  int ld);
/* 1 (a note in msg) when f at x differs between cm->t and later times, at the prepared
 * parameter or at a second value of ip (cont_autonomous.c); 0 when not; -1 when the model
 * cannot be prepared again. par is left prepared for the parameter it had */
int cont_time_dependent(cont_model *cm, const double *x, char *msg, size_t len);
/* The eigenvalues of J (n x n) into cm->re, cm->im, sorted (dyn_eig_sort); a map's
 * multipliers, those of J + I: 0 or non-zero */
int cont_model_eig(cont_model *cm, const double *J);
/* A point's record appended to branch b: x, the parameters, stability from cm->re (when
 * eig is non-zero, after cont_model_eig), label, l1 and omega */
int cont_model_store(cont_model *cm, dyn_branch *b, const double *x, double p, double p2,
                     int eig, dyn_cont_label label, double l1, double omega);

/* A map's branches (cont_map.c): the test functions of a period doubling (psi[0], count[0])
 * and of a Neimark-Sacker point (psi[1], count[1]) from the multipliers in cm->re, cm->im;
 * whether they make a fixed point asymptotically stable (every |mu| < 1 - tol); the angle
 * arg mu in (0, pi) of the complex pair nearest the unit circle (NAN when none). */
void cont_map_tests(const cont_model *cm, double *psi, int *count);
/* F^period(x) into y (cm->period > 1), the right-hand side counted: 0 or non-zero */
int cont_map_iterate(cont_model *cm, const double *x, double *y);
/* dF^period/dx at x into A (n x n) by the chain rule over the iterates: 0 or non-zero */
int cont_map_jacobian(cont_model *cm, const double *x, double *A);
int cont_map_stable(const cont_model *cm, double tol);
double cont_map_angle(const cont_model *cm);

/* The last branch of d removed and freed (one that got no point) */
void cont_diagram_drop_last(dyn_diagram *d);

/* The curves of folds (from an LP) or Hopf points (from an HB) through point `point` of
 * the branch with index `branch` of d, both directions, appended to d (cont_curves.c).
 * Returns 0 (a curve that cannot start is noted in info->message), or -1 when out of
 * memory. */
int cont_curves_from(cont_model *cm, const dyn_cont_opts *o, dyn_diagram *d, int branch,
                     long point, dyn_cont_info *info);

#endif /* DYN_ANALYSIS_CONT_EQUILIBRIUM_H */
