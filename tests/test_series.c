/* SPDX-License-Identifier: BSD-3-Clause */
/* The time series behind the report (dyn_homework_series) are the runs of the answers:
 * each answer of dyn_homework_compute is a sample of a table, bit for bit (the last angle of
 * the pendulum's reference run, the final states of van der Pol and of the plane, the
 * distance and principal angle at the end, the cart's largest constraint force, 4b's final
 * forces); the van der Pol errors against the step show each method's order; the pendulum's
 * energy is conserved by RK4 and grows under Euler (at every step of the first swing); every column
 * has a name and a unit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/report.h"
#include "test_util.h"

static dyn_homework hw;
static dyn_hw_series series;

static int setup(void **state)
{
    (void)state;
    char err[256];
    if (dyn_homework_compute(&hw, err, sizeof err) ||
        dyn_homework_series(&hw, &series, err, sizeof err)) {
        fprintf(stderr, "setup: %s\n", err);
        return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    dyn_hw_series_free(&series);
    return 0;
}

static const dyn_hw_table *table(const char *id)
{
    const dyn_hw_table *t = dyn_hw_series_find(&series, id);
    CHECK(t != NULL && t->rows > 0 && t->data != NULL, "no table %s", id);
    return t;
}

static double cell(const dyn_hw_table *t, long row, const char *column)
{
    int c = dyn_hw_table_column(t, column);
    CHECK(c >= 0, "table %s has no column %s", t->id, column);
    if (row < 0)
        row += t->rows;
    return t->data[row * t->cols + c];
}

static void test_every_column_named_with_unit(void **state)
{
    (void)state;
    CHECK(series.count >= 13, "%d tables", series.count);
    for (int i = 0; i < series.count; i++) {
        const dyn_hw_table *t = &series.table[i];
        CHECK(t->id && t->title && t->cols >= 2 && t->rows >= 4, "table %d incomplete", i);
        for (int c = 0; c < t->cols; c++)
            CHECK(t->names[c] && t->units[c] && t->names[c][0] && t->units[c][0],
                  "%s: column %d has no name or unit", t->id, c);
        for (long k = 0; k < t->rows * t->cols; k++)
            CHECK(isfinite(t->data[k]), "%s: value %ld not finite", t->id, k);
    }
    CHECK(dyn_hw_series_find(&series, "nope") == NULL, "found a table that does not exist");
}

static void test_pendulum_answers_are_samples(void **state)
{
    (void)state;
    const dyn_hw_table *ref = table("pendulum.step"), *eul = table("pendulum.euler");
    CHECK(same_bits(cell(ref, -1, "t"), hw.pendulum.te), "reference run ends at %.17g",
          cell(ref, -1, "t"));
    CHECK(same_bits(cell(ref, -1, "phi"), hw.pendulum.phi_nonlinear_rad),
          "reference run: %.17g, answer %.17g", cell(ref, -1, "phi"),
          hw.pendulum.phi_nonlinear_rad);
    CHECK(same_bits(cell(ref, -1, "phi_small_angle"), hw.pendulum.phi_small_angle_rad),
          "small angle at te");
    CHECK(same_bits(cell(ref, -1, "small_angle_error"), hw.pendulum.error_small_angle),
          "small-angle error at te");
    CHECK(same_bits(cell(eul, 1, "t"), hw.pendulum.te) &&
              same_bits(cell(eul, 1, "phi"), hw.pendulum.phi_euler_rad),
          "the first Euler step is 1e's answer");
    /* energy: RK4 keeps it, Euler's grows with every step */
    const dyn_hw_table *nl = table("pendulum.nonlinear");
    const double e0 = cell(nl, 0, "energy");
    for (long k = 0; k < nl->rows; k++)
        CHECK(fabs(cell(nl, k, "energy") - e0) < 1e-6 * e0, "RK4 energy drifts at row %ld", k);
    for (long k = 1; k < 10; k++)
        CHECK(cell(eul, k, "energy") > cell(eul, k - 1, "energy"), "Euler energy at row %ld", k);
    CHECK(cell(eul, -1, "energy") > 1.3 * cell(eul, 0, "energy"), "Euler energy %g from %g",
          cell(eul, -1, "energy"), cell(eul, 0, "energy"));
    /* the height never exceeds 1a's maximum along the accurate run */
    for (long k = 0; k < nl->rows; k++)
        CHECK(cell(nl, k, "height") <= hw.pendulum.max_height_m * (1 + 1e-9), "height row %ld", k);
}

