/* The methods the tool offers: the library's registry (dyn_method_find) and, when dynkit is
 * built with SUNDIALS, "cvode", the CVODE backend (dynkit/cvode.h), which is a library of
 * its own and not in the core registry. Its descriptor only names it for the tool (listing,
 * labels, adaptive/stiff tests); cli_run_solve sends runs with it to dyn_cvode_solve. */
#include <string.h>

#include "cli.h"

#ifdef DYNKIT_HAVE_CVODE
/* A descriptor, never a table for the library's drivers: kind stiff, so that
 * dyn_method_is_adaptive and dyn_method_is_stiff say yes; no coefficients. */
static const dyn_tableau cvode_method = {
    .name = "cvode",
    .title = "SUNDIALS CVODE: BDF, variable order 1-5 and step, Newton iteration with a dense "
             "LU (optional backend)",
    .reference = "Hindmarsh et al., ACM TOMS 31 (2005) 363-396; CVODE user guide",
    .kind = DYN_KIND_ROSENBROCK,
    .order = 5,
};
#endif

const dyn_tableau *cli_cvode_method(void)
{
#ifdef DYNKIT_HAVE_CVODE
    return &cvode_method;
#else
    return NULL;
#endif
}

int cli_method_is_cvode(const dyn_tableau *m) { return m && m == cli_cvode_method(); }

const dyn_tableau *cli_method_find(const char *name)
{
    const dyn_tableau *m = dyn_method_find(name);
    if (!m && name && strcmp(name, "cvode") == 0)
        m = cli_cvode_method();
    return m;
}

char *cli_method_names(char *buf, size_t size)
{
    dyn_method_names(buf, size);
    size_t used = strlen(buf);
    if (cli_cvode_method() && used < size)
        snprintf(buf + used, size - used, ", cvode");
    return buf;
}

int cli_method_error(const char *command, const char *what, const char *name)
{
    char names[640];
    if (name && strcmp(name, "cvode") == 0 && !cli_cvode_method())
        return cli_usage_error(command,
                               "%s cvode: dynkit was built without SUNDIALS, so the CVODE "
                               "backend is not available (install libsundials-dev and "
                               "rebuild; rodas4 is the built-in stiff method)",
                               what);
    return cli_usage_error(command, "%s: unknown method '%s' (accepted: %s)", what, name,
                           cli_method_names(names, sizeof names));
}
