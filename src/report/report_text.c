/* SPDX-License-Identifier: BSD-3-Clause */
/* The homework report as text: every question of problems 1 to 4 in order, each answer with
 * its unit and how it was computed, and the judgements with the numbers behind them. */
#include <math.h>

#include "dynkit/mech.h"
#include "dynkit/report.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

static void state12(FILE *out, const char *label, const double *y)
{
    fprintf(out, "     %-10s s = (%.6f, %.6f, %.6f) m  psi,theta,phi = (%.6f, %.6f, %.6f) rad\n",
            label, y[0], y[1], y[2], y[3], y[4], y[5]);
    fprintf(out, "     %-10s ds = (%.6f, %.6f, %.6f) m/s  omega = (%.6f, %.6f, %.6f) rad/s\n", "",
            y[6], y[7], y[8], y[9], y[10], y[11]);
}

static void pendulum(FILE *out, const dyn_hw_pendulum *p)
{
    const double w = sqrt(p->g / p->l);
    fprintf(out,
            "Problem 1 - pendulum: m = %g kg, l = %g m, g = %g m/s^2, phi(0) = %g rad, "
            "dphi(0) = %.6g rad/s\n",
            p->m, p->l, p->g, p->y0[0], p->y0[1]);
    fprintf(out, " 1a  maximum height above the bottom: %.6f m\n", p->max_height_m);
    fprintf(out, "     energy: 1/2 m (l dphi0)^2 = m g h, so h = (l dphi0)^2 / (2 g)");
    if (p->goes_over_top)
        fprintf(out, "; this exceeds 2 l: the mass goes over the top, h = 2 l\n");
    else
        fprintf(out, " < 2 l = %g m: the mass turns back%s\n", 2 * p->l,
                p->max_height_m > p->l ? " (above the pivot: the rigid rod holds it)" : "");
    fprintf(out, " 1b  equation of motion (moments about the pivot): m l^2 ddphi = -m g l sin(phi),\n"
                 "     ddphi = -(g/l) sin(phi); the mass m cancels\n");
    fprintf(out, " 1c  small angles, sin(phi) ~ phi: phi(t) = phi0 cos(w t) + dphi0/w sin(w t), "
                 "w = sqrt(g/l) = %g 1/s\n", w);
    fprintf(out, "     phi(%g s) = %.10f rad\n", p->te, p->phi_small_angle_rad);
    fprintf(out, " 1d  x = (phi, dphi): dx/dt = (dphi, -(g/l) sin(phi))\n");
    fprintf(out, " 1e  one Euler step, h = %g s: phi(%g s) = phi0 + h dphi0 = %.10f rad "
                 "(dphi = %.10f rad/s)\n", p->te, p->te, p->phi_euler_rad, p->dphi_euler);
    fprintf(out, "     nonlinear solution (RK4, h = %g s; halving the step changes it by %.1e rad): "
                 "phi(%g s) = %.10f rad\n", p->ref_step, p->ref_error_estimate, p->te,
            p->phi_nonlinear_rad);
    fprintf(out, "     error of the small-angle result: %+.3e rad; of the Euler result: %+.3e rad\n",
            p->error_small_angle, p->error_euler);
    const int trust_small = fabs(p->error_small_angle) < fabs(p->error_euler);
    fprintf(out, "     trust more: the %s result, %.0f times closer to the nonlinear solution.\n",
            trust_small ? "small-angle" : "Euler",
            trust_small ? fabs(p->error_euler / p->error_small_angle)
                        : fabs(p->error_small_angle / p->error_euler));
    fprintf(out, "     Over %g s the angle stays small (%.2f rad), so linearising costs little, "
                 "while one Euler step of %g s\n     ignores that the rod decelerates during "
                 "the step (its error is O(h^2)). For longer times the small-angle\n"
                 "     solution fails: the amplitude here reaches %.2f rad.\n",
            p->te, p->phi_nonlinear_rad, p->te, acos(1.0 - p->max_height_m / p->l));
    fprintf(out, " 1f  two measures: (1) smaller steps: 10 Euler steps of %g s give an error of "
                 "%+.3e rad;\n     (2) a higher-order method: one RK4 step of %g s gives "
                 "%+.3e rad. Both together converge fastest.\n",
            p->te / 10, p->euler_10_steps_error, p->te, p->rk4_one_step_error);
}

