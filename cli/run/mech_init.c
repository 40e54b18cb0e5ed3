/* SPDX-License-Identifier: BSD-3-Clause */
/* The initial state of a mechanism's run (docs/mechanisms.md, "Initial values"): checked
 * against the constraints after --set and --init (refused with the constraint's name and
 * value), or moved onto them with --project-init (dyn_project_constraints), printing each
 * state it changed and the assembly mode reached (the sign of the determinant of the
 * holonomic constraints' gradient on the coordinates they solve for, which changes only
 * through a singular configuration); a projection that does not reach the constraints is
 * an error naming each constraint's value left. The constraints' values come from
 * dyn_mech_constraints_to_c's model, compiled beside the run's (lin_constrained.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/analysis.h"
#include "models/lin_constrained.h"
#include "run/mech_init.h"

/* the name of the r-th constraint among the outputs "holonomic"/"speeds" */
static const char *constraint_name(const dyn_model *cm, int r)
{
    for (int i = 0; i < cm->n_outputs; i++) {
        const char *u = cm->outputs[i].unit;
        if (u && (strcmp(u, "holonomic") == 0 || strcmp(u, "speeds") == 0) && r-- == 0)
            return cm->outputs[i].name;
    }
    return "?";
}

static int check(const char *command, const dyn_model *cm, const cli_run *run)
{
    const int N = cm->n_states, n = N / 2, no = cm->n_outputs + 1;
    double *h = malloc((size_t)no * 2 * sizeof *h);
    int *hol = malloc((size_t)no * sizeof *hol);
    int m = h && hol ? dyn_constraint_values(cm, run->par, run->t0, run->y0, h, h + no, hol)
                     : -1;
    const double tq = dyn_constraint_tolerance(run->y0, n),
                 tu = dyn_constraint_tolerance(run->y0 + n, n);
    int rc = m < 0 ? cli_usage_error(command, "the constraints' values failed at the "
                                              "initial state")
                   : CLI_OK;
    for (int r = 0; r < m && rc == CLI_OK; r++) {
        const double f = h[no + r];
        if (hol[r] && !(fabs(f) <= tq))
            rc = cli_usage_error(command, "the initial state does not hold constraint '%s': "
                                 "its value is %s, not 0 (give --project-init to move the "
                                 "initial state onto the constraints, or other --init "
                                 "values)", constraint_name(cm, r), CLI_NUM(f));
        else if (!(fabs(h[r]) <= tu))
            rc = cli_usage_error(command, "the initial state does not hold constraint '%s': "
                                 "its %s is %s, not 0 (give --project-init to move the "
                                 "initial state onto the constraints, or other --init "
                                 "values)", constraint_name(cm, r),
                                 hol[r] ? "rate" : "value", CLI_NUM(h[r]));
    }
    free(h);
    free(hol);
    return rc;
}

/* "q1=0.5, q2=1" of the n coordinates y (the first n states), malloc'd */
static char *coordinates_text(const dyn_model *m, const double *y, int n)
{
    size_t cap = 64, len = 0;
    char *s = malloc(cap);
    for (int j = 0; j < n && s; j++) {
        const size_t add = strlen(m->states[j].name) + DYN_DOUBLE_CHARS + 4;
        if (len + add >= cap) {
            char *t = realloc(s, cap = 2 * (len + add));
            if (!t) {
                free(s);
                return NULL;
            }
            s = t;
        }
        len += (size_t)snprintf(s + len, cap - len, "%s%s=%s", j ? ", " : "",
                                m->states[j].name, CLI_NUM(y[j]));
    }
    if (s && n == 0)
        s[0] = '\0';
    return s;
}

/* The projection stopped short of the constraints at y: each holonomic constraint and its
 * value there, and the coordinates they involve, to start from nearer. */
