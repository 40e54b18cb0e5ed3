/* SPDX-License-Identifier: BSD-3-Clause */
/* A program of one's own that loads a model file through the installed API: the .ode text
 * translated to C (dynkit/lang.h), the C compiled and loaded (dynkit/jit.h), the loaded
 * model run with dyn_ivp_solve (dynkit/ivp.h). The model, oscillator.ode, is the damped
 * linear oscillator x'' + 2 zeta w x' + w^2 x = 0 from x = 1 at rest, whose solution is
 * x(t) = exp(-zeta w t) (cos(wd t) + zeta w / wd sin(wd t)), wd = w sqrt(1 - zeta^2).
 * Prints x(5) and its difference from that closed form; exits 1 when the difference
 * exceeds 1e-9 m (dop853 at rtol = atol = 1e-12). Usage: ode_user FILE.ode */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dynkit/dynkit.h>
#include <dynkit/jit.h>
#include <dynkit/lang.h>

static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16;
    char *text = malloc(cap);
    *len = text ? fread(text, 1, cap - 1, f) : 0;
    fclose(f);
    if (text)
        text[*len] = '\0';
    return text;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: ode_user FILE.ode\n");
        return 2;
    }
    size_t len;
    char *text = read_file(argv[1], &len);
    if (!text) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 1;
    }
    char *c_source = NULL, msg[4096];
    dyn_lang_diag diag;
    if (dyn_ode_to_c(argv[1], text, len, &c_source, &diag, NULL, NULL) != 0) {
        fputs(dyn_lang_diag_format(&diag, msg, sizeof msg), stderr);
        free(text);
        return 1;
    }
    free(text);
    dyn_jit_model jm;
    if (dyn_jit_load_source(c_source, strlen(c_source), argv[1], NULL, &jm, msg, sizeof msg)) {
        fprintf(stderr, "%s\n", msg);
        free(c_source);
        return 1;
    }
    free(c_source);
    const dyn_model *m = jm.model;
    void *par = calloc(1, m->par_size + 1);
    double y0[2];
    if (!par || m->n_states != 2 || dyn_model_default_params(m, par, msg, sizeof msg)) {
        fprintf(stderr, "%s: not the oscillator's two states and parameters\n", argv[1]);
        return 1;
    }
    dyn_model_initial_state(m, par, y0);
    const dyn_ivp_opts opts = {.method = "dop853", .rtol = 1e-12, .atol = 1e-12};
    dyn_ivp_solution *sol = dyn_ivp_solve(m->rhs, m->n_states, par, 0.0, 5.0, y0, &opts);
    if (!sol || sol->status != DYN_OK) {
        fprintf(stderr, "the run failed: %s\n", sol ? sol->message : "out of memory");
        return 1;
    }
    const double zeta = dyn_model_get_param(m, par, dyn_model_param_index(m, "zeta"));
    const double w = dyn_model_get_param(m, par, dyn_model_param_index(m, "w"));
    const double wd = w * sqrt(1.0 - zeta * zeta), t = 5.0;
    const double exact = exp(-zeta * w * t) * (cos(wd * t) + zeta * w / wd * sin(wd * t));
    const double x = sol->y[(sol->n_t - 1) * 2];
    printf("x(5) = %.15g m, the closed form %.15g m, difference %.1e m\n", x, exact,
           fabs(x - exact));
    const int bad = !(fabs(x - exact) <= 1e-9) || sol->t[sol->n_t - 1] != t;
    dyn_ivp_free(sol);
    free(par);
    dyn_jit_unload(&jm);
    return bad;
}
