/* SPDX-License-Identifier: BSD-3-Clause */
/* The time series behind the homework answers (report.h, dyn_homework_series): the runs of
 * dyn_homework_compute recorded sample by sample, with the same models, methods, steps and
 * initial states, so that every answer is one sample of a table; longer spans for the
 * pictures of the pendulum; the final-state error of van der Pol against the step size
 * (the observed order of each method, Hairer, Nørsett & Wanner, "Solving ODEs I", II.1);
 * the distance and principal angle between the plane's Euler and RK4 runs at each sample.
 * A table holds t (or the step), the states and the model's extra outputs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/cart.h"
#include "dynkit/mech.h"
#include "dynkit/models.h"
#include "dynkit/plane.h"
#include "report/hw_common.h"

#define PENDULUM_SPAN 10.0 /* [s] span of the pendulum pictures: a full swing and more */
#define PENDULUM_STEP 0.01 /* [s] RK4 step of the long pendulum run */

static dyn_hw_table *new_table(dyn_hw_series *s, const char *id, const char *title,
                               const char *method, double step, char *err, size_t errlen)
{
    if (s->count >= DYN_HW_MAX_TABLES) {
        snprintf(err, errlen, "internal: more than %d tables", DYN_HW_MAX_TABLES);
        return NULL;
    }
    dyn_hw_table *tab = &s->table[s->count++];
    memset(tab, 0, sizeof *tab);
    tab->id = id;
    tab->title = title;
    tab->method = method;
    tab->step = step;
    return tab;
}

static void add_column(dyn_hw_table *tab, const char *name, const char *unit)
{
    if (tab->cols < DYN_HW_MAX_COLS) {
        tab->names[tab->cols] = name;
        tab->units[tab->cols] = unit;
        tab->cols++;
    }
}

/* t, the states and the outputs of model m. */
static void add_model_columns(dyn_hw_table *tab, const dyn_model *m)
{
    add_column(tab, "t", "s");
    for (int i = 0; i < m->n_states; i++)
        add_column(tab, m->states[i].name, m->states[i].unit);
    for (int i = 0; i < m->n_outputs; i++)
        add_column(tab, m->outputs[i].name, m->outputs[i].unit);
}

static int allocate(dyn_hw_table *tab, long rows, char *err, size_t errlen)
{
    tab->data = calloc((size_t)rows * (size_t)tab->cols, sizeof *tab->data);
    if (!tab->data) {
        snprintf(err, errlen, "out of memory for table %s (%ld rows)", tab->id, rows);
        return 1;
    }
    tab->rows = 0;
    return 0;
}

/* Sample recorder for the driver's output callback: t, y and the model's outputs. */
typedef struct recorder {
    dyn_hw_table *tab;
    const dyn_model *m;
    const void *par;
    long every, last_k, capacity;
} recorder;

static int record(long k, double t, const double *y, void *ctx)
{
    recorder *r = ctx;
    if ((k % r->every != 0 && k != r->last_k) || r->tab->rows >= r->capacity)
        return 0;
    double *row = r->tab->data + r->tab->rows * r->tab->cols;
    const int n = r->m->n_states;
    row[0] = t;
    memcpy(row + 1, y, (size_t)n * sizeof *y);
    if (r->m->n_outputs > 0 && r->m->compute_outputs(t, y, r->par, row + 1 + n))
        for (int i = 0; i < r->m->n_outputs; i++)
            row[1 + n + i] = NAN;
    r->tab->rows++;
    return 0;
}

/* A run of model m (parameters par) with method over [0, t1] at step h from y0, every
 * every-th sample and the last one, into a new table with the model's columns and
 * extra_cols more columns (zero, for the caller to fill). */
static dyn_hw_table *record_run(dyn_hw_series *s, const char *id, const char *title,
                                const dyn_model *m, void *par, const char *method, double t1,
                                double h, const double *y0, long every, int extra_cols, char *err,
                                size_t errlen)
{
    dyn_grid grid;
    if (dyn_grid_plan(0.0, t1, h, DYN_END_EXACT, &grid, err, errlen))
        return NULL;
    dyn_hw_table *tab = new_table(s, id, title, method, h, err, errlen);
    if (!tab)
        return NULL;
    add_model_columns(tab, m);
    tab->cols += extra_cols; /* named by the caller */
    recorder r = {tab, m, par, every, grid.samples - 1, (grid.samples + every - 1) / every + 1};
    double y[HW_MAX_STATES];
    if (allocate(tab, r.capacity, err, errlen) ||
        hw_run(method, m->rhs, par, m->n_states, 0.0, t1, h, y0, y, record, &r, err, errlen))
        return NULL;
    return tab;
}

