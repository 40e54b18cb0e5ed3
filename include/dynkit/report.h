/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/report.h — the homework's answers (TU Delft Advanced Dynamics, homework 8),
 * computed at run time, and writers for them as text and JSON.
 *
 * dyn_homework_compute runs every analysis of problems 1 to 4 and fills one struct; the
 * writers only format it. Everything is computed from the models and integrators of the
 * library: no number is stored. dyn_homework_series records the runs behind the answers as
 * tables of samples, for plots and animations (the dynkit tool draws them in a page).
 */
#ifndef DYNKIT_REPORT_H
#define DYNKIT_REPORT_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Problem 1: pendulum. */
typedef struct dyn_hw_pendulum {
    double m, l, g;             /* [kg], [m], [m/s^2] */
    double y0[2];               /* phi0 [rad], dphi0 [rad/s] */
    double te;                  /* [s] time of 1c/1e */
    double max_height_m;        /* 1a: from energy */
    int goes_over_top;          /* 1a: energy exceeds 2 m g l */
    double phi_small_angle_rad; /* 1c */
    double phi_euler_rad;       /* 1e: one Euler step h = te */
    double dphi_euler;          /* 1e: its angular velocity [rad/s] */
    double phi_nonlinear_rad;   /* reference: RK4 at ref_step */
    double ref_step;            /* [s] */
    double ref_error_estimate;  /* |RK4(ref_step) - RK4(2 ref_step)| [rad] */
    double error_small_angle;   /* phi_small_angle - phi_nonlinear [rad] */
    double error_euler;         /* phi_euler - phi_nonlinear [rad] */
    /* 1f: the two measures, each measured */
    double euler_10_steps_error;  /* Euler with 10 steps of te/10, error [rad] */
    double rk4_one_step_error;    /* one RK4 step of te, error [rad] */
} dyn_hw_pendulum;

/* Problem 2: van der Pol, final state at t1 for each method. */
typedef struct dyn_hw_vanderpol {
    double mu, step, t1, y0[2];
    double euler[2], modified_euler[2], midpoint[2], rk4[2];
    double reference[2];        /* RK4 at ref_step */
    double ref_step, ref_error_estimate;
    double error[4];            /* |final - reference| (2-norm): euler, heun, midpoint, rk4 */
} dyn_hw_vanderpol;

/* Problem 3: the plane, Euler vs RK4 at the same step. */
typedef struct dyn_hw_plane {
    double step_s, end_time_s;
    double final_euler[12], final_rk4[12];
    double distance_m;          /* |s_euler - s_rk4| at end_time */
    double principal_angle_rad; /* rotation between the two final orientations */
    double euler_min_theta_margin_rad; /* closest approach of theta to +-pi/2 (Euler run) */
    double rk4_min_theta_margin_rad;
    /* converged reference: RK4 at ref_step, checked against 2 ref_step */
    double reference[12];
    double ref_step, ref_error_estimate_m;
    double rk4_distance_to_reference_m, rk4_angle_to_reference_rad;
    double euler_distance_to_reference_m, euler_angle_to_reference_rad;
    double energy_drift_euler, energy_drift_rk4; /* relative change of energy over the run */
} dyn_hw_plane;

