/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady.h — dynkit continue on a mechanism's steady motions (cont_steady.c). */
#ifndef DYNKIT_CLI_CONT_STEADY_H
#define DYNKIT_CLI_CONT_STEADY_H

#include "cli.h"
#include "dynkit/continuation.h"

typedef struct cont_steady_args {
    const char *unknown; /* --unknown NAME,... or NULL */
    const char *cyclic;  /* --cyclic NAME,... or NULL */
    const char **init;   /* the --init NAME=VALUE texts (held states) */
    int n_init;
} cont_steady_args;

/* When run's model is a mechanism file (spec) with constraints or cyclic coordinates (or
 * --unknown is given): its steady motions continued with the options o into d (*used = 1).
 * Otherwise nothing is done (*used = 0). Returns CLI_OK or a CLI status after a message. */
int cont_steady_run(const char *spec, const cli_run *run, const cont_steady_args *a,
                    const dyn_cont_opts *o, dyn_diagram *d, dyn_cont_info *info, int *used);

#endif