/* Study: the period against the amplitude (report_studies.h). */
static void period_study(FILE *out, const dyn_study_period *s)
{
    fprintf(out, "     Many runs: the period against the amplitude, %d runs of dyn_sweep (released "
                 "at rest from phi(0) = a,\n     dop853 with rtol = atol = %g, each stopped at "
                 "its first bottom, T = 4 t_bottom) against 4 K(k)/w, k = sin(a/2):\n",
            s->n, s->rtol);
    fprintf(out, "     %10s  %20s  %20s  %10s\n", "a [rad]", "T [s]", "4 K(k)/w [s]",
            "T w/(2 pi)");
    const int every = s->n > 6 ? (s->n - 1) / 5 : 1;
    for (int i = 0; i < s->n; i++)
        if (i % every == 0 || i == s->n - 1)
            fprintf(out, "     %10.4f  %20.15f  %20.15f  %10.6f\n", s->amplitude_rad[i],
                    s->period_s[i], s->exact_s[i], s->period_s[i] * s->w / (2.0 * DYN_PI));
    fprintf(out, "     largest |T - 4 K(k)/w| = %.2e s (at a = %.4f rad)%s; the small-angle "
                 "period 2 pi/w holds only for small a.\n",
            s->max_difference_s, s->amplitude_at_max_rad,
            s->n_failed ? " over the runs that finished" : "");
}

static void vanderpol(FILE *out, const dyn_hw_vanderpol *v)
{
    fprintf(out, "Problem 2 - van der Pol, mu = %g, y0 = (%g, %g), %g s at step %g s: "
                 "final state y(%g s)\n", v->mu, v->y0[0], v->y0[1], v->t1, v->step, v->t1);
    const char *names[4] = {"Euler", "modified Euler", "RK2 (midpoint)", "RK4"};
    const double *finals[4] = {v->euler, v->modified_euler, v->midpoint, v->rk4};
    for (int i = 0; i < 4; i++)
        fprintf(out, "     %-15s y = (%.15f, %.15f)   distance to reference %.2e\n", names[i],
                finals[i][0], finals[i][1], v->error[i]);
    fprintf(out, "     reference       y = (%.15f, %.15f)   (RK4 at h = %g s; halving it "
                 "changes it by %.1e)\n\n", v->reference[0], v->reference[1], v->ref_step,
            v->ref_error_estimate);
}

