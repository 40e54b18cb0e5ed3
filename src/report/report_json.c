/* SPDX-License-Identifier: BSD-3-Clause */
/* The homework report as one flat JSON object: the dotted keys of the design
 * ("pendulum.max_height_m", ...), SI units, numbers as numbers (the shortest decimal that
 * reads back to the same double, dyn_format_double; null if not finite), vectors as arrays,
 * judgements as booleans or short strings. */
#include <math.h>

#include "dynkit/io.h"

#include "dynkit/report.h"

typedef struct json_out {
    FILE *out;
    int count;
    int bad;
} json_out;

static void key(json_out *j, const char *name)
{
    j->bad |= fprintf(j->out, "%s\n  \"%s\": ", j->count++ ? "," : "", name) < 0;
}

static void number(json_out *j, double v)
{
    char s[DYN_DOUBLE_CHARS];
    if (isfinite(v)) {
        dyn_format_double(v, s);
        j->bad |= fputs(s, j->out) < 0;
    } else
        j->bad |= fputs("null", j->out) < 0;
}

static void num(json_out *j, const char *name, double v)
{
    key(j, name);
    number(j, v);
}

static void vec(json_out *j, const char *name, const double *v, int n)
{
    key(j, name);
    j->bad |= fputc('[', j->out) == EOF;
    for (int i = 0; i < n; i++) {
        if (i)
            j->bad |= fputs(", ", j->out) < 0;
        number(j, v[i]);
    }
    j->bad |= fputc(']', j->out) == EOF;
}

static void boolean(json_out *j, const char *name, int v)
{
    key(j, name);
    j->bad |= fputs(v ? "true" : "false", j->out) < 0;
}

static void string(json_out *j, const char *name, const char *v)
{
    key(j, name);
    j->bad |= fprintf(j->out, "\"%s\"", v) < 0;
}

static void pendulum(json_out *j, const dyn_hw_pendulum *p)
{
    num(j, "pendulum.max_height_m", p->max_height_m);
    num(j, "pendulum.phi_small_angle_rad", p->phi_small_angle_rad);
    num(j, "pendulum.phi_euler_rad", p->phi_euler_rad);
    num(j, "pendulum.phi_nonlinear_rad", p->phi_nonlinear_rad);
    num(j, "pendulum.te_s", p->te);
    num(j, "pendulum.dphi_euler_radps", p->dphi_euler);
    num(j, "pendulum.error_small_angle_rad", p->error_small_angle);
    num(j, "pendulum.error_euler_rad", p->error_euler);
    string(j, "pendulum.more_trusted",
           fabs(p->error_small_angle) < fabs(p->error_euler) ? "small_angle" : "euler");
    boolean(j, "pendulum.goes_over_top", p->goes_over_top);
    num(j, "pendulum.euler_10_steps_error_rad", p->euler_10_steps_error);
    num(j, "pendulum.rk4_one_step_error_rad", p->rk4_one_step_error);
    num(j, "pendulum.reference_step_s", p->ref_step);
}

static void vanderpol(json_out *j, const dyn_hw_vanderpol *v)
{
    vec(j, "vanderpol.euler", v->euler, 2);
    vec(j, "vanderpol.modified_euler", v->modified_euler, 2);
    vec(j, "vanderpol.rk4", v->rk4, 2);
    vec(j, "vanderpol.midpoint", v->midpoint, 2);
    vec(j, "vanderpol.reference", v->reference, 2);
    num(j, "vanderpol.step_s", v->step);
    num(j, "vanderpol.end_time_s", v->t1);
    vec(j, "vanderpol.error_euler_heun_midpoint_rk4", v->error, 4);
    num(j, "vanderpol.reference_step_s", v->ref_step);
}

static void plane(json_out *j, const dyn_hw_plane *p)
{
    num(j, "plane.step_s", p->step_s);
    num(j, "plane.end_time_s", p->end_time_s);
    num(j, "plane.distance_m", p->distance_m);
    num(j, "plane.principal_angle_rad", p->principal_angle_rad);
    vec(j, "plane.final_euler", p->final_euler, 12);
    vec(j, "plane.final_rk4", p->final_rk4, 12);
    vec(j, "plane.final_reference", p->reference, 12);
    num(j, "plane.reference_step_s", p->ref_step);
    num(j, "plane.rk4_distance_to_reference_m", p->rk4_distance_to_reference_m);
    num(j, "plane.euler_distance_to_reference_m", p->euler_distance_to_reference_m);
    num(j, "plane.euler_min_theta_margin_rad", p->euler_min_theta_margin_rad);
    num(j, "plane.rk4_min_theta_margin_rad", p->rk4_min_theta_margin_rad);
    num(j, "plane.rk4_angle_to_reference_rad", p->rk4_angle_to_reference_rad);
    num(j, "plane.euler_angle_to_reference_rad", p->euler_angle_to_reference_rad);
    num(j, "plane.energy_drift_euler", p->energy_drift_euler);
    num(j, "plane.energy_drift_rk4", p->energy_drift_rk4);
}

