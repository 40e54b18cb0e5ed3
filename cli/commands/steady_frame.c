/* SPDX-License-Identifier: BSD-3-Clause */
/* steady_frame.c — a steady motion's frame, shared by dynkit steady and dynkit continue
 * (steady_frame.h): the kept states and the admissible directions P of a mechanism with
 * constraints (cli_lin_basis), its dependent states solved from the constraints
 * (dyn_steady_dependent), and the cyclic states: those whose column of the linearization
 * along P vanishes on the other kept states' rows at the state and at a nearby one
 * (dyn_steady_cyclic). docs/analysis.md, "Steady motions". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/steady_frame.h"
#include "dynkit/analysis.h"
#include "dynkit/equilibria.h"
#include "dynkit/steady.h"

int steady_frame_alloc(steady_frame *fr, const cli_lin_constraints *cc, int n)
{
    const size_t N = (size_t)n;
    fr->cc = cc;
    fr->n = fr->k = n;
    fr->nd = 0;
    fr->kept = malloc(N * sizeof(int));
    fr->dep = malloc(N * sizeof(int));
    fr->P = malloc(N * N * sizeof(double));
    if (fr->kept && fr->dep && fr->P)
        return 0;
    steady_frame_free(fr);
    return -1;
}

void steady_frame_free(steady_frame *fr)
{
    free(fr->kept);
    free(fr->dep);
    free(fr->P);
    fr->kept = fr->dep = NULL;
    fr->P = NULL;
}

int steady_complete_dependent(void *ctx, double t, double *y, void *par, char *err,
                              size_t errlen)
{
    const steady_frame *fr = ctx;
    return dyn_steady_dependent(fr->cc->jm.model, par, t, y, fr->nd, fr->dep, err, errlen);
}

int steady_frame_at(const char *cmd, steady_frame *fr, double t, const double *y, void *par)
{
    const int n = fr->n;
    char err[256] = "";
    if (fr->cc->m > 0) {
        if (cli_lin_basis(fr->cc, t, y, par, fr->P, fr->kept, &fr->k, err, sizeof err)) {
            cli_error("%s: the admissible directions: %s", cmd, err[0] ? err : "singular");
            return CLI_FAILED;
        }
    } else {
        fr->k = n;
        memset(fr->P, 0, (size_t)n * (size_t)n * sizeof *fr->P);
        for (int i = 0; i < n; i++) {
            fr->kept[i] = i;
            fr->P[(size_t)i * (size_t)n + (size_t)i] = 1.0;
        }
    }
    fr->nd = 0;
    for (int i = 0; i < n; i++) {
        int is_kept = 0;
        for (int j = 0; j < fr->k; j++)
            is_kept |= fr->kept[j] == i;
        if (!is_kept)
            fr->dep[fr->nd++] = i;
    }
    return CLI_OK;
}

int steady_split_names(char *list, char **names, int max)
{
    int k = 0;
    for (char *tok = list, *next = NULL; tok && *tok; tok = next) {
        char *comma = strchr(tok, ',');
        next = comma ? comma + 1 : NULL;
        if (comma)
            *comma = '\0';
        if (k == max)
            return -1;
        names[k++] = tok;
    }
    return k;
}

/* AP (n x k): the linearization along the admissible directions P of fr at (t, y). */
static int linearize_along(const char *cmd, const dyn_model *m, double t, const double *y,
                           void *par, const steady_frame *fr, double *AP)
{
    const size_t N = (size_t)m->n_states, K = (size_t)fr->k;
    double *A = malloc(N * N * sizeof *A),
           *w = malloc(dyn_linearize_work_size(m->n_states) * sizeof *w);
    dyn_linearize_info li;
    int rc = A && w ? CLI_OK : CLI_FAILED;
    if (rc == CLI_OK && dyn_linearize(m, t, y, par, NULL, A, w, &li)) {
        cli_error("%s: %s", cmd, li.message);
        rc = CLI_FAILED;
    }
    for (size_t i = 0; i < N && rc == CLI_OK; i++)
        for (size_t j = 0; j < K; j++) {
            double s = 0.0;
            for (size_t l = 0; l < N; l++)
                s += A[i * N + l] * fr->P[l * K + j];
            AP[i * K + j] = s;
        }
    free(A);
    free(w);
    return rc;
}