static void test_vanderpol_finals_and_orders(void **state)
{
    (void)state;
    static const char *const ids[4] = {"vanderpol.euler", "vanderpol.heun", "vanderpol.midpoint",
                                       "vanderpol.rk4"};
    const double *finals[4] = {hw.vanderpol.euler, hw.vanderpol.modified_euler,
                               hw.vanderpol.midpoint, hw.vanderpol.rk4};
    for (int i = 0; i < 4; i++) {
        const dyn_hw_table *t = table(ids[i]);
        CHECK(t->rows == 1501, "%s: %ld rows", ids[i], t->rows);
        CHECK(same_bits(cell(t, -1, "y1"), finals[i][0]) &&
                  same_bits(cell(t, -1, "y2"), finals[i][1]),
              "%s: final state differs from the answer", ids[i]);
    }
    const dyn_hw_table *st = table("vanderpol.steps");
    static const char *const methods[4] = {"euler", "heun", "midpoint", "rk4"};
    static const double order[4] = {1, 2, 2, 4};
    long at = -1;
    for (long k = 0; k < st->rows; k++)
        if (cell(st, k, "step") == hw.vanderpol.step)
            at = k;
    CHECK(at >= 0, "the homework's step is not in the study");
    for (int i = 0; i < 4; i++) {
        CHECK(same_bits(cell(st, at, methods[i]), hw.vanderpol.error[i]),
              "%s: error at the homework's step %.17g, answer %.17g", methods[i],
              cell(st, at, methods[i]), hw.vanderpol.error[i]);
        /* observed order between the homework's step and the next smaller one */
        double p = log(cell(st, at, methods[i]) / cell(st, at + 1, methods[i])) /
                   log(cell(st, at, "step") / cell(st, at + 1, "step"));
        CHECK(fabs(p - order[i]) < 0.15, "%s: observed order %.3f, expected %g", methods[i], p,
              order[i]);
    }
}

static void test_plane_answers_are_samples(void **state)
{
    (void)state;
    const dyn_hw_table *e = table("plane.euler"), *r = table("plane.rk4");
    const dyn_hw_table *c = table("plane.compare");
    CHECK(e->rows == 501 && r->rows == 501 && c->rows == 501, "rows %ld %ld %ld", e->rows, r->rows,
          c->rows);
    for (int i = 0; i < 12; i++) {
        CHECK(same_bits(e->data[(e->rows - 1) * e->cols + 1 + i], hw.plane.final_euler[i]),
              "Euler final state %d", i);
        CHECK(same_bits(r->data[(r->rows - 1) * r->cols + 1 + i], hw.plane.final_rk4[i]),
              "RK4 final state %d", i);
    }
    CHECK(same_bits(cell(c, -1, "distance"), hw.plane.distance_m), "distance %.17g vs %.17g",
          cell(c, -1, "distance"), hw.plane.distance_m);
    CHECK(same_bits(cell(c, -1, "principal_angle"), hw.plane.principal_angle_rad),
          "principal angle %.17g vs %.17g", cell(c, -1, "principal_angle"),
          hw.plane.principal_angle_rad);
    CHECK(cell(c, 0, "distance") == 0.0 && cell(c, 0, "principal_angle") < 1e-12,
          "the runs do not start together");
    double min_margin = INFINITY;
    for (long k = 0; k < e->rows; k++)
        min_margin = fmin(min_margin, cell(e, k, "theta_margin"));
    CHECK(same_bits(min_margin, hw.plane.euler_min_theta_margin_rad), "closest approach %.17g",
          min_margin);
}

static void test_cart_answers_are_samples(void **state)
{
    (void)state;
    const dyn_hw_table *f = table("cart.forward"), *p = table("cart.prescribed");
    CHECK(f->rows == hw.cart.N && p->rows == hw.cart.N, "rows %ld %ld", f->rows, p->rows);
    CHECK(same_bits(cell(f, -1, "sX"), hw.cart.forward_sX_m), "sX(te) %.17g vs %.17g",
          cell(f, -1, "sX"), hw.cart.forward_sX_m);
    double worst = 0.0, t_worst = 0.0;
    for (long k = 0; k < f->rows; k++)
        if (fabs(cell(f, k, "lambda")) > worst) {
            worst = fabs(cell(f, k, "lambda"));
            t_worst = cell(f, k, "t");
        }
    CHECK(same_bits(worst, hw.cart.max_constraint_force_N) &&
              same_bits(t_worst, hw.cart.t_max_constraint_force),
          "max |lambda| %.17g at %g vs %.17g", worst, t_worst, hw.cart.max_constraint_force_N);
    CHECK(same_bits(cell(p, -1, "Fx"), hw.cart.final_Fx_N) &&
              same_bits(cell(p, -1, "Fy"), hw.cart.final_Fy_N),
          "4b's final forces");
    CHECK(same_bits(cell(p, 0, "dsY"), hw.cart.initial_dsY_mps), "4a's initial dsY");
    CHECK(fabs(cell(p, -1, "sX") - hw.cart.exact_sX_m) < 1e-12, "prescribed sX(te)");
    /* the forward run reads the table: the same forces at the samples */
    for (long k = 0; k < f->rows; k++)
        CHECK(cell(f, k, "Fx") == cell(p, k, "Fx") && cell(f, k, "Fy") == cell(p, k, "Fy"),
              "forces differ at row %ld", k);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_column_named_with_unit),
        cmocka_unit_test(test_pendulum_answers_are_samples),
        cmocka_unit_test(test_vanderpol_finals_and_orders),
        cmocka_unit_test(test_plane_answers_are_samples),
        cmocka_unit_test(test_cart_answers_are_samples),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
