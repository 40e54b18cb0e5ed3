/* SPDX-License-Identifier: BSD-3-Clause */
/* The meaning of XPPAUT's operators and functions for the evaluators of expression trees
 * (constant expressions in deriv.c, animation formulas in ani_eval.c), the same as the C
 * text of emit_c.c gives them: heav(x) = x < 0 ? 0 : 1, sign(0) = 0, mod(x,y) = fmod(x,y)
 * plus y when negative (XPPAUT's pmod), flr = floor, max/min as x>y?x:y and x<y?x:y,
 * x^2 = x*x, comparisons, & and | give 1 or 0. */
#include <math.h>

#include "lang/lang_internal.h"

static double heav(double x) { return x < 0.0 ? 0.0 : 1.0; }
static double sgn(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0; }
static double pmod(double x, double y)
{
    double z = fmod(x, y);
    if (z < 0.0)
        z += y;
    return z;
}

double lang_apply_bin(int op, double a, double b)
{
    switch (op) {
    case OP_ADD: return a + b;
    case OP_SUB: return a - b;
    case OP_MUL: return a * b;
    case OP_DIV: return a / b;
    case OP_POW: return b == 2.0 ? a * a : pow(a, b);
    case OP_GT: return a > b ? 1.0 : 0.0;
    case OP_LT: return a < b ? 1.0 : 0.0;
    case OP_GE: return a >= b ? 1.0 : 0.0;
    case OP_LE: return a <= b ? 1.0 : 0.0;
    case OP_EQ: return a == b ? 1.0 : 0.0;
    case OP_NE: return a != b ? 1.0 : 0.0;
    case OP_AND: return a != 0.0 && b != 0.0 ? 1.0 : 0.0;
    case OP_OR: return a != 0.0 || b != 0.0 ? 1.0 : 0.0;
    default: return NAN;
    }
}

double lang_apply_fun(int op, double a, double b)
{
    switch (op) {
    case F_SIN: return sin(a);
    case F_COS: return cos(a);
    case F_TAN: return tan(a);
    case F_ASIN: return asin(a);
    case F_ACOS: return acos(a);
    case F_ATAN: return atan(a);
    case F_ATAN2: return atan2(a, b);
    case F_SINH: return sinh(a);
    case F_COSH: return cosh(a);
    case F_TANH: return tanh(a);
    case F_EXP: return exp(a);
    case F_LN: return log(a);
    case F_LOG10: return log10(a);
    case F_SQRT: return sqrt(a);
    case F_ABS: return fabs(a);
    case F_HEAV: return heav(a);
    case F_SIGN: return sgn(a);
    case F_MOD: return pmod(a, b);
    case F_FLR: return floor(a);
    case F_CEIL: return ceil(a);
    case F_MAX: return a > b ? a : b;
    case F_MIN: return a < b ? a : b;
    case F_ERF: return erf(a);
    case F_ERFC: return erfc(a);
    default: return NAN;
    }
}