static void cart(json_out *j, const dyn_hw_cart *c)
{
    num(j, "cart.initial_dsY_mps", c->initial_dsY_mps);
    num(j, "cart.final_Fx_N", c->final_Fx_N);
    num(j, "cart.final_Fy_N", c->final_Fy_N);
    num(j, "cart.forward_error_sX_m", c->forward_error_sX_m);
    num(j, "cart.max_constraint_force_N", c->max_constraint_force_N);
    num(j, "cart.friction_limit_N", c->friction_limit_N);
    boolean(j, "cart.rear_wheels_slip", c->rear_wheels_slip);
    num(j, "cart.te_s", c->te);
    num(j, "cart.N", (double)c->N);
    num(j, "cart.Ts_s", c->Ts);
    num(j, "cart.forward_sX_m", c->forward_sX_m);
    num(j, "cart.exact_sX_m", c->exact_sX_m);
    num(j, "cart.t_max_constraint_force_s", c->t_max_constraint_force);
    num(j, "cart.max_constraint_force_prescribed_N", c->max_constraint_force_prescribed_N);
    vec(j, "cart.study_Ts_s", c->study_Ts, c->n_study);
    vec(j, "cart.study_error_heun_hold_m", c->study_error_heun_hold, c->n_study);
    vec(j, "cart.study_error_rk4_hold_m", c->study_error_rk4_hold, c->n_study);
    vec(j, "cart.study_error_rk4_linear_m", c->study_error_rk4_linear, c->n_study);
    num(j, "cart.max_constraint_residual_mps", c->max_constraint_residual);
    num(j, "cart.instability_rate_per_s", c->instability_rate);
    num(j, "cart.t_departure_1cm_s", c->t_departure_1cm);
    num(j, "cart.t_departure_1m_s", c->t_departure_1m);
    num(j, "cart.sensitivity_step_s", c->sensitivity_step);
    num(j, "cart.sensitivity_dtheta0_rad", c->sensitivity_dtheta0);
    num(j, "cart.sensitivity_error_sX_m", c->sensitivity_error_sX_m);
    num(j, "cart.sensitivity_sX_m", c->sensitivity_sX_m);
}

/* The studies of many runs (report_studies.h): their answers and small curves; the page
 * carries the runs themselves. */
static void studies(json_out *j, const dyn_hw_studies *s)
{
    const dyn_study_period *pe = &s->period;
    const dyn_study_plane *pl = &s->plane;
    const dyn_study_cart *c = &s->cart;
    static const double percent[DYN_STUDY_PERCENTILES] = {5, 25, 50, 75, 95};
    double dist[2] = {pl->distance_min, pl->distance_max};
    double ang[2] = {pl->angle_min, pl->angle_max};
    vec(j, "plane.distance_spread_m", dist, 2);
    vec(j, "plane.principal_angle_spread_rad", ang, 2);
    num(j, "plane.perturbation_relative", pl->perturbation);
    num(j, "studies.threads", s->threads);
    num(j, "studies.runs", (double)s->runs);
    num(j, "studies.wall_seconds", s->wall_seconds);
    num(j, "studies.period.runs", pe->n);
    num(j, "studies.period.failed", pe->n_failed);
    num(j, "studies.period.rtol", pe->rtol);
    vec(j, "studies.period.amplitude_rad", pe->amplitude_rad, pe->n);
    vec(j, "studies.period.period_s", pe->period_s, pe->n);
    vec(j, "studies.period.exact_s", pe->exact_s, pe->n);
    num(j, "studies.period.small_angle_period_s", 2.0 * DYN_PI / pe->w);
    num(j, "studies.period.max_difference_s", pe->max_difference_s);
    num(j, "studies.period.amplitude_at_max_rad", pe->amplitude_at_max_rad);
    num(j, "studies.plane.runs", (double)pl->n_runs);
    num(j, "studies.plane.seed", (double)pl->seed);
    num(j, "studies.plane.changed_states", pl->n_changed);
    num(j, "studies.plane.failed", (double)pl->n_failed);
    vec(j, "studies.plane.percentiles", percent, DYN_STUDY_PERCENTILES);
    num(j, "studies.plane.distance_mean_m", pl->distance_mean);
    vec(j, "studies.plane.distance_percentiles_m", pl->distance_pct, DYN_STUDY_PERCENTILES);
    num(j, "studies.plane.angle_mean_rad", pl->angle_mean);
    vec(j, "studies.plane.angle_percentiles_rad", pl->angle_pct, DYN_STUDY_PERCENTILES);
    num(j, "studies.cart.runs", (double)c->n_v0 * c->n_f);
    num(j, "studies.cart.failed", (double)c->n_failed);
    vec(j, "studies.cart.v0_mps", c->v0, c->n_v0);
    vec(j, "studies.cart.f_Hz", c->f, c->n_f);
    vec(j, "studies.cart.boundary_f_Hz", c->boundary_f, c->n_v0);
    num(j, "studies.cart.homework_ratio", c->homework_ratio);
    num(j, "studies.cart.homework_slip_fraction", c->homework_slip_fraction);
}

int dyn_homework_write_json(const dyn_homework *hw, FILE *out)
{
    json_out j = {out, 0, 0};
    j.bad |= fputc('{', out) == EOF;
    pendulum(&j, &hw->pendulum);
    vanderpol(&j, &hw->vanderpol);
    plane(&j, &hw->plane);
    cart(&j, &hw->cart);
    if (hw->studies.computed)
        studies(&j, &hw->studies);
    num(&j, "compute_seconds", hw->compute_seconds);
    j.bad |= fputs("\n}\n", out) < 0;
    return j.bad;
}