/* Problem 4: the cart, prescribed motion, inverse and forward dynamics. */
#define DYN_HW_CART_STUDY 4
typedef struct dyn_hw_cart {
    double v0, f, Ts, te;       /* [m/s], [Hz], [s], [s] */
    long N;
    double initial_dsY_mps;     /* 4a */
    double final_Fx_N, final_Fy_N;  /* 4b: at te */
    double forward_sX_m, exact_sX_m, forward_error_sX_m; /* 4c: heun, force table held */
    double max_constraint_force_N;  /* 4d: max |lambda| over the N samples */
    double t_max_constraint_force;
    double friction_limit_N;    /* mu (2/3) m g */
    double mu, g, m;
    int rear_wheels_slip;
    double max_constraint_residual; /* of the forward run [m/s] */
    /* how the forward error behaves as the sampling time (table and step) is halved: the
     * homework's heun with the table held, and RK4, whose midpoint stages fall between the
     * samples, with the table held and linearly interpolated */
    int n_study;
    double study_Ts[DYN_HW_CART_STUDY];
    double study_error_heun_hold[DYN_HW_CART_STUDY];
    double study_error_rk4_hold[DYN_HW_CART_STUDY];
    double study_error_rk4_linear[DYN_HW_CART_STUDY];
    double max_constraint_force_prescribed_N; /* along the exact prescribed motion */
    double t_departure_1cm, t_departure_1m; /* when the 4c run leaves the prescribed path */
    /* growth rate of a yaw perturbation of straight backward motion, linearised:
     * sigma = m v0 l / (m l^2/2 + 2 Is) [1/s] */
    double instability_rate;
    /* the instability itself: forces of the exact motion at every instant, RK4 at
     * sensitivity_step, from the exact initial state and from theta(0) + dtheta0 */
    double sensitivity_step, sensitivity_dtheta0;
    double sensitivity_error_sX_m;   /* |sX(te) - exact| from the exact initial state */
    double sensitivity_sX_m;         /* |change of sX(te)| caused by dtheta0 */
} dyn_hw_cart;

/* ---- three studies of many runs, computed by the sweep library (dynkit/report_studies.h,
 * library dynkit_sweep); dyn_homework_compute leaves them out (studies.computed = 0) ---- */

/* Problem 1: the period against the amplitude, against the exact 4 K(k) / w, k = sin(a/2). */
#define DYN_STUDY_PERIOD_RUNS 60
typedef struct dyn_study_period {
    int n;                      /* runs */
    double w;                   /* sqrt(g/l) [1/s] */
    double rtol;                /* of the runs (dop853, atol = rtol) */
    double amplitude_rad[DYN_STUDY_PERIOD_RUNS]; /* phi(0), released at rest */
    double period_s[DYN_STUDY_PERIOD_RUNS];      /* 4 x the time of the first bottom */
    double exact_s[DYN_STUDY_PERIOD_RUNS];       /* 4 K(k) / w, K by the AGM */
    int n_failed;
    double max_difference_s;    /* max |period - exact| */
    double amplitude_at_max_rad;
} dyn_study_period;

/* Problem 3: Euler vs RK4 from many starts, each non-zero initial state changed by a
 * relative normal amount (Philox4x32-10, seed). Percentiles: 5, 25, 50, 75, 95. */
#define DYN_STUDY_PLANE_RUNS 1000
#define DYN_STUDY_PERCENTILES 5
typedef struct dyn_study_plane {
    long n_runs;
    unsigned long seed;
    double perturbation;        /* standard deviation of the relative change */
    int n_changed;              /* initial states changed (the non-zero ones) */
    long n_failed;              /* runs of either method that failed (left out) */
    double distance_m[DYN_STUDY_PLANE_RUNS];  /* NaN for a failed run */
    double angle_rad[DYN_STUDY_PLANE_RUNS];
    double distance_mean, distance_min, distance_max, distance_pct[DYN_STUDY_PERCENTILES];
    double angle_mean, angle_min, angle_max, angle_pct[DYN_STUDY_PERCENTILES];
} dyn_study_plane;

/* Problem 4: max |lambda| / friction limit along the prescribed motion (4d's "along the
 * exact prescribed motion", N samples at Ts) over a grid of v0 and f. */
#define DYN_STUDY_CART_V0 31
#define DYN_STUDY_CART_F 31
typedef struct dyn_study_cart {
    int n_v0, n_f;
    double v0[DYN_STUDY_CART_V0], f[DYN_STUDY_CART_F]; /* [m/s], [Hz] */
    double ratio[DYN_STUDY_CART_V0 * DYN_STUDY_CART_F];  /* [i * n_f + j]: v0[i], f[j] */
    double boundary_f[DYN_STUDY_CART_V0]; /* smallest f of ratio 1 (linear between grid
                                           * points), NaN if none on the grid */
    long n_failed;
    double homework_ratio;      /* the cell of the homework's v0, f */
    double homework_slip_fraction; /* of the time its wheels would slip (time average) */
} dyn_study_cart;

