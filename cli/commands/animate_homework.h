/* SPDX-License-Identifier: BSD-3-Clause */
/* The homework's run as the default animation of a homework model (animate_homework.c). */
#ifndef DYNKIT_CLI_ANIMATE_HOMEWORK_H
#define DYNKIT_CLI_ANIMATE_HOMEWORK_H

#include "pages/pages.h"

/* 1 when `dynkit animate` plays the homework's run of v's model: the built-in cart with none
 * of the options that choose a run (--forces, --set, --init, --tspan, --step, --method,
 * --times, --end) among argv[1..argc). */
int cli_animate_homework_applies(const cli_view *v, int argc, char **argv);
/* Set v's run to the homework's (problem 4c: the force table of 4b from the prescribed
 * path of 4a, held over each sample; modified Euler at Ts from the prescribed initial
 * state). CLI_OK, or CLI_FAILED with a message printed. */
int cli_animate_homework_setup(cli_view *v);
/* After cli_view_record: label the forward run, and add the prescribed path of 4a at the
 * forward run's sample times as one more series. CLI_OK, or CLI_FAILED (out of memory). */
int cli_animate_homework_finish(cli_view *v);
/* The page's sentence on what it shows, into buf. */
void cli_animate_homework_shows(char *buf, size_t size);

#endif
