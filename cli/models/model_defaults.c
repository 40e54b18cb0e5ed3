/* SPDX-License-Identifier: BSD-3-Clause */
/* The method and tolerances of a model's default run, and where each comes from: the
 * model's own (a built-in model's, dyn_model.method or .rtol in a C model, @ meth or
 * @ rtol in a model file), or the one rule for models that name none (DYN_MODEL_METHOD,
 * DYN_MODEL_RTOL, DYN_MODEL_ATOL of model.h). For run --verbose and info. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

const char *cli_model_method(const dyn_model *m)
{
    return m->method ? m->method : DYN_MODEL_METHOD;
}

/* The library's rule (dyn_run_default_rtol): the model's own, else dynkit's default, or
 * rkmil's 1e-3 and 1e-6 for a model with noise. */
double cli_model_rtol(const dyn_model *m) { return dyn_run_default_rtol(m); }

double cli_model_atol(const dyn_model *m) { return dyn_run_default_atol(m); }

static int has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcmp(path + n - e, ext) == 0;
}

const char *cli_model_default_source(const dyn_model *m, cli_default_field field, char *buf,
                                     size_t size)
{
    static const char *const c_names[] = {"method", "rtol", "atol"};
    static const char *const ode_names[] = {"meth", "rtol", "atol"};
    const int own = field == CLI_DEFAULT_METHOD ? m->method != NULL
                    : field == CLI_DEFAULT_RTOL ? m->rtol > 0.0
                                                : m->atol > 0.0;
    if (!own && m->n_noise > 0)
        return "dynkit's default for models with noise that name none";
    if (!own)
        return "dynkit's default for models that name none";
    if (field == CLI_DEFAULT_METHOD && m->n_noise > 0 && m->source &&
        (strcmp(m->method, "rkmil") == 0 || strcmp(m->method, "euler") == 0))
        return "the method for its noise, or its @ meth=euler";
    if (field == CLI_DEFAULT_METHOD && m->volterra)
        return "the only method for its integrals";
    const char *path = cli_model_path(m);
    if (!path)
        return "the model's";
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (has_ext(base, ".c"))
        snprintf(buf, size, "dyn_model.%s in %s", c_names[field], base);
    else if (has_ext(base, ".ode"))
        snprintf(buf, size, "@ %s in %s", ode_names[field], base);
    else
        snprintf(buf, size, "set in %s", base);
    return buf;
}

const char *cli_time_unit(const dyn_model *m)
{
    return m->time_unit && *m->time_unit ? m->time_unit : "s";
}