static int not_reached(const char *command, const char *spec, const dyn_model *cm,
                       const cli_run *run, const double *y)
{
    const int N = cm->n_states, n = N / 2, no = cm->n_outputs + 1;
    double *h = malloc((size_t)no * (2 + 2 * (size_t)n) * sizeof *h);
    int *hol = malloc((size_t)no * sizeof *hol);
    char *from = coordinates_text(run->model, run->y0, n), *at = coordinates_text(run->model,
                                                                                  y, n);
    if (!h || !hol || !from || !at) {
        free(h), free(hol), free(from), free(at);
        cli_stderr("dynkit: error: out of memory\n");
        return CLI_FAILED;
    }
    double *f = h + no, *G = f + no, *G0 = G + (size_t)no * n;
    const int m = dyn_constraint_values(cm, run->par, run->t0, y, h, f, hol);
    const int mg = m < 0 ? -1 : dyn_holonomic_gradient(cm, run->par, run->t0, y, G, NULL);
    const int m0 = mg < 0 ? -1 : dyn_holonomic_gradient(cm, run->par, run->t0, run->y0, G0,
                                                        NULL);
    const double tol = dyn_constraint_tolerance(y, n);
    cli_stderr("dynkit: error: %s: --project-init did not bring %s onto its constraints: "
               "from %s Gauss-Newton's projection stopped at %s, where\n",
               command, spec, from, at);
    for (int r = 0; r < m; r++)
        if (hol[r]) {
            const char *name = constraint_name(cm, r);
            cli_stderr("  constraint '%s' is %s%s\n", name, CLI_NUM(f[r]),
                       fabs(f[r]) <= tol ? " (holds)" : " (does not hold)");
        }
    for (int j = 0; j < n; j++) {
        const double q = fabs(y[j]), gap = nextafter(q, INFINITY) - q;
        if (gap > tol)
            cli_stderr("  (%s = %s: the doubles near it are %s apart, coarser than the "
                       "tolerance)\n",
                       run->model->states[j].name, CLI_NUM(y[j]), CLI_NUM(gap));
    }
    cli_stderr("  (a constraint holds within %s); no result is computed from this "
               "state: give --init values of",
               CLI_NUM(tol));
    int named = 0;
    for (int j = 0; j < n && m0 >= 0; j++) {
        int involved = 0;
        for (int r = 0; r < m && !involved; r++)
            involved = hol[r] && (G[r * n + j] != 0.0 || G0[r * n + j] != 0.0);
        if (involved)
            cli_stderr("%s %s", named++ ? "," : "", run->model->states[j].name);
    }
    cli_stderr("%s nearer a state that holds the constraints (a sketch of the assembled "
               "mechanism), or check that the constraints can hold together\n",
               named ? "" : " the coordinates");
    free(h), free(hol), free(from), free(at);
    return CLI_FAILED;
}

/* The sign of the determinant of the k x k minor of G (rows rows, columns cols; row length
 * n) by elimination with partial pivoting: 1, -1, or 0 when it is singular. */
static int minor_sign(const double *G, int n, const int *rows, const int *cols, int k,
                      double *a)
{
    for (int i = 0; i < k; i++)
        for (int j = 0; j < k; j++)
            a[i * k + j] = G[rows[i] * n + cols[j]];
    int sign = 1;
    double big = 0.0;
    for (int i = 0; i < k * k; i++)
        big = fmax(big, fabs(a[i]));
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int i = c + 1; i < k; i++)
            if (fabs(a[i * k + c]) > fabs(a[p * k + c]))
                p = i;
        if (!(fabs(a[p * k + c]) > 1e-9 * big))
            return 0;
        if (p != c) {
            sign = -sign;
            for (int j = 0; j < k; j++) {
                const double t = a[c * k + j];
                a[c * k + j] = a[p * k + j];
                a[p * k + j] = t;
            }
        }
        if (a[c * k + c] < 0)
            sign = -sign;
        for (int i = c + 1; i < k; i++) {
            const double l = a[i * k + c] / a[c * k + c];
            for (int j = c; j < k; j++)
                a[i * k + j] -= l * a[c * k + j];
        }
    }
    return sign;
}

/* The assembly mode that the projection reached: the holonomic constraints solve for as
 * many coordinates (picked by complete pivoting of G at y), and the sign of that minor's
 * determinant at y and at the start. Printed when a constraint couples coordinates (a
 * loop, a circle: where more than one mode may hold), unless quiet; a change of sign (the
 * projection went through a singular configuration into another mode) always. */
