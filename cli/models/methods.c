/* SPDX-License-Identifier: BSD-3-Clause */
/* The methods the tool offers: the library's registry (dyn_method_find) and, when dynkit is
 * built with SUNDIALS, "cvode", the CVODE backend (dynkit/cvode.h), which is a library of
 * its own; with the methods for noise and Volterra integrals, the descriptors of dyn_run
 * (dynkit/run.h), which sends runs with them to their solver family.
 * Names are matched without regard to case, and MATLAB's solver names are understood: ode45
 * and ode23 are the library's aliases of dp45 and bs23, ode15s and ode23s select the stiff
 * method rodas4; ode113 and the other MATLAB solvers without a counterpart are refused with
 * a pointer to the method to use instead. */
#include <ctype.h>
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"

/* MATLAB's solvers: the method each selects, or NULL with the advice for the message. */
static const struct {
    const char *matlab, *method, *advice;
} matlab_solvers[] = {
    {"ode15s", "rodas4", NULL},
    {"ode23s", "rodas4", NULL},
    {"ode113", NULL,
     "MATLAB's ode113 (variable-order Adams-Bashforth-Moulton) is not available; for smooth "
     "non-stiff problems at tight tolerances use dop853 (order 8, adaptive)"},
    {"ode23t", NULL,
     "MATLAB's ode23t (trapezoidal rule) is not available; for stiff problems use rodas4 (or "
     "ode15s/ode23s, which select it)"},
    {"ode23tb", NULL,
     "MATLAB's ode23tb (TR-BDF2) is not available; for stiff problems use rodas4 (or "
     "ode15s/ode23s, which select it)"},
    {"ode15i", NULL,
     "MATLAB's ode15i solves implicit equations f(t, y, y') = 0, which dynkit does not take; "
     "write the model as y' = f(t, y) and use rodas4"},
};

/* name in lower case into buf (names longer than the buffer are cut, and then unknown). */
static const char *lower(const char *name, char *buf, size_t size)
{
    size_t i = 0;
    for (; name && name[i] && i + 1 < size; i++)
        buf[i] = (char)tolower((unsigned char)name[i]);
    buf[i] = '\0';
    return buf;
}

/* The descriptors of the solver families that are not tables are the library's
 * (dyn_run_method_find); cvode is offered only when the backend is built. */
int cli_method_is_volterra(const dyn_tableau *m) { return m == dyn_run_method_volterra(); }

const dyn_tableau *cli_rkmil_method(void) { return dyn_run_method_rkmil(); }

int cli_method_is_rkmil(const dyn_tableau *m) { return m == dyn_run_method_rkmil(); }

const dyn_tableau *cli_sriw1_method(void) { return dyn_run_method_sriw1(); }

int cli_method_is_sde_adaptive(const dyn_tableau *m)
{
    return m == dyn_run_method_rkmil() || m == dyn_run_method_sriw1();
}

int cli_sde_method(const dyn_tableau *m) { return dyn_run_sde_method(m); }

const dyn_tableau *cli_cvode_method(void)
{
#ifdef DYNKIT_HAVE_CVODE
    return dyn_run_method_cvode();
#else
    return NULL;
#endif
}

int cli_method_is_cvode(const dyn_tableau *m) { return m && m == cli_cvode_method(); }

const dyn_tableau *cli_method_find(const char *name)
{
    char buf[64];
    if (!name || strlen(name) >= sizeof buf)
        return NULL;
    name = lower(name, buf, sizeof buf);
    for (size_t i = 0; i < sizeof matlab_solvers / sizeof matlab_solvers[0]; i++)
        if (strcmp(name, matlab_solvers[i].matlab) == 0)
            return matlab_solvers[i].method ? dyn_method_find(matlab_solvers[i].method) : NULL;
    const dyn_tableau *m = dyn_run_method_find(name);
    return m == dyn_run_method_cvode() ? cli_cvode_method() : m;
}

char *cli_method_names(char *buf, size_t size)
{
    dyn_method_names(buf, size);
    size_t used = strlen(buf);
    if (cli_cvode_method() && used < size)
        used += (size_t)snprintf(buf + used, size - used, ", cvode");
    if (used < size)
        snprintf(buf + used, size - used, ", rkmil, sriw1, volterra");
    return buf;
}

int cli_method_error(const char *command, const char *what, const char *name)
{
    char names[640], buf[64];
    const char *low = lower(name, buf, sizeof buf);
    for (size_t i = 0; i < sizeof matlab_solvers / sizeof matlab_solvers[0]; i++)
        if (strcmp(low, matlab_solvers[i].matlab) == 0 && matlab_solvers[i].advice)
            return cli_usage_error(command, "%s %s: %s", what, name, matlab_solvers[i].advice);
    /* the nearest name or alias, as a likely typo */
    const char *known[80];
    int n = 0;
    for (int i = 0; i < dyn_method_count() && n + 6 < 80; i++) {
        const dyn_tableau *m = dyn_method_at(i);
        known[n++] = m->name;
        if (m->alias)
            known[n++] = m->alias;
    }
    if (cli_cvode_method())
        known[n++] = "cvode";
    known[n++] = "rkmil";
    known[n++] = "volterra";
    known[n++] = "sriw1";
    const char *near = name ? dyn_lang_nearest(name, known, n) : NULL;
    if (near)
        return cli_usage_error(command, "%s: unknown method '%s' (did you mean '%s'? accepted: %s)",
                               what, name, near, cli_method_names(names, sizeof names));
    if (strcmp(low, "cvode") == 0 && !cli_cvode_method())
        return cli_usage_error(command,
                               "%s cvode: dynkit was built without SUNDIALS, so the CVODE "
                               "backend is not available (install libsundials-dev and "
                               "rebuild; rodas4 is the built-in stiff method)",
                               what);
    return cli_usage_error(command, "%s: unknown method '%s' (accepted: %s)", what, name,
                           cli_method_names(names, sizeof names));
}
