/* SPDX-License-Identifier: BSD-3-Clause */
/* The values of --vary NAME=A:B:N (N evenly spaced, the ends exactly A and B) or
 * NAME=V1,V2,... (listed), shared by sweep and linearize. A, B and each V are numbers or
 * formulas of the parameters (cli_parse_value); a list is cut at the commas outside
 * parentheses, so max(a,b) is one value. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/sweep.h"

/* The length of the item at p: up to the first comma outside parentheses, or the end. */
static size_t item_length(const char *p)
{
    int depth = 0;
    size_t k = 0;
    for (; p[k] && !(p[k] == ',' && depth == 0); k++)
        depth += p[k] == '(' ? 1 : p[k] == ')' ? -1 : 0;
    return k;
}

int cli_parse_values(const char *command, const char *text, const char *v, long max,
                     double **values, long *count)
{
    char buf[256];
    *values = NULL;
    *count = 0;
    if (strchr(v, ':')) {
        double a, b;
        long n;
        const char *c1 = strchr(v, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        int ok = c2 && (size_t)(c1 - v) < sizeof buf && (size_t)(c2 - c1 - 1) < sizeof buf;
        if (ok) {
            memcpy(buf, v, (size_t)(c1 - v));
            buf[c1 - v] = '\0';
            ok = cli_parse_value(buf, &a, NULL, 0) == 0;
            memcpy(buf, c1 + 1, (size_t)(c2 - c1 - 1));
            buf[c2 - c1 - 1] = '\0';
            ok = ok && cli_parse_value(buf, &b, NULL, 0) == 0 &&
                 cli_parse_count(c2 + 1, 1, &n) == 0;
        }
        if (!ok)
            return cli_usage_error(command,
                                   "--vary '%s': A:B:N needs two numbers and a count >= 1 "
                                   "(e.g. dphi=0.1:1.9:50; A and B may be formulas of the "
                                   "parameters)",
                                   text);
        if (n > max)
            return cli_usage_error(command, "--vary '%s': at most %ld values", text, max);
        *values = malloc((size_t)n * sizeof(double));
        if (!*values)
            return CLI_FAILED;
        for (long k = 0; k < n; k++)
            (*values)[k] = dyn_linspace_at(a, b, n, k);
        *count = n;
        return CLI_OK;
    }
    long n = 1;
    for (const char *p = v; p[item_length(p)]; p += item_length(p) + 1)
        n++;
    if (n > max)
        return cli_usage_error(command, "--vary '%s': at most %ld values", text, max);
    *values = malloc((size_t)n * sizeof(double));
    if (!*values)
        return CLI_FAILED;
    const char *p = v;
    for (long k = 0; k < n; k++) {
        size_t len = item_length(p);
        if (len >= sizeof buf)
            len = sizeof buf - 1;
        memcpy(buf, p, len);
        buf[len] = '\0';
        char why[400];
        if (cli_parse_value(buf, &(*values)[k], why, sizeof why)) {
            free(*values);
            *values = NULL;
            return cli_usage_error(command,
                                   "--vary '%s': '%s' is not a number or a formula of the "
                                   "parameters (%s; give NAME=A:B:N or NAME=V1,V2,...)",
                                   text, buf, why);
        }
        p += item_length(p);
        if (*p)
            p++;
    }
    *count = n;
    return CLI_OK;
}
