/* SPDX-License-Identifier: BSD-3-Clause */
/* Output files of the tool that a failed or interrupted run never destroys, the check of
 * standard output at exit, and SIGINT/SIGTERM (out_file.c). */
#ifndef DYNKIT_CLI_OUT_FILE_H
#define DYNKIT_CLI_OUT_FILE_H

#include <signal.h>

#include "cli.h"

/* An output being written: f is a temporary file beside the real name (regular files),
 * the file itself (devices, pipes), or stdout (no path, or "-"). */
typedef struct cli_out {
    FILE *f;
    const char *what; /* the option, e.g. "--output" */
    const char *path; /* the name given, NULL for stdout */
    char *target;     /* the file renamed over (symbolic links followed), owned */
    char *tmp;        /* the temporary name, owned, or NULL when written in place */
    int failure_told; /* set by a caller that reported a failed write itself: not again */
} cli_out;

/* Open path for writing (NULL or "-": stdout). A directory, a missing directory or a place
 * that cannot be written is an error naming the option and the file, printed; returns
 * CLI_OK or CLI_FAILED. A file the command reads (cli_input_note) is refused: CLI_USAGE.
 * The file under the real name is untouched until cli_out_close. */
int cli_out_open(cli_out *o, const char *what, const char *path);
/* Close o. keep: the temporary file replaces the real name; else it is removed and the real
 * name keeps what it had. A failed write is an error naming the file whether kept or not;
 * so is a real name that became an input since it was opened (CLI_USAGE, not replaced).
 * Returns CLI_OK, CLI_FAILED or CLI_USAGE (message printed; stdout failures are reported
 * by cli_stdout_check). */
int cli_out_close(cli_out *o, int keep);
/* 1 if path's file name ends in the extension ext (".svg"; case ignored). */
int cli_has_extension(const char *path, const char *ext);
/* CLI_OK when path (NULL or "-": standard output) ends in one of the extensions exts
 * (NULL-terminated, e.g. ".svg"; case ignored) or is a device or pipe; else a usage error of
 * command, printed, that names option, the file and the accepted extensions (CLI_USAGE). */
int cli_out_check_extension(const char *command, const char *option, const char *path,
                            const char *const *exts);
/* 1 if the two paths name the same file (existing or not; "-" is never a file). */
int cli_same_file(const char *a, const char *b);
/* Note path (when it is a regular file) as an input of the command, what it is in words
 * ("the model file", "the --forces table"; a constant): no output may replace it. */
void cli_input_note(const char *path, const char *what);
/* What path is among the inputs noted (the same device and inode), or NULL. */
const char *cli_input_named(const char *path);
/* The usage error for an output (option, path) that names an input of the command (what:
 * "the model file", "the --forces table"): writing it would destroy the input. Printed
 * (with the hint to command's --help unless command is NULL); returns CLI_USAGE. */
int cli_out_refuse_input(const char *command, const char *option, const char *path,
                         const char *what);
/* At exit: flush stdout; a failed write turns rc into CLI_FAILED with a message (a closed
 * pipe, EPIPE, ends quietly). Returns the exit status. */
int cli_stdout_check(int rc);

/* SIGINT and SIGTERM: by default the temporary output file is removed and the signal ends
 * the program as usual; in graceful mode (a run writing rows) the signal is only recorded:
 * the run finishes its row, stops, keeps its file and exits with cli_signal_status(). */
extern volatile sig_atomic_t cli_stop_signal;
void cli_signals_install(void);
void cli_signals_graceful(int on);
void cli_signals_track(const char *tmp_path);
/* 128 + the signal received (130 SIGINT, 143 SIGTERM), or 0. */
int cli_signal_status(void);
const char *cli_signal_name(void);

#endif