static void report_mode(const char *command, const dyn_model *cm, const cli_run *run,
                        const double *y)
{
    const int N = cm->n_states, n = N / 2, no = cm->n_outputs + 1;
    double *G = malloc((size_t)no * n * 3 * sizeof *G + (size_t)no * 2 * sizeof *G);
    int *idx = malloc((size_t)(2 * no + 2 * n + 1) * sizeof *idx);
    if (!G || !idx) {
        free(G), free(idx);
        return;
    }
    double *G0 = G + (size_t)no * n, *a = G0 + (size_t)no * n, *hf = a + (size_t)no * n;
    int *hol = idx, *rows = hol + no, *cols = rows + n, *used = cols + n;
    const int m = dyn_constraint_values(cm, run->par, run->t0, y, hf, hf + no, hol);
    if (m <= 0 || dyn_holonomic_gradient(cm, run->par, run->t0, y, G, NULL) != m ||
        dyn_holonomic_gradient(cm, run->par, run->t0, run->y0, G0, NULL) != m) {
        free(G), free(idx);
        return;
    }
    int k = 0, coupled = 0;
    for (int r = 0; r < m && k < n; r++) {
        if (!hol[r])
            continue;
        int nz = 0;
        for (int j = 0; j < n; j++)
            nz += G[r * n + j] != 0.0;
        coupled |= nz > 1;
        rows[k++] = r;
    }
    /* the columns: complete pivoting on a copy of the rows */
    for (int i = 0; i < k; i++)
        for (int j = 0; j < n; j++)
            a[i * n + j] = G[rows[i] * n + j];
    for (int j = 0; j < n; j++)
        used[j] = 0;
    int ok = k > 0;
    for (int c = 0; c < k && ok; c++) {
        int pi = -1, pj = -1;
        double big = 0.0;
        for (int i = c; i < k; i++)
            for (int j = 0; j < n; j++)
                if (!used[j] && fabs(a[i * n + j]) > big) {
                    big = fabs(a[i * n + j]);
                    pi = i;
                    pj = j;
                }
        if (pi < 0) {
            ok = 0;
            break;
        }
        for (int j = 0; j < n; j++) {
            const double t = a[c * n + j];
            a[c * n + j] = a[pi * n + j];
            a[pi * n + j] = t;
        }
        used[pj] = 1;
        cols[c] = pj;
        for (int i = c + 1; i < k; i++) {
            const double l = a[i * n + pj] / a[c * n + pj];
            for (int j = 0; j < n; j++)
                a[i * n + j] -= l * a[c * n + j];
        }
    }
    for (int i = 1; i < k; i++) /* in the coordinates' order: one determinant, one sign */
        for (int j = i; j > 0 && cols[j - 1] > cols[j]; j--) {
            const int t = cols[j];
            cols[j] = cols[j - 1];
            cols[j - 1] = t;
        }
    const int s1 = ok ? minor_sign(G, n, rows, cols, k, a) : 0;
    const int s0 = ok ? minor_sign(G0, n, rows, cols, k, a) : 0;
    if (ok && s1 && coupled && (!run->quiet || (s0 && s0 != s1))) {
        cli_stderr("dynkit: %s: --project-init: the constraints hold in the assembly mode "
                   "where det d(",
                   command);
        for (int i = 0; i < k; i++)
            cli_stderr("%s%s", i ? "," : "", constraint_name(cm, rows[i]));
        cli_stderr(")/d(");
        for (int i = 0; i < k; i++)
            cli_stderr("%s%s", i ? "," : "", run->model->states[cols[i]].name);
        cli_stderr(") %s 0 (another mode has %s 0), at", s1 > 0 ? ">" : "<", s1 > 0 ? "<" : ">");
        for (int j = 0; j < n; j++)
            cli_stderr("%s %s=%s", j ? "," : "", run->model->states[j].name, CLI_NUM(y[j]));
        if (s0 && s0 != s1)
            cli_stderr("; the start was in the other mode (%s 0): the projection went "
                       "through a singular configuration, start nearer the mode wanted",
                       s0 > 0 ? ">" : "<");
        else if (!s0)
            cli_stderr("; the start was at a singular configuration (det 0)");
        cli_stderr("\n");
    }
    free(G), free(idx);
}

static int project(const char *command, const char *spec, const dyn_model *cm, cli_run *run)
{
    const int N = cm->n_states;
    double *y = malloc((size_t)N * sizeof *y);
    if (!y) {
        cli_stderr("dynkit: error: out of memory\n");
        return CLI_FAILED;
    }
    memcpy(y, run->y0, (size_t)N * sizeof *y);
    double res[2] = {0.0, 0.0};
    int bad = -1;
    char err[256] = "";
    if (dyn_project_constraints(cm, run->par, run->t0, y, res, &bad, err, sizeof err)) {
        int rc;
        if (bad >= 0)
            rc = cli_usage_error(command, "--project-init: %s at the initial state: "
                                 "constraint '%s' depends on the ones before it (remove "
                                 "one, or start away from this configuration)", err,
                                 constraint_name(cm, bad));
        else if (!(res[0] <= dyn_constraint_tolerance(y, N / 2)))
            rc = not_reached(command, spec, cm, run, y);
        else {
            cli_stderr("dynkit: error: %s: --project-init: %s\n", command, err);
            rc = CLI_FAILED;
        }
        free(y);
        return rc;
    }
    if (!run->quiet) {
        int changed = 0;
        for (int i = 0; i < N; i++)
            if (y[i] != run->y0[i]) {
                cli_stderr("%s %s %s -> ",
                           changed ? "," : "dynkit: --project-init:", run->model->states[i].name,
                           CLI_NUM(run->y0[i]));
                cli_stderr("%s", CLI_NUM(y[i]));
                changed = 1;
            }
        if (changed)
            cli_stderr(" (the constraints hold within %s, their rates within %s)\n",
                       CLI_NUM(res[0]), CLI_NUM(res[1]));
        else
            cli_stderr("dynkit: --project-init: the initial state holds the "
                       "constraints; nothing changed\n");
    }
    report_mode(command, cm, run, y);
    memcpy(run->y0, y, (size_t)N * sizeof *y);
    free(y);
    return CLI_OK;
}

int cli_mech_initial(const char *command, const char *spec, cli_run *run, int projected)
{
    cli_lin_constraints cc;
    int rc = cli_lin_constraints_open(spec, run->model, &cc);
    if (rc != CLI_OK)
        return rc;
    if (cc.loaded && cc.m > 0)
        rc = projected ? project(command, spec, cc.jm.model, run) : check(command, cc.jm.model, run);
    else if (cc.loaded && projected && !run->quiet)
        cli_stderr("dynkit: --project-init: %s has no constraints; nothing changed\n", spec);
    cli_lin_constraints_close(&cc);
    return rc;
}
