/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_settings.h — the settings of dynkit continue: XPPAUT's AUTO options read from a
 * model file's @ lines (ntst, ncol, nmax, npr, ds, dsmin, dsmax, parmin, parmax, autoxmin,
 * autoxmax, autoymin, autoymax, autovar), then --opt NAME=VALUE on the command line, over the
 * defaults of dynkit/continuation.h (cont_settings.c). */
#ifndef DYNKIT_CLI_CONT_SETTINGS_H
#define DYNKIT_CLI_CONT_SETTINGS_H

#include "dynkit/continuation.h"

typedef struct cont_settings {
    dyn_cont_opts opts;
    double window[4];     /* autoxmin, autoxmax, autoymin, autoymax (NAN: not given) */
    char from[16][320];   /* where each setting came from ("FILE:LINE:COL", "--opt"; "":
                           * not given), by cont_settings.c's order of the names */
    char autovar[64];     /* AUTOVAR, the state on the diagram's y axis ("": not given) */
    char autovar_from[320];
} cont_settings;

/* Apply NAME=VALUE (text) to s; where: "FILE:LINE:COL" or "--opt" for messages. Returns
 * 0, or -1 with a message in err (unknown name, bad number). */
int cont_settings_apply(cont_settings *s, const char *name, const char *value, const char *where,
                        char *err, size_t errlen);

/* The AUTO settings of the model file text (len bytes) applied to s, as the model file's
 * parser reads its @ lines (dyn_ode_auto_options, dynkit/lang.h); path names the file in
 * messages. Returns 0, or -1 with "FILE:LINE:COL: ..." in err. */
int cont_settings_read_file(cont_settings *s, const char *text, size_t len, const char *path,
                            char *err, size_t errlen);

/* The window [parmin, parmax] made to contain the start p0 of the parameter named par: a
 * bound that neither the file's @ lines nor --opt gave (a default) and that excludes p0 is
 * moved to p0 + (p0 - parmin), or p0 - (parmax - p0) (the start the window's middle; at
 * least the default window's width away from p0), and note (when not NULL) says so, else
 * note is "". Returns 0, or -1 with a message in err when a bound that was given excludes
 * p0. */
int cont_settings_fit_start(cont_settings *s, double p0, const char *par, char *note,
                            size_t notelen, char *err, size_t errlen);

#endif