/* ---- problem 1 ---- */

static int pendulum_series(const dyn_hw_pendulum *hw, dyn_hw_series *s, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_pendulum;
    dyn_pendulum_par p;
    if (dyn_model_default_params(m, &p, err, errlen))
        return 1;
    p.m = hw->m;
    p.l = hw->l;
    p.g = hw->g;
    struct {
        const char *id, *title, *method;
        double t1, h;
        long every;
        int small_angle;
    } runs[3] = {
        {"pendulum.nonlinear", "nonlinear (RK4)", "rk4", PENDULUM_SPAN, PENDULUM_STEP, 1, 1},
        {"pendulum.euler", "Euler, h = te", "euler", PENDULUM_SPAN, hw->te, 1, 0},
        {"pendulum.step", "nonlinear (RK4, reference step)", "rk4", hw->te, hw->ref_step, 10, 1},
    };
    for (int i = 0; i < 3; i++) {
        dyn_hw_table *tab =
            record_run(s, runs[i].id, runs[i].title, m, &p, runs[i].method, runs[i].t1, runs[i].h,
                       hw->y0, runs[i].every, 2 * runs[i].small_angle, err, errlen);
        if (!tab)
            return 1;
        if (!runs[i].small_angle)
            continue;
        const int c = tab->cols - 2;
        tab->names[c] = "phi_small_angle";
        tab->units[c] = "rad";
        tab->names[c + 1] = "small_angle_error"; /* phi_small_angle - phi */
        tab->units[c + 1] = "rad";
        for (long k = 0; k < tab->rows; k++) {
            double *row = tab->data + k * tab->cols;
            row[c] = dyn_pendulum_small_angle(&p, hw->y0, row[0]);
            row[c + 1] = row[c] - row[1];
        }
    }
    return 0;
}

/* ---- problem 2 ---- */

static const double vdp_steps[] = {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001};

static int vanderpol_series(const dyn_hw_vanderpol *hw, dyn_hw_series *s, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_vanderpol;
    dyn_vanderpol_par p = {hw->mu};
    static const char *const methods[4] = {"euler", "heun", "midpoint", "rk4"};
    static const char *const ids[4] = {"vanderpol.euler", "vanderpol.heun", "vanderpol.midpoint",
                                       "vanderpol.rk4"};
    static const char *const titles[4] = {"Euler", "modified Euler", "RK2 (midpoint)", "RK4"};
    for (int i = 0; i < 4; i++)
        if (!record_run(s, ids[i], titles[i], m, &p, methods[i], hw->t1, hw->step, hw->y0, 1, 0,
                        err, errlen))
            return 1;
    const int n_steps = (int)(sizeof vdp_steps / sizeof vdp_steps[0]);
    dyn_hw_table *tab = new_table(s, "vanderpol.steps", "final-state error against the step", NULL,
                                  0.0, err, errlen);
    if (!tab)
        return 1;
    add_column(tab, "step", "s");
    for (int i = 0; i < 4; i++)
        add_column(tab, methods[i], "1");
    if (allocate(tab, n_steps, err, errlen))
        return 1;
    for (int k = 0; k < n_steps; k++) {
        double *row = tab->data + k * tab->cols, y[2];
        row[0] = vdp_steps[k];
        for (int i = 0; i < 4; i++) {
            if (hw_final_state(methods[i], dyn_vanderpol_rhs, &p, 2, 0.0, hw->t1, vdp_steps[k],
                               hw->y0, y, err, errlen))
                return 1;
            row[1 + i] = hw_distance(y, hw->reference, 2);
        }
        tab->rows++;
    }
    return 0;
}

/* ---- problem 3 ---- */

