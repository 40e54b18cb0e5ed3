/* SPDX-License-Identifier: BSD-3-Clause */
/* test_mech_util.h — what the mechanism suites share: a file refused by `dynkit run` at its
 * place, and a mechanism's picture read from a text or a file (dyn_mech_scene_read). Needs
 * cmocka, test_util.h (CHECK) and test_cli_run.h included first. */
#ifndef DYNKIT_TEST_MECH_UTIL_H
#define DYNKIT_TEST_MECH_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "dynkit/mbs.h"

/* text written as bad.mech in the test's directory and run: exit 2 (bad input) with where
 * (FILE:LINE:COL) and what in the message */
static inline void mech_refused(const char *text, const char *where, const char *what)
{
    const char *path = cli_path("bad.mech");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    cli_result r = cli("run %s", path);
    CHECK(r.status == 2 && strstr(r.err, where) && strstr(r.err, what),
          "status %d, expected '%s' and '%s' in:\n%s\nfor:\n%s", r.status, where, what, r.err,
          text);
    cli_free(&r);
}

/* the picture of a mechanism given by its text, read as the file path */
static inline dyn_mech_scene *mech_scene_read(const char *path, const char *text, size_t len)
{
    dyn_mech_scene *sc = NULL;
    dyn_lang_diag d;
    char buf[2048];
    const int rc = dyn_mech_scene_read(path, text, len, NULL, 0, &sc, &d);
    CHECK(rc == 0, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    return sc;
}

static inline dyn_mech_scene *mech_scene_of(const char *text)
{
    return mech_scene_read("t.mech", text, strlen(text));
}

static inline dyn_mech_scene *mech_scene_of_file(const char *path)
{
    size_t len;
    char *text = cli_read_file(path, &len);
    assert_non_null(text);
    dyn_mech_scene *sc = mech_scene_read(path, text, len);
    free(text);
    return sc;
}

#endif
