/* SPDX-License-Identifier: BSD-3-Clause */
/* The registry of built-in models and the generic accessors of dyn_model (model.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/models.h"
#include "dynkit/cart.h"
#include "dynkit/plane.h"
#include "dynkit/problems.h"

static const dyn_model *const builtin[] = {
    &dyn_model_pendulum,
    &dyn_model_vanderpol,
    &dyn_model_plane,
    &dyn_model_plane_quat,
    &dyn_model_cart,
    /* verification problems (problems.h) */
    &dyn_model_arenstorf,
    &dyn_model_robertson,
    &dyn_model_hires,
};

int dyn_model_count(void) { return (int)(sizeof builtin / sizeof builtin[0]); }

const dyn_model *dyn_model_at(int i)
{
    return (i >= 0 && i < dyn_model_count()) ? builtin[i] : NULL;
}

const dyn_model *dyn_model_find(const char *name)
{
    for (int i = 0; name && i < dyn_model_count(); i++)
        if (strcmp(builtin[i]->name, name) == 0)
            return builtin[i];
    return NULL;
}

char *dyn_model_names(char *buf, size_t size)
{
    size_t used = 0;
    if (size == 0)
        return buf;
    buf[0] = '\0';
    for (int i = 0; i < dyn_model_count(); i++) {
        int w = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", builtin[i]->name);
        if (w < 0 || (size_t)w >= size - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

int dyn_model_default_params(const dyn_model *m, void *par, char *err, size_t errlen)
{
    memset(par, 0, m->par_size);
    for (int i = 0; i < m->n_params; i++)
        dyn_model_set_param(m, par, i, m->params[i].value);
    return m->prepare ? m->prepare(par, err, errlen) : 0;
}

void dyn_model_initial_state(const dyn_model *m, const void *par, double *y0)
{
    if (m->initial_state)
        m->initial_state(par, y0);
    else
        memcpy(y0, m->y0, (size_t)m->n_states * sizeof *y0);
}

static int var_index(const dyn_var *vars, int count, const char *name)
{
    for (int i = 0; name && i < count; i++)
        if (strcmp(vars[i].name, name) == 0)
            return i;
    return -1;
}

int dyn_model_state_index(const dyn_model *m, const char *name)
{
    return var_index(m->states, m->n_states, name);
}

int dyn_model_output_index(const dyn_model *m, const char *name)
{
    return var_index(m->outputs, m->n_outputs, name);
}

int dyn_model_param_index(const dyn_model *m, const char *name)
{
    for (int i = 0; name && i < m->n_params; i++)
        if (strcmp(m->params[i].name, name) == 0)
            return i;
    return -1;
}

double dyn_model_get_param(const dyn_model *m, const void *par, int i)
{
    double v;
    memcpy(&v, (const char *)par + m->params[i].offset, sizeof v);
    return v;
}

void dyn_model_set_param(const dyn_model *m, void *par, int i, double value)
{
    memcpy((char *)par + m->params[i].offset, &value, sizeof value);
}

int dyn_check_positive(const char *name, double value, char *err, size_t errlen)
{
    if (isfinite(value) && value > 0.0)
        return 0;
    if (err && errlen)
        snprintf(err, errlen, "parameter %s must be a finite number > 0 (got %g)", name, value);
    return 1;
}
