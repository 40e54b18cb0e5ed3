/* SPDX-License-Identifier: BSD-3-Clause */
/* The admissible directions of a mechanism's linearization (docs/analysis.md, "Mechanisms
 * with constraints"): the constraints' values on the speeds h(t, q, u) from
 * dyn_mech_constraints_to_c and the holonomic ones' values f(t, q), their derivatives G by
 * central differences (dyn_holonomic_gradient, dynkit/analysis.h), and a basis P of the directions (dq, du) with df/dq dq = 0 for each
 * holonomic constraint and dh/dq dq + dh/du du = 0 for every constraint (df/dq, not dh/du:
 * with declared speeds q' = W(q) u, dh/du = df/dq W) — its null space by Gauss-Jordan
 * elimination with complete pivoting among the speeds first, then the coordinates; the
 * pivots' states are the dependent ones. */
#include "models/lin_constrained.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/analysis.h"
#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "util/out_file.h"

int cli_lin_constraints_open(const char *spec, const dyn_model *m, cli_lin_constraints *cc)
{
    memset(cc, 0, sizeof *cc);
    if (!cli_has_extension(spec, ".mech")) /* as model_open.c: any case */
        return 0;
    size_t len = 0;
    char *text = cli_read_model_file(spec, &len);
    if (!text)
        return CLI_USAGE;
    char *c_source = NULL;
    dyn_lang_diag diag;
    int rc = dyn_mech_constraints_to_c(spec, text, len, NULL, 0, &c_source, &diag);
    free(text);
    if (rc != 0) {
        char shown[2048];
        fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
        return rc == 1 ? CLI_FAILED : CLI_USAGE;
    }
    char err[1024] = "";
    const size_t c_len = strlen(c_source);
    rc = dyn_jit_load_source(c_source, c_len, spec, cli_mech_jit_opts(c_len), &cc->jm, err,
                             sizeof err);
    free(c_source);
    if (rc != 0) {
        cli_error("compiling the constraints of %s: %s", spec, err);
        return CLI_FAILED;
    }
    cc->loaded = 1;
    const dyn_model *cm = cc->jm.model;
    if (cm->n_states != m->n_states || cm->par_size != m->par_size || cm->n_states % 2) {
        cli_error("the constraints of %s do not match its model", spec);
        return CLI_FAILED;
    }
    for (int i = 0; i < cm->n_outputs; i++) {
        const char *u = cm->outputs[i].unit;
        if (u && (strcmp(u, "holonomic") == 0 || strcmp(u, "speeds") == 0))
            cc->m++;
    }
    return 0;
}

void cli_lin_constraints_close(cli_lin_constraints *cc)
{
    if (cc->loaded)
        dyn_jit_unload(&cc->jm);
    cc->loaded = 0;
}

int cli_lin_basis(const cli_lin_constraints *cc, double t, const double *y, const void *par,
                  double *P, int *kept, int *k_out, char *err, size_t errlen)
{
    const dyn_model *cm = cc->jm.model;
    const int N = cm->n_states, n = N / 2, m = cc->m;
    const size_t mo = (size_t)cm->n_outputs + 1;
    double *hf = malloc(2 * mo * sizeof *hf); /* h, then f */
    int *hol = malloc(mo * sizeof *hol);
    double *dh = malloc(mo * (size_t)N * sizeof *dh); /* dh_r/dy_j */
    double *df = malloc(mo * (size_t)n * sizeof *df); /* df_r/dq_k, 0 on the speeds' rows */
    double *G = malloc((size_t)(2 * m * N + 1) * sizeof *G);
    int *piv = malloc((size_t)(N + 1) * sizeof *piv);
    int rc = !hf || !hol || !dh || !df || !G || !piv;
    if (rc)
        snprintf(err, errlen, "out of memory");
    if (!rc && (dyn_constraint_values(cm, par, t, y, hf, hf + mo, hol) != m ||
                dyn_holonomic_gradient(cm, par, t, y, df, dh) != m)) {
        snprintf(err, errlen, "the constraints' values failed at the state");
        rc = -1;
    }
    /* G: rows df/dq on the coordinates' columns for the holonomic constraints, then dh/dy */
    int rows = 0;
    for (int r = 0; r < m && !rc; r++)
        if (hol[r]) {
            for (int j = 0; j < N; j++)
                G[rows * N + j] = j < n ? df[r * n + j] : 0.0;
            rows++;
        }
    for (int r = 0; r < m && !rc; r++, rows++)
        memcpy(G + rows * N, dh + r * N, (size_t)N * sizeof *G);
    /* Gauss-Jordan with complete pivoting: each pivot's column is a dependent state */
    double big = 0.0;
    for (int i = 0; i < rows * N && !rc; i++)
        big = fmax(big, fabs(G[i]));
    int rank = 0;
    for (int j = 0; j < N; j++)
        piv[j] = -1;
    while (!rc && rank < rows) {
        int bi = -1, bj = -1;
        /* the speeds first: a constraint removes a speed where it can, a coordinate only
         * where no speed is left (a holonomic constraint's row on the positions) */
        for (int pass = 0; pass < 2 && bi < 0; pass++) {
            double best = 1e-10 * big;
            for (int i = rank; i < rows; i++)
                for (int j = pass ? 0 : n; j < (pass ? n : N); j++)
                    if (piv[j] < 0 && fabs(G[i * N + j]) > best) {
                        best = fabs(G[i * N + j]);
                        bi = i;
                        bj = j;
                    }
        }
        if (bi < 0)
            break; /* the remaining rows depend on the others */
        for (int j = 0; j < N; j++) {
            const double s = G[rank * N + j];
            G[rank * N + j] = G[bi * N + j];
            G[bi * N + j] = s;
        }
        const double d = G[rank * N + bj];
        for (int j = 0; j < N; j++)
            G[rank * N + j] /= d;
        for (int i = 0; i < rows; i++)
            if (i != rank && G[i * N + bj] != 0.0) {
                const double f = G[i * N + bj];
                for (int j = 0; j < N; j++)
                    G[i * N + j] -= f * G[rank * N + j];
            }
        piv[bj] = rank++;
    }
    int k = 0;
    for (int j = 0; j < N && !rc; j++) {
        if (piv[j] >= 0)
            continue;
        for (int i = 0; i < N; i++)
            P[i * (N - rank) + k] = piv[i] >= 0 ? -G[piv[i] * N + j] : i == j ? 1.0 : 0.0;
        kept[k++] = j;
    }
    *k_out = k;
    free(hf);
    free(hol);
    free(dh);
    free(df);
    free(G);
    free(piv);
    return rc;
}
