/* SPDX-License-Identifier: BSD-3-Clause */
/* Values on the command line that are formulas of the model's parameters (--init, --set,
 * --vary's bounds): a number as cli_parse_number reads it (decimal, multiples of pi, 45deg),
 * else a formula as a model file's `init` line takes it (dyn_lang_formula_value), of the
 * parameters' values that the command has set so far. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"

static const dyn_model *formula_model;
static const void *formula_par;

void cli_formula_params(const dyn_model *m, const void *par)
{
    formula_model = m;
    formula_par = par;
}

int cli_parse_value(const char *text, double *out, char *why, size_t size)
{
    if (why && size)
        why[0] = '\0';
    if (cli_parse_number(text, out) == 0)
        return 0;
    const dyn_model *m = formula_model;
    const int n = m && formula_par ? m->n_params : 0;
    const char **names = malloc(((size_t)n + 1) * sizeof *names);
    double *values = malloc(((size_t)n + 1) * sizeof *values);
    int rc = -1;
    if (names && values) {
        for (int i = 0; i < n; i++) {
            names[i] = m->params[i].name;
            values[i] = dyn_model_get_param(m, formula_par, i);
        }
        dyn_lang_diag d;
        rc = dyn_lang_formula_value(text, names, values, n, out, &d) == 0 ? 0 : -1;
        if (rc && why && size && d.col > 0)
            snprintf(why, size, "%s (at character %d)", d.message, d.col);
        else if (rc && why && size)
            snprintf(why, size, "%s", d.message);
    } else if (why && size) {
        snprintf(why, size, "out of memory");
    }
    free(names);
    free(values);
    return rc;
}