static int plane_series(const dyn_hw_plane *hw, dyn_hw_series *s, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_plane;
    dyn_plane_par p;
    double y0[12];
    if (dyn_model_default_params(m, &p, err, errlen))
        return 1;
    dyn_model_initial_state(m, &p, y0); /* the same start as dyn_hw_plane_compute */
    const dyn_hw_table *e = record_run(s, "plane.euler", "Euler", m, &p, "euler", hw->end_time_s,
                                       hw->step_s, y0, 1, 0, err, errlen);
    const dyn_hw_table *r = e ? record_run(s, "plane.rk4", "RK4", m, &p, "rk4", hw->end_time_s,
                                           hw->step_s, y0, 1, 0, err, errlen)
                              : NULL;
    dyn_hw_table *tab =
        r ? new_table(s, "plane.compare", "Euler against RK4", NULL, hw->step_s, err, errlen)
          : NULL;
    if (!tab)
        return 1;
    add_column(tab, "t", "s");
    add_column(tab, "distance", "m");
    add_column(tab, "principal_angle", "rad");
    const long rows = e->rows < r->rows ? e->rows : r->rows;
    if (allocate(tab, rows, err, errlen))
        return 1;
    for (long k = 0; k < rows; k++) {
        const double *ye = e->data + k * e->cols + 1, *yr = r->data + k * r->cols + 1;
        double Re[9], Rr[9], axis[3], *row = tab->data + k * tab->cols;
        dyn_euler_to_mat(ye + 3, Re);
        dyn_euler_to_mat(yr + 3, Rr);
        row[0] = e->data[k * e->cols];
        row[1] = dyn_vec3_distance(ye, yr);
        row[2] = dyn_principal_angle(Re, Rr, axis);
        tab->rows++;
    }
    return 0;
}

/* ---- problem 4 ---- */

static int cart_series(const dyn_hw_cart *hw, dyn_hw_series *s, char *err, size_t errlen)
{
    const dyn_model *m = &dyn_model_cart;
    dyn_cart_par p;
    if (dyn_model_default_params(m, &p, err, errlen))
        return 1;
    double *table = malloc((size_t)hw->N * 3 * sizeof *table), y0[6];
    if (!table) {
        snprintf(err, errlen, "out of memory for the force table");
        return 1;
    }
    int rc = dyn_cart_force_table(&p, hw->v0, hw->f, hw->N, hw->Ts, table, err, errlen);
    rc = rc ? rc : dyn_cart_prescribed(&p, hw->v0, hw->f, 0.0, y0, NULL);
    dyn_hw_table *tab =
        rc ? NULL : new_table(s, "cart.prescribed", "prescribed motion", NULL, hw->Ts, err, errlen);
    if (tab) {
        add_column(tab, "t", "s");
        for (int i = 0; i < m->n_states; i++)
            add_column(tab, m->states[i].name, m->states[i].unit);
        add_column(tab, "Fx", "N");
        add_column(tab, "Fy", "N");
        add_column(tab, "lambda", "N");
        rc = allocate(tab, hw->N, err, errlen);
        for (long k = 0; k < hw->N && !rc; k++) {
            double *row = tab->data + k * tab->cols, acc[3];
            row[0] = (double)k * hw->Ts;
            rc = dyn_cart_prescribed(&p, hw->v0, hw->f, row[0], row + 1, acc);
            row[7] = table[k * 3 + 1];
            row[8] = table[k * 3 + 2];
            row[9] = dyn_cart_lambda(&p, table[k * 3 + 2], acc[2]);
            tab->rows++;
        }
    } else {
        rc = 1;
    }
    rc = rc ? rc : dyn_cart_set_forces(&p, table, hw->N, DYN_INTERP_HOLD, err, errlen);
    if (!rc && !record_run(s, "cart.forward", "forward, modified Euler, forces held", m, &p, "heun",
                           hw->te, hw->Ts, y0, 1, 0, err, errlen))
        rc = 1;
    free(table);
    return rc;
}

int dyn_homework_series(const dyn_homework *hw, dyn_hw_series *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    if (pendulum_series(&hw->pendulum, s, err, errlen) ||
        vanderpol_series(&hw->vanderpol, s, err, errlen) ||
        plane_series(&hw->plane, s, err, errlen) || cart_series(&hw->cart, s, err, errlen))
        return 1;
    return 0;
}

void dyn_hw_series_free(dyn_hw_series *s)
{
    for (int i = 0; i < s->count && i < DYN_HW_MAX_TABLES; i++)
        free(s->table[i].data);
    memset(s, 0, sizeof *s);
}

const dyn_hw_table *dyn_hw_series_find(const dyn_hw_series *s, const char *id)
{
    for (int i = 0; i < s->count; i++)
        if (strcmp(s->table[i].id, id) == 0)
            return &s->table[i];
    return NULL;
}

int dyn_hw_table_column(const dyn_hw_table *tab, const char *name)
{
    for (int j = 0; j < tab->cols; j++)
        if (tab->names[j] && strcmp(tab->names[j], name) == 0)
            return j;
    return -1;
}