static void plane(FILE *out, const dyn_hw_plane *p, const dyn_hw_studies *st)
{
    fprintf(out, "Problem 3 - model plane on a spring (Newton-Euler, type I Euler angles), "
                 "step %g s, %g s\n", p->step_s, p->end_time_s);
    state12(out, "Euler:", p->final_euler);
    state12(out, "RK4:", p->final_rk4);
    fprintf(out, "     distance between the final centres of mass (Euler vs RK4): %.6f m\n",
            p->distance_m);
    fprintf(out, "     principal angle between the final orientations: %.6f rad (%.3f deg)\n",
            p->principal_angle_rad, p->principal_angle_rad * RAD2DEG);
    fprintf(out, "     How much these numbers mean:\n");
    fprintf(out, "     - the Euler run comes within %.3f deg of theta = +-90 deg (the Euler-angle "
                 "singularity); RK4 stays %.1f deg away\n",
            p->euler_min_theta_margin_rad * RAD2DEG, p->rk4_min_theta_margin_rad * RAD2DEG);
    if (st && st->computed) {
        const dyn_study_plane *d = &st->plane;
        fprintf(out, "     - %ld starts, each of the %d non-zero initial states changed by a relative "
                     "normal amount (standard deviation %.0e;\n       Philox4x32-10, seed %lu), "
                     "Euler and RK4 each through dyn_sweep%s:\n",
                d->n_runs, d->n_changed, d->perturbation, d->seed,
                d->n_failed ? " (runs that failed left out)" : "");
        fprintf(out, "       distance mean %.4f m, percentiles 5/25/50/75/95 %% = %.4f/%.4f/%.4f/%.4f/%.4f m, "
                     "range [%.4f, %.4f] m\n",
                d->distance_mean, d->distance_pct[0], d->distance_pct[1], d->distance_pct[2],
                d->distance_pct[3], d->distance_pct[4], d->distance_min, d->distance_max);
        fprintf(out, "       angle mean %.4f rad, percentiles 5/25/50/75/95 %% = %.4f/%.4f/%.4f/%.4f/%.4f rad, "
                     "range [%.4f, %.4f] rad:\n       at this step the Euler answer is %s with "
                     "respect to rounding\n",
                d->angle_mean, d->angle_pct[0], d->angle_pct[1], d->angle_pct[2], d->angle_pct[3],
                d->angle_pct[4], d->angle_min, d->angle_max,
                (d->distance_max - d->distance_min) > 1e-6 * (1 + p->distance_m) ? "chaotic"
                                                                                  : "stable");
    }
    fprintf(out, "     - converged reference: RK4 at h = %g s (halving the step moves s by "
                 "%.1e m); RK4 at %g s is %.1e m\n       and %.1e rad from it, Euler at %g s is "
                 "%.3f m and %.3f rad from it: the distance above is Euler's error\n",
            p->ref_step, p->ref_error_estimate_m, p->step_s, p->rk4_distance_to_reference_m,
            p->rk4_angle_to_reference_rad, p->step_s, p->euler_distance_to_reference_m,
            p->euler_angle_to_reference_rad);
    fprintf(out, "     - energy (conserved by the exact motion) changes by %+.2e (Euler) and "
                 "%+.2e (RK4), relative\n\n", p->energy_drift_euler, p->energy_drift_rk4);
}

static void cart(FILE *out, const dyn_hw_cart *c)
{
    fprintf(out, "Problem 4 - three-wheeled cart: sX = -v0 t, theta = pi/8 sin(2 pi f t), "
                 "v0 = %g m/s, f = %g Hz, N = %ld, Ts = %g s\n", c->v0, c->f, c->N, c->Ts);
    fprintf(out, " 4a  initial lateral velocity from the constraint dsY cos(theta) - dsX "
                 "sin(theta) = (l/2) omega:\n     dsY(0) = %.10f m/s\n", c->initial_dsY_mps);
    fprintf(out, " 4b  inverse dynamics, body-frame forces at te = (N-1) Ts = %g s:\n"
                 "     Fx = %.10f N, Fy = %.10f N\n", c->te, c->final_Fx_N, c->final_Fy_N);
    fprintf(out, " 4c  forward run, modified Euler at Ts, forces held at the nearest sample:\n"
                 "     sX(te) = %.10f m, exact -v0 te = %.10f m, absolute error %.6e m\n",
            c->forward_sX_m, c->exact_sX_m, c->forward_error_sX_m);
    fprintf(out, "     the run leaves the prescribed path by 1 cm at t = %g s and by 1 m at "
                 "t = %g s.\n", c->t_departure_1cm, c->t_departure_1m);
    fprintf(out, "     Driving backwards with the no-slip axle at the rear is unstable open "
                 "loop: linearised about straight\n     backward motion, a yaw rate grows like "
                 "exp(sigma t), sigma = m v0 l / (m l^2/2 + 2 Is) = %.4g 1/s, a factor\n"
                 "     %.1e over te. Every error (the step's, the held forces') is amplified "
                 "until the cart leaves the path:\n     even with the forces of the exact motion "
                 "at every instant and RK4 at %g s, sX(te) is off by %.3g m,\n     and "
                 "changing theta(0) by %.0e rad moves it by %.3g m. So this error measures the "
                 "instability,\n     not the step. Table and step refined together:\n"
                 "     %10s  %16s  %16s  %16s\n", c->instability_rate,
            exp(c->instability_rate * c->te), c->sensitivity_step, c->sensitivity_error_sX_m,
            c->sensitivity_dtheta0, c->sensitivity_sX_m, "Ts [s]", "heun, held [m]",
            "RK4, held [m]", "RK4, linear [m]");
    for (int i = 0; i < c->n_study; i++)
        fprintf(out, "     %10g  %16.6e  %16.6e  %16.6e\n", c->study_Ts[i],
                c->study_error_heun_hold[i], c->study_error_rk4_hold[i],
                c->study_error_rk4_linear[i]);
    fprintf(out, "     (heun evaluates the forces only at sample times, where holding and "
                 "interpolating agree;\n     RK4's midpoint stages fall between samples.)\n");
    fprintf(out, " 4d  rear-axle constraint force lambda = Fy - 2 Is domega / l over the N samples "
                 "of the forward run:\n     max |lambda| = %.6f N (at t = %g s); along the exact "
                 "prescribed motion %.6f N\n", c->max_constraint_force_N,
            c->t_max_constraint_force, c->max_constraint_force_prescribed_N);
    fprintf(out, "     friction limit of the two rear wheels, mu (2/3) m g = %g * 2/3 * %g * %g = "
                 "%.6f N\n", c->mu, c->m, c->g, c->friction_limit_N);
    fprintf(out, "     no-slip assumption valid: %s (max |lambda| is %.2f times the limit)\n",
            c->rear_wheels_slip ? "NO, the rear wheels would slip" : "yes",
            c->max_constraint_force_N / c->friction_limit_N);
}

