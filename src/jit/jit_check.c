/* SPDX-License-Identifier: BSD-3-Clause */
/* The check of the dyn_model a compiled model returns (dynkit_model()): names, counts,
 * arrays, parameter offsets inside par_size, a declared band or pattern, default run;
 * shared by both backends and dyn_jit_check_model (model.h's contract). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dynkit/volterra.h"
#include "jit_internal.h"

static int check_vars(const dyn_var *v, int n, const char *what, const char *where, char *err,
                      size_t errlen)
{
    if (n < 0)
        return jit_fail(err, errlen, "%s: dynkit_model() returned a model with n_%s = %d", where,
                        what, n);
    if (n > 0 && !v)
        return jit_fail(err, errlen,
                        "%s: dynkit_model() returned a model with n_%s = %d but no %s array", where,
                        what, n, what);
    for (int i = 0; i < n; i++)
        if (!v[i].name || !v[i].name[0])
            return jit_fail(err, errlen, "%s: %s %d of the model has no name", where, what, i);
    return 0;
}

int jit_check_model(const dyn_model *m, const char *where, char *err, size_t errlen)
{
    if (!m)
        return jit_fail(err, errlen, "%s: dynkit_model() returned NULL instead of a model", where);
    if (!m->name || !m->name[0])
        return jit_fail(err, errlen, "%s: the model has no name (dyn_model.name)", where);
    if (m->n_states <= 0)
        return jit_fail(err, errlen,
                        "%s: the model '%s' has n_states = %d (it needs at least one state)", where,
                        m->name, m->n_states);
    if (!m->rhs)
        return jit_fail(err, errlen, "%s: the model '%s' has no right-hand side (dyn_model.rhs)",
                        where, m->name);
    if (!m->y0 && !m->initial_state)
        return jit_fail(err, errlen,
                        "%s: the model '%s' has no initial state (dyn_model.y0 or initial_state)",
                        where, m->name);
    if (check_vars(m->states, m->n_states, "states", where, err, errlen) ||
        check_vars(m->outputs, m->n_outputs, "outputs", where, err, errlen) ||
        check_vars(m->inputs, m->n_inputs, "inputs", where, err, errlen))
        return 1;
    if (m->n_outputs > 0 && !m->compute_outputs)
        return jit_fail(err, errlen, "%s: the model '%s' has %d outputs but no compute_outputs",
                        where, m->name, m->n_outputs);
    if (m->n_inputs > 0 && !m->set_input)
        return jit_fail(err, errlen, "%s: the model '%s' has %d inputs but no set_input", where,
                        m->name, m->n_inputs);
    if (m->n_params < 0 || (m->n_params > 0 && !m->params))
        return jit_fail(err, errlen, "%s: the model '%s' has n_params = %d but no params array",
                        where, m->name, m->n_params);
    for (int i = 0; i < m->n_params; i++) {
        const dyn_param *p = &m->params[i];
        if (!p->name || !p->name[0])
            return jit_fail(err, errlen, "%s: parameter %d of the model '%s' has no name", where, i,
                            m->name);
        if (m->par_size < sizeof(double) || p->offset > m->par_size - sizeof(double) ||
            p->offset % _Alignof(double) != 0)
            return jit_fail(err, errlen,
                            "%s: parameter '%s' of the model '%s' lies outside its parameter "
                            "struct (offset %zu, par_size %zu): set par_size = sizeof(the "
                            "struct) and offset = offsetof(the struct, member)",
                            where, p->name, m->name, p->offset, m->par_size);
    }
    if (m->n_events < 0 || (m->n_events > 0 && !m->events))
        return jit_fail(err, errlen, "%s: the model '%s' has n_events = %d but no events array",
                        where, m->name, m->n_events);
    for (int i = 0; i < m->n_events; i++)
        if (!m->events[i].name || !m->events[i].name[0] || !m->events[i].g)
            return jit_fail(err, errlen,
                            "%s: event %d of the model '%s' has no name or no function g", where, i,
                            m->name);
    if (m->jac_banded && (m->jac_lower < 0 || m->jac_upper < 0 || m->jac_lower >= m->n_states ||
                          m->jac_upper >= m->n_states))
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares a band of its Jacobian with jac_lower = %d, "
                        "jac_upper = %d (accepted: 0 to n_states - 1 = %d)",
                        where, m->name, m->jac_lower, m->jac_upper, m->n_states - 1);
    char why[160];
    if (m->jac_pattern.nnz > 0 &&
        dyn_sparse_pattern_check(&m->jac_pattern, m->n_states, why, sizeof why))
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares a pattern of its Jacobian (jac_pattern) "
                        "that is not accepted: %s",
                        where, m->name, why);
    if (m->n_noise < 0 || (m->n_noise > 0 && !m->noise_kinds) ||
        (m->n_noise > 0 && (m->noise_offset % sizeof(double) != 0 ||
                            m->noise_offset > m->par_size ||
                            (m->par_size - m->noise_offset) / sizeof(double) <
                                (size_t)m->n_noise)) ||
        m->noise_class < DYN_NOISE_GENERAL || m->noise_class > DYN_NOISE_COMMUTATIVE)
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares %d noise slots that do not fit its parameter "
                        "struct (noise_offset %zu, par_size %zu, noise_kinds %s, noise_class %d)",
                        where, m->name, m->n_noise, m->noise_offset, m->par_size,
                        m->noise_kinds ? "given" : "NULL", m->noise_class);
    for (int i = 0; i < m->n_noise; i++)
        if (m->noise_kinds[i] < DYN_NOISE_WIENER || m->noise_kinds[i] > DYN_NOISE_UNIFORM)
            return jit_fail(err, errlen, "%s: noise slot %d of the model '%s' has kind %d "
                            "(accepted: 0 wiener, 1 normal, 2 uniform)", where, i, m->name,
                            m->noise_kinds[i]);
    if (m->jump && m->n_noise < 1)
        return jit_fail(err, errlen, "%s: the model '%s' has jumps (dyn_model.jump) but no noise "
                        "slots for their random numbers (n_noise = 0): only the methods for "
                        "noise take jumps", where, m->name);
    const int sde_method = m->method && m->n_noise > 0 && strcmp(m->method, "rkmil") == 0;
    const int volt_method = m->method && m->volterra && strcmp(m->method, "volterra") == 0;
    if (m->volterra &&
        (m->volterra->n_int < 0 || !m->volterra->is_int || !m->volterra->integrand ||
         m->volterra->ints_offset + ((size_t)m->volterra->n_int + 1) * sizeof(double) >
             m->par_size))
        return jit_fail(err, errlen,
                        "%s: the model '%s' declares Volterra integrals that do not fit its "
                        "parameter struct (ints_offset %zu, n_int %d, par_size %zu)",
                        where, m->name, m->volterra->ints_offset, m->volterra->n_int,
                        m->par_size);
    if (m->method && !sde_method && !volt_method && !dyn_method_find(m->method))
        return jit_fail(err, errlen,
                        "%s: the model '%s' names an unknown default method (dyn_model.method = "
                        "\"%s\"; e.g. \"dp45\" or \"rk4\", or NULL for " DYN_MODEL_METHOD ")",
                        where, m->name, m->method);
    if (!isfinite(m->t0) || !isfinite(m->t1) || !(m->t1 > m->t0) || !isfinite(m->step) ||
        m->step < 0 || (m->step == 0 && m->samples != DYN_SAMPLES_STEPS))
        return jit_fail(err, errlen,
                        "%s: the model '%s' has a bad default run (t0 = %g, t1 = %g, step = %g): "
                        "set dyn_model.t0 < t1 and step > 0 (the sample interval of adaptive "
                        "methods)",
                        where, m->name, m->t0, m->t1, m->step);
    return 0;
}

