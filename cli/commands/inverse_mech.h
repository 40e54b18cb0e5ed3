/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit inverse FILE.mech (inverse_mech.c). */
#ifndef DYNKIT_CLI_INVERSE_MECH_H
#define DYNKIT_CLI_INVERSE_MECH_H

#include "cli.h"

/* argv[0] is the mechanism file, the rest its options; returns a CLI status. */
int cli_inverse_mech(int argc, char **argv);

#endif
