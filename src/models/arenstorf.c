/* SPDX-License-Identifier: BSD-3-Clause */
/* Arenstorf orbit: the restricted three-body problem (a light body moving in the plane of
 * Earth and Moon, in the frame rotating with them), with the initial state of a periodic
 * orbit found by R. F. Arenstorf (1963). Equations, data and the period from Hairer,
 * Nørsett & Wanner, "Solving Ordinary Differential Equations I", 2nd ed., sec. II.0,
 * eqs. (0.1)-(0.2):
 *   y1'' = y1 + 2 y2' - mu' (y1 + mu) / D1 - mu (y1 - mu') / D2
 *   y2'' = y2 - 2 y1' - mu' y2 / D1 - mu y2 / D2
 *   D1 = ((y1 + mu)^2 + y2^2)^(3/2), D2 = ((y1 - mu')^2 + y2^2)^(3/2),
 *   mu = 0.012277471, mu' = 1 - mu,
 *   y1(0) = 0.994, y1'(0) = 0, y2(0) = 0, y2'(0) = -2.00158510637908252240537862224,
 * periodic with period T = 17.0652165601579625588917206249. The Jacobi constant
 * 2 Omega - |v|^2, Omega = (y1^2 + y2^2)/2 + mu'/r1 + mu/r2, is conserved.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "dynkit/problems.h"

int dyn_arenstorf_rhs(double t, const double *y, double *dydt, void *par)
{
    const dyn_arenstorf_par *p = par;
    const double mu = p->mu, mup = 1.0 - mu;
    (void)t;
    const double x1 = y[0] + mu, x2 = y[0] - mup;
    const double r1s = x1 * x1 + y[1] * y[1], r2s = x2 * x2 + y[1] * y[1];
    const double D1 = r1s * sqrt(r1s), D2 = r2s * sqrt(r2s);
    dydt[0] = y[2];
    dydt[1] = y[3];
    dydt[2] = y[0] + 2.0 * y[3] - mup * x1 / D1 - mu * x2 / D2;
    dydt[3] = y[1] - 2.0 * y[2] - mup * y[1] / D1 - mu * y[1] / D2;
    return 0;
}

int dyn_arenstorf_jac(double t, const double *y, double *J, void *par)
{
    const dyn_arenstorf_par *p = par;
    const double mu = p->mu, mup = 1.0 - mu;
    (void)t;
    const double x1 = y[0] + mu, x2 = y[0] - mup, y2 = y[1];
    const double r1s = x1 * x1 + y2 * y2, r2s = x2 * x2 + y2 * y2;
    const double i3a = 1.0 / (r1s * sqrt(r1s)), i3b = 1.0 / (r2s * sqrt(r2s));
    const double i5a = i3a / r1s, i5b = i3b / r2s;
    /* d(x / r^3)/dx = 1/r^3 - 3 x^2 / r^5, d(x / r^3)/dy = -3 x y / r^5 */
    const double a1y1 = 1.0 - mup * (i3a - 3.0 * x1 * x1 * i5a) - mu * (i3b - 3.0 * x2 * x2 * i5b);
    const double a1y2 = 3.0 * y2 * (mup * x1 * i5a + mu * x2 * i5b);
    const double a2y2 = 1.0 - mup * (i3a - 3.0 * y2 * y2 * i5a) - mu * (i3b - 3.0 * y2 * y2 * i5b);
    const double Jv[16] = {
        0.0,  0.0,  1.0,  0.0,
        0.0,  0.0,  0.0,  1.0,
        a1y1, a1y2, 0.0,  2.0,
        a1y2, a2y2, -2.0, 0.0,
    };
    for (int i = 0; i < 16; i++)
        J[i] = Jv[i];
    return 0;
}

