/* SPDX-License-Identifier: BSD-3-Clause */
/* The names of a sweep: run-table columns (parameters, then states) and reductions, parsed
 * as given ("final", "max:NAME", "event:NAME", ...) and named as columns ("max_NAME",
 * "event_NAME": letters, digits and '_', which NumPy, pandas, MATLAB and Octave keep as they
 * are; dynkit/sweep.h). */
#include <stdio.h>
#include <string.h>

#include "dynkit/sweep.h"

static const struct {
    const char *name;
    dyn_reduce_op op;
} ops[] = {{"final", DYN_REDUCE_FINAL},   {"max", DYN_REDUCE_MAX},
           {"min", DYN_REDUCE_MIN},       {"mean", DYN_REDUCE_MEAN},
           {"argmax", DYN_REDUCE_ARGMAX}, {"argmin", DYN_REDUCE_ARGMIN},
           {"event", DYN_REDUCE_EVENT},   {"count", DYN_REDUCE_COUNT}};

/* "a, b, c" of the model's names of one kind into buf (for messages). */
static void list_names(char *buf, size_t size, int n, const char *(*name)(const dyn_model *, int),
                       const dyn_model *m)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && used + 1 < size; i++) {
        int w = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", name(m, i));
        if (w < 0)
            break;
        used += (size_t)w;
    }
    if (n == 0)
        snprintf(buf, size, "none");
}

static const char *state_name(const dyn_model *m, int i) { return m->states[i].name; }
static const char *output_name(const dyn_model *m, int i) { return m->outputs[i].name; }
static const char *param_name(const dyn_model *m, int i) { return m->params[i].name; }
static const char *event_name(const dyn_model *m, int i) { return m->events[i].name; }

int dyn_sweep_var_find(const dyn_model *m, const char *name, dyn_sweep_var *var, char *err,
                       size_t errlen)
{
    int i = dyn_model_param_index(m, name);
    if (i >= 0) {
        *var = (dyn_sweep_var){DYN_SWEEP_PARAM, i};
        return 0;
    }
    i = dyn_model_state_index(m, name);
    if (i >= 0) {
        *var = (dyn_sweep_var){DYN_SWEEP_STATE, i};
        return 0;
    }
    char p[512], s[512];
    list_names(p, sizeof p, m->n_params, param_name, m);
    list_names(s, sizeof s, m->n_states, state_name, m);
    snprintf(err, errlen,
             "'%s' is neither a parameter nor a state of %s (parameters: %s; states: %s)", name,
             m->name, p, s);
    return -1;
}

const char *dyn_sweep_var_name(const dyn_model *m, const dyn_sweep_var *var)
{
    return var->kind == DYN_SWEEP_PARAM ? m->params[var->index].name
                                        : m->states[var->index].name;
}

char *dyn_reduce_name(const dyn_model *m, const dyn_reduce *r, char *buf, size_t size)
{
    const char *op = "?";
    for (size_t k = 0; k < sizeof ops / sizeof ops[0]; k++)
        if (ops[k].op == r->op)
            op = ops[k].name;
    const char *name = r->source == DYN_SOURCE_STATE    ? m->states[r->index].name
                       : r->source == DYN_SOURCE_OUTPUT ? m->outputs[r->index].name
                                                        : m->events[r->index].name;
    snprintf(buf, size, "%s_%s", op, name);
    return buf;
}

static int add(dyn_reduce *out, int max, int *count, dyn_reduce r, char *err, size_t errlen)
{
    if (*count >= max) {
        snprintf(err, errlen, "too many reductions (at most %d columns)", max);
        return -1;
    }
    out[(*count)++] = r;
    return 0;
}

int dyn_reduce_parse(const dyn_model *m, const char *list, dyn_reduce *out, int max,
                     int *count, char *err, size_t errlen)
{
    *count = 0;
    const char *p = list;
    if (!list || !*list) {
        snprintf(err, errlen, "no reduction given (e.g. final, max:NAME, event:NAME)");
        return -1;
    }
    for (;;) {
        size_t len = strcspn(p, ",");
        char item[128];
        if (len == 0 || len >= sizeof item) {
            snprintf(err, errlen, "an empty or too long item in the reductions '%s'", list);
            return -1;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        char *colon = strchr(item, ':');
        const char *name = NULL;
        if (colon) {
            *colon = '\0';
            name = colon + 1;
        }
        int op = -1;
        for (size_t k = 0; k < sizeof ops / sizeof ops[0]; k++)
            if (strcmp(ops[k].name, item) == 0)
                op = (int)ops[k].op;
        if (op < 0) {
            snprintf(err, errlen,
                     "unknown reduction '%s' (accepted: final, final:NAME, max:NAME, min:NAME, "
                     "mean:NAME, argmax:NAME, argmin:NAME, event:NAME, count:NAME)",
                     item);
            return -1;
        }
        if (!name && op == DYN_REDUCE_FINAL) {
            for (int i = 0; i < m->n_states; i++)
                if (add(out, max, count, (dyn_reduce){DYN_REDUCE_FINAL, DYN_SOURCE_STATE, i},
                        err, errlen))
                    return -1;
        } else if (!name || !*name) {
            snprintf(err, errlen, "reduction '%s' needs a name: %s:NAME", item, item);
            return -1;
        } else if (op == DYN_REDUCE_EVENT || op == DYN_REDUCE_COUNT) {
            int e = -1;
            for (int i = 0; i < m->n_events; i++)
                if (strcmp(m->events[i].name, name) == 0)
                    e = i;
            if (e < 0) {
                char ev[512];
                list_names(ev, sizeof ev, m->n_events, event_name, m);
                snprintf(err, errlen, "%s:%s: %s has no event '%s' (events: %s)", item, name,
                         m->name, name, ev);
                return -1;
            }
            if (add(out, max, count, (dyn_reduce){(dyn_reduce_op)op, DYN_SOURCE_EVENT, e}, err,
                    errlen))
                return -1;
        } else {
            int i = dyn_model_state_index(m, name);
            dyn_reduce_source src = DYN_SOURCE_STATE;
            if (i < 0) {
                i = dyn_model_output_index(m, name);
                src = DYN_SOURCE_OUTPUT;
            }
            if (i < 0) {
                char s[512], o[512];
                list_names(s, sizeof s, m->n_states, state_name, m);
                list_names(o, sizeof o, m->n_outputs, output_name, m);
                snprintf(err, errlen,
                         "%s:%s: '%s' is neither a state nor an output of %s (states: %s; "
                         "outputs: %s)",
                         item, name, name, m->name, s, o);
                return -1;
            }
            if (add(out, max, count, (dyn_reduce){(dyn_reduce_op)op, src, i}, err, errlen))
                return -1;
        }
        p += len;
        if (!*p)
            break;
        p++;
    }
    return 0;
}
