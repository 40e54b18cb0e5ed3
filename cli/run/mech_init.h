/* SPDX-License-Identifier: BSD-3-Clause */
/* The initial state of a mechanism's run against its constraints (mech_init.c). */
#ifndef DYNKIT_CLI_MECH_INIT_H
#define DYNKIT_CLI_MECH_INIT_H

#include "cli.h"

/* For a mechanism file spec: run->y0 (at run->t0 with run->par) checked against the
 * constraints (a usage error naming the first that does not hold, with its value), or with
 * projected moved onto them, each changed state printed on stderr unless run->quiet.
 * Other models: nothing. Returns CLI_OK or a CLI status after printing why. */
int cli_mech_initial(const char *command, const char *spec, cli_run *run, int projected);

#endif
