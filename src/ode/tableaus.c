/* Butcher tables of the explicit Runge–Kutta methods, as data in one place.
 *
 * Coefficients: Hairer, Nørsett & Wanner, "Solving Ordinary Differential Equations I",
 * 2nd ed., sec. II.1 (Euler, Heun, midpoint, Runge's RK4, Kutta's 3/8 rule) and
 * A. Ralston, "Runge-Kutta methods with minimum error bounds", Math. Comp. 16 (1962).
 * Heun's method is the homework's "modified Euler" (Greenwood, "Advanced Dynamics", p. 341):
 * predictor y~ = y + h f(t, y), corrector y + h/2 (f(t, y) + f(t + h, y~)).
 * Every table is driven by the one stage loop in rk_step.c.
 */
#include <stdio.h>
#include <string.h>

#include "dynkit/ode.h"

static const double euler_a[] = {0.0};
static const double euler_b[] = {1.0};
static const double euler_c[] = {0.0};

static const double heun_a[] = {0.0, 0.0,
                                1.0, 0.0};
static const double heun_b[] = {0.5, 0.5};
static const double heun_c[] = {0.0, 1.0};

static const double midpoint_a[] = {0.0, 0.0,
                                    0.5, 0.0};
static const double midpoint_b[] = {0.0, 1.0};
static const double midpoint_c[] = {0.0, 0.5};

static const double ralston_a[] = {0.0, 0.0,
                                   2.0 / 3.0, 0.0};
static const double ralston_b[] = {0.25, 0.75};
static const double ralston_c[] = {0.0, 2.0 / 3.0};

static const double rk4_a[] = {0.0, 0.0, 0.0, 0.0,
                               0.5, 0.0, 0.0, 0.0,
                               0.0, 0.5, 0.0, 0.0,
                               0.0, 0.0, 1.0, 0.0};
static const double rk4_b[] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[] = {0.0, 0.5, 0.5, 1.0};

static const double rk38_a[] = {0.0, 0.0, 0.0, 0.0,
                                1.0 / 3.0, 0.0, 0.0, 0.0,
                                -1.0 / 3.0, 1.0, 0.0, 0.0,
                                1.0, -1.0, 1.0, 0.0};
static const double rk38_b[] = {1.0 / 8.0, 3.0 / 8.0, 3.0 / 8.0, 1.0 / 8.0};
static const double rk38_c[] = {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};

#define TABLE(nm, al, ti, ref, s, p, pre) \
    {nm, al, ti, ref, DYN_KIND_EXPLICIT_RK, s, p, pre##_a, pre##_b, pre##_c}

static const dyn_tableau methods[] = {
    TABLE("euler", NULL, "explicit Euler, y + h f(t, y)", "Euler 1768; HNW I sec. II.1", 1, 1,
          euler),
    TABLE("heun", "modified-euler", "Heun / modified Euler: Euler predictor, trapezoidal corrector",
          "Greenwood, Advanced Dynamics, p. 341; HNW I sec. II.1", 2, 2, heun),
    TABLE("midpoint", "rk2", "explicit midpoint rule (RK2)", "Runge 1895; HNW I sec. II.1", 2, 2,
          midpoint),
    TABLE("ralston", NULL, "Ralston's 2nd-order method (minimum error bound)",
          "Ralston, Math. Comp. 16 (1962)", 2, 2, ralston),
    TABLE("rk4", NULL, "classical 4th-order Runge-Kutta", "Kutta 1901; HNW I table 1.2", 4, 4,
          rk4),
    TABLE("rk38", NULL, "Kutta's 3/8 rule, 4th order", "Kutta 1901; HNW I table 1.2", 4, 4, rk38),
};

int dyn_method_count(void) { return (int)(sizeof methods / sizeof methods[0]); }

const dyn_tableau *dyn_method_at(int i)
{
    return (i >= 0 && i < dyn_method_count()) ? &methods[i] : NULL;
}

const dyn_tableau *dyn_method_find(const char *name)
{
    if (!name)
        return NULL;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = &methods[i];
        if (strcmp(m->name, name) == 0 || (m->alias && strcmp(m->alias, name) == 0))
            return m;
    }
    return NULL;
}

char *dyn_method_names(char *buf, size_t size)
{
    size_t used = 0;
    if (size == 0)
        return buf;
    buf[0] = '\0';
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = &methods[i];
        int w = snprintf(buf + used, size - used, "%s%s%s%s%s", i ? ", " : "", m->name,
                         m->alias ? " (" : "", m->alias ? m->alias : "", m->alias ? ")" : "");
        if (w < 0 || (size_t)w >= size - used)
            break;
        used += (size_t)w;
    }
    return buf;
}