typedef struct dyn_hw_studies {
    int computed;
    int threads;
    long runs;                  /* all runs of the three studies */
    double wall_seconds;
    dyn_study_period period;
    dyn_study_plane plane;
    dyn_study_cart cart;
} dyn_hw_studies;

typedef struct dyn_homework {
    dyn_hw_pendulum pendulum;
    dyn_hw_vanderpol vanderpol;
    dyn_hw_plane plane;
    dyn_hw_cart cart;
    double compute_seconds;     /* CPU time of dyn_homework_compute */
    dyn_hw_studies studies;     /* filled by dyn_homework_studies (report_studies.h) */
} dyn_homework;

/* Compute every answer. Returns 0, or non-zero with a message in err. */
int dyn_homework_compute(dyn_homework *hw, char *err, size_t errlen);

/* Write the report as text (answers, how they were computed, judgements) or as one flat
 * JSON object with the dotted keys of the design; the studies too when computed. Return 0
 * or non-zero on a write error. */
int dyn_homework_write_text(const dyn_homework *hw, FILE *out);
int dyn_homework_write_json(const dyn_homework *hw, FILE *out);


/* ---- the time series behind the answers, for plots and animations (hw_series.c) ---- */

#define DYN_HW_MAX_COLS 24
#define DYN_HW_MAX_TABLES 16

/* A table of samples: column 0 is the abscissa (the time, or the step size of a study),
 * the others named quantities with SI units. Names and units are static strings. */
typedef struct dyn_hw_table {
    const char *id;            /* e.g. "pendulum.nonlinear", "plane.euler" */
    const char *title;         /* one line for people, e.g. "RK4, h = 0.01 s" (static) */
    const char *method;        /* integration method name, or NULL (exact motion, study) */
    double step;               /* step of the run [s], 0 when not a run */
    int cols;
    const char *names[DYN_HW_MAX_COLS];
    const char *units[DYN_HW_MAX_COLS];
    long rows;
    double *data;              /* (rows x cols) row-major, owned: dyn_hw_series_free */
} dyn_hw_table;

/* Every table of the report page, in a fixed order. */
typedef struct dyn_hw_series {
    int count;
    dyn_hw_table table[DYN_HW_MAX_TABLES];
} dyn_hw_series;

/* The runs behind hw (filled by dyn_homework_compute), recorded sample by sample with the
 * same models, methods, steps and initial states, so each answer is a sample of a table
 * (the last row of "pendulum.step" is phi_nonlinear_rad, of "plane.euler" final_euler, the
 * largest |lambda| of "cart.forward" max_constraint_force_N, ...), plus longer spans for
 * the pictures and the final-state error of van der Pol against the step. Tables:
 *   pendulum.nonlinear  RK4 at 0.01 s over 10 s: t, phi, dphi, energy, height, phi_small_angle,
 *                       small_angle_error (phi_small_angle - phi)
 *   pendulum.euler      Euler at te over 10 s: t, phi, dphi, energy, height
 *   pendulum.step       the reference run over [0, te], every 10th sample, as .nonlinear
 *   vanderpol.euler, .heun, .midpoint, .rk4   t, y1, y2 at the homework's step
 *   vanderpol.steps     step, error of euler, heun, midpoint, rk4 at t1 (2-norm)
 *   plane.euler, plane.rk4   t, the 12 states, energy, spring_length, theta_margin
 *   plane.compare       t, distance between the two centres of mass, principal angle
 *   cart.prescribed     t, the exact motion (6 states), the table's Fx, Fy, and lambda
 *   cart.forward        t, the 4c run's states and the cart's outputs (Fx, Fy, lambda, ...)
 * s is zeroed first and owns the data; release it with dyn_hw_series_free (also after a
 * failure). Returns 0, or non-zero with a message in err. */
int dyn_homework_series(const dyn_homework *hw, dyn_hw_series *s, char *err, size_t errlen);
/* Release the tables of s and zero it; safe on a zeroed struct. */
void dyn_hw_series_free(dyn_hw_series *s);
/* The table called id, or NULL. */
const dyn_hw_table *dyn_hw_series_find(const dyn_hw_series *s, const char *id);
/* Index of the column called name in tab, or -1. */
int dyn_hw_table_column(const dyn_hw_table *tab, const char *name);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_REPORT_H */
