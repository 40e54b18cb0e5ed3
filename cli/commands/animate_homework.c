/* SPDX-License-Identifier: BSD-3-Clause */
/* `dynkit animate cart` without run options plays the homework's run (problem 4, "Three-
 * wheeler"), not the model's lecture default of a constant force: the backward path
 * sX = -v0 t, theta = pi/8 sin(2 pi f t) with v0 = 20 m/s, f = 2 Hz (4a), its force table
 * of N = 500 samples at Ts = 0.01 s by the inverse dynamics (4b), and the forward run with
 * modified Euler (heun) at Ts driven by that table held over each sample from the
 * prescribed initial state (4c) -- the run dynkit report's problem 4 computes
 * (src/report/hw_cart.c) -- drawn beside the prescribed path itself. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/animate_homework.h"
#include "dynkit/cart.h"

/* the problem's data (homework 4a, 4b) */
#define HW_V0 20.0 /* [m/s] backward speed */
#define HW_F 2.0   /* [Hz] heading frequency */
#define HW_N 500L  /* samples of the force table */
#define HW_TS 0.01 /* [s] their sampling time, the forward run's step */

int cli_animate_homework_applies(const cli_view *v, int argc, char **argv)
{
    static const char *const chooses[] = {"--forces", "--set", "--init", "--tspan", "--step",
                                          "--method", "-m",    "--times", "--end",  "--interp"};
    if (v->run.model != &dyn_model_cart)
        return 0;
    for (int i = 1; i < argc; i++)
        for (size_t k = 0; k < sizeof chooses / sizeof chooses[0]; k++) {
            const size_t n = strlen(chooses[k]);
            if (strncmp(argv[i], chooses[k], n) == 0 && (argv[i][n] == '\0' || argv[i][n] == '='))
                return 0;
        }
    return 1;
}

int cli_animate_homework_setup(cli_view *v)
{
    cli_run *run = &v->run;
    const dyn_model *m = run->model;
    dyn_cart_par *p = run->par;
    char err[512];
    double *table = malloc((size_t)HW_N * 3 * sizeof *table);
    if (!table) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    if (dyn_cart_force_table(p, HW_V0, HW_F, HW_N, HW_TS, table, err, sizeof err) ||
        dyn_cart_prescribed(p, HW_V0, HW_F, 0.0, run->y0, NULL) ||
        m->set_input(run->par, table, HW_N, DYN_INTERP_HOLD, err, sizeof err)) {
        free(table);
        cli_error("the homework's cart run: %s", err);
        return CLI_FAILED;
    }
    free(run->input);
    run->input = table;
    run->input_rows = HW_N;
    run->interp = DYN_INTERP_HOLD;
    run->method = cli_method_find("heun");
    run->t0 = 0.0;
    run->t1 = (double)(HW_N - 1) * HW_TS;
    run->step = HW_TS;
    run->step_given = 1;
    return run->method ? CLI_OK : CLI_FAILED;
}

int cli_animate_homework_finish(cli_view *v)
{
    if (v->n_series < 1 || v->n_series >= 1 + CLI_MAX_COMPARE)
        return CLI_OK;
    const cli_series *fw = &v->series[0];
    cli_series *s = &v->series[v->n_series];
    const dyn_model *m = v->run.model;
    memset(s, 0, sizeof *s);
    snprintf(v->series[0].label, sizeof v->series[0].label,
             "forward run (4c): heun, h = %g s, forces held", HW_TS);
    snprintf(s->label, sizeof s->label, "prescribed path (4a)");
    s->method = NULL;
    s->step = fw->step;
    s->cols = fw->cols;
    s->samples = fw->rows;
    s->status = DYN_OK;
    if (fw->rows > 0 && !(s->data = malloc((size_t)fw->rows * (size_t)fw->cols * sizeof *s->data))) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    for (long k = 0; k < fw->rows; k++) {
        double *row = s->data + k * s->cols;
        row[0] = fw->data[k * fw->cols];
        if (dyn_cart_prescribed(v->run.par, HW_V0, HW_F, row[0], row + 1, NULL) ||
            (m->n_outputs > 0 && m->compute_outputs(row[0], row + 1, v->run.par,
                                                    row + 1 + m->n_states)))
            for (int c = 1; c < s->cols; c++)
                row[c] = NAN;
    }
    s->rows = fw->rows;
    v->n_series++;
    return CLI_OK;
}

void cli_animate_homework_shows(char *buf, size_t size)
{
    snprintf(buf, size,
             "Shown: the homework's run (problem 4): the prescribed backward path sX = -v0 t, "
             "theta = pi/8 sin(2 pi f t) with v0 = %g m/s, f = %g Hz (4a), and the forward "
             "run with modified Euler (heun) at Ts = %g s driven by its force table of %ld "
             "samples (4b), each force held over its sample (4c), from the prescribed initial "
             "state; as dynkit report computes it. The backward run is unstable, so the "
             "forward run leaves the path. Any of --forces, --set, --init, --tspan, --step or "
             "--method makes another run.",
             HW_V0, HW_F, HW_TS, HW_N);
}