int steady_find_cyclic(const char *cmd, const dyn_model *m, double t, const double *y, void *par,
                       const steady_frame *fr, char *given, int *cyclic)
{
    const int n = m->n_states, k = fr->k;
    const size_t N = (size_t)n;
    if (given[0]) {
        char *names[256];
        const int c = steady_split_names(given, names, 256);
        if (c < 0)
            return cli_usage_error(cmd, "--cyclic: at most 256 names");
        memset(cyclic, 0, (size_t)k * sizeof *cyclic);
        for (int i = 0; i < c; i++) {
            const int s = dyn_model_state_index(m, names[i]);
            int at = -1;
            for (int j = 0; j < k; j++)
                if (fr->kept[j] == s)
                    at = j;
            if (at < 0)
                return cli_usage_error(cmd, "--cyclic %s: not a state of %s%s", names[i],
                                       m->name, s >= 0 ? " that its constraints leave free" : "");
            cyclic[at] = 1;
        }
        return CLI_OK;
    }
    /* at the state and at a nearby one (each kept state moved by a tenth of max(|y|, 1)
     * times a Halton number): a column that vanishes only at the state (a rate that is 0
     * there) is not taken for a cyclic state's */
    double *AP = malloc(N * N * sizeof *AP), *AP2 = malloc(N * N * sizeof *AP2),
           *y2 = malloc(N * sizeof *y2);
    steady_frame fr2;
    const int fr2_bad = steady_frame_alloc(&fr2, fr->cc, n);
    int rc = AP && AP2 && y2 && !fr2_bad ? CLI_OK : CLI_FAILED;
    if (rc == CLI_OK)
        rc = linearize_along(cmd, m, t, y, par, fr, AP);
    if (rc == CLI_OK) {
        memcpy(y2, y, N * sizeof *y2);
        for (int j = 0; j < k; j++) {
            const int s = fr->kept[j];
            y2[s] += 0.1 * fmax(fabs(y[s]), 1.0) * dyn_halton(1 + j, 0);
        }
        char err[256];
        int same =
            !(fr->nd && steady_complete_dependent((void *)fr, t, y2, par, err, sizeof err)) &&
            steady_frame_at(cmd, &fr2, t, y2, par) == CLI_OK && fr2.k == k &&
            memcmp(fr2.kept, fr->kept, (size_t)k * sizeof *fr->kept) == 0 &&
            linearize_along(cmd, m, t, y2, par, &fr2, AP2) == CLI_OK;
        for (size_t e = 0; same && e < N * (size_t)k; e++)
            AP[e] = fmax(fabs(AP[e]), fabs(AP2[e]));
        dyn_steady_cyclic(n, k, fr->kept, AP, 1e-8, cyclic);
    }
    free(AP);
    free(AP2);
    free(y2);
    if (!fr2_bad)
        steady_frame_free(&fr2);
    return rc;
}

int steady_frame_prepare(const char *cmd, steady_frame *fr, const dyn_model *m, double t,
                         double *y, void *par, char *given, int *cyclic, int *eqs, int *n_eq)
{
    *n_eq = 0;
    int rc = steady_frame_at(cmd, fr, t, y, par);
    char err[256] = "";
    if (rc == CLI_OK && fr->nd && steady_complete_dependent(fr, t, y, par, err, sizeof err)) {
        cli_error("%s: the initial state on the constraints: %s", cmd, err);
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK)
        rc = steady_find_cyclic(cmd, m, t, y, par, fr, given, cyclic);
    for (int j = 0; j < fr->k && rc == CLI_OK; j++)
        if (!cyclic[j])
            eqs[(*n_eq)++] = fr->kept[j];
    return rc;
}