/* Study: where the rear wheels start to slip (report_studies.h). */
static void cart_study(FILE *out, const dyn_study_cart *s)
{
    fprintf(out, "     Many runs: max |lambda| / (mu (2/3) m g) along the prescribed motion over v0 = "
                 "%g..%g m/s and f = %g..%g Hz,\n     %d x %d runs of dyn_sweep (RK4 of the path "
                 "at Ts, N samples)%s:\n",
            s->v0[0], s->v0[s->n_v0 - 1], s->f[0], s->f[s->n_f - 1], s->n_v0, s->n_f,
            s->n_failed ? ", runs that failed left out" : "");
    fprintf(out, "     at the homework's v0 = 20 m/s, f = 2 Hz the ratio is %.4f (4d along the exact "
                 "motion), the wheels would slip\n     %.0f %% of the time; "
                 "the rear wheels slip (ratio >= 1) from f =\n",
            s->homework_ratio, 100.0 * s->homework_slip_fraction);
    const int every = s->n_v0 > 7 ? (s->n_v0 - 1) / 6 : 1;
    for (int i = 0; i < s->n_v0; i += every) {
        if (isnan(s->boundary_f[i]))
            fprintf(out, "       %8s Hz at v0 = %g m/s (no slip up to %g Hz)\n", "-", s->v0[i],
                    s->f[s->n_f - 1]);
        else
            fprintf(out, "       %8.4f Hz at v0 = %g m/s\n", s->boundary_f[i], s->v0[i]);
    }
}

int dyn_homework_write_text(const dyn_homework *hw, FILE *out)
{
    fprintf(out, "dynkit report - TU Delft Advanced Dynamics, homework 8, every number computed "
                 "now\n\n");
    pendulum(out, &hw->pendulum);
    if (hw->studies.computed)
        period_study(out, &hw->studies.period);
    fputc('\n', out);
    vanderpol(out, &hw->vanderpol);
    plane(out, &hw->plane, &hw->studies);
    cart(out, &hw->cart);
    if (hw->studies.computed)
        cart_study(out, &hw->studies.cart);
    fputc('\n', out);
    fprintf(out, "(computed in %.3f s of CPU time)\n", hw->compute_seconds);
    if (hw->studies.computed)
        fprintf(out, "(the studies of many runs: %ld runs on %d thread%s in %.3f s)\n",
                hw->studies.runs, hw->studies.threads, hw->studies.threads == 1 ? "" : "s",
                hw->studies.wall_seconds);
    return ferror(out) ? 1 : 0;
}