double dyn_arenstorf_jacobi(const dyn_arenstorf_par *p, const double *y)
{
    const double mu = p->mu, mup = 1.0 - mu;
    const double x1 = y[0] + mu, x2 = y[0] - mup;
    const double r1 = sqrt(x1 * x1 + y[1] * y[1]), r2 = sqrt(x2 * x2 + y[1] * y[1]);
    const double omega = 0.5 * (y[0] * y[0] + y[1] * y[1]) + mup / r1 + mu / r2;
    return 2.0 * omega - (y[2] * y[2] + y[3] * y[3]);
}

static int arenstorf_outputs(double t, const double *y, const void *par, double *out)
{
    const dyn_arenstorf_par *p = par;
    const double mu = p->mu, mup = 1.0 - mu;
    (void)t;
    out[0] = dyn_arenstorf_jacobi(p, y);
    out[1] = hypot(y[0] + mu, y[1]);
    out[2] = hypot(y[0] - mup, y[1]);
    return 0;
}

static int arenstorf_prepare(void *par, char *err, size_t errlen)
{
    const dyn_arenstorf_par *p = par;
    if (dyn_check_positive("mu", p->mu, err, errlen))
        return 1;
    if (p->mu >= 1.0) {
        if (err && errlen)
            snprintf(err, errlen, "parameter mu must be < 1 (got %g)", p->mu);
        return 1;
    }
    return 0;
}

static const dyn_var states[] = {
    {"y1", "1", "position along the Earth-Moon line (rotating frame, unit = their distance)"},
    {"y2", "1", "position across the Earth-Moon line"},
    {"dy1", "1", "velocity along the Earth-Moon line (time unit = 1/angular rate)"},
    {"dy2", "1", "velocity across the Earth-Moon line"},
};
static const double y0[] = {0.994, 0.0, 0.0, DYN_ARENSTORF_Y2DOT0};
static const dyn_param params[] = {
    {"mu", "1", "mass ratio Moon / (Earth + Moon)", offsetof(dyn_arenstorf_par, mu),
     DYN_ARENSTORF_MU},
};
static const dyn_var outputs[] = {
    {"jacobi", "1", "Jacobi constant 2 Omega - |v|^2 (conserved)"},
    {"r_earth", "1", "distance to the Earth"},
    {"r_moon", "1", "distance to the Moon"},
};

const dyn_model dyn_model_arenstorf = {
    .name = "arenstorf",
    .title = "Arenstorf orbit, restricted three-body problem (periodic; HNW I sec. II.0)",
    .description =
        "A light body in the plane of Earth and Moon, in the frame rotating with them.\n"
        "  y1'' = y1 + 2 y2' - mu' (y1 + mu)/D1 - mu (y1 - mu')/D2\n"
        "  y2'' = y2 - 2 y1' - mu' y2/D1 - mu y2/D2\n"
        "  D1 = ((y1 + mu)^2 + y2^2)^(3/2), D2 = ((y1 - mu')^2 + y2^2)^(3/2), mu' = 1 - mu\n"
        "The default state starts Arenstorf's periodic orbit, period\n"
        "T = 17.0652165601579625588917206249 (Hairer, Norsett & Wanner I, sec. II.0).",
    .n_states = 4,
    .states = states,
    .y0 = y0,
    .n_params = 1,
    .params = params,
    .par_size = sizeof(dyn_arenstorf_par),
    .n_outputs = 3,
    .outputs = outputs,
    .rhs = dyn_arenstorf_rhs,
    .compute_outputs = arenstorf_outputs,
    .prepare = arenstorf_prepare,
    .t0 = 0.0,
    .t1 = DYN_ARENSTORF_PERIOD,
    .step = DYN_ARENSTORF_PERIOD / 100000.0, /* RK4 closes the orbit to 5e-4 */
    .method = "dop853", /* closes the orbit to 1e-7 (RK4 at this step: --method rk4) */
    .rtol = 1e-10,
    .atol = 1e-10,
    .jacobian = dyn_arenstorf_jac,
};
