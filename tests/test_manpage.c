/* SPDX-License-Identifier: BSD-3-Clause */
/* The manual page docs/dynkit.1 and the bash completion completions/dynkit.bash:
 * - man renders the page without a warning (man --warnings, and groff -ww when there);
 * - every option that a command's --help names (--name, and the short -o, -m) appears in
 *   the page, so that a new option cannot be left out of it;
 * - the exit statuses are in the page and in `dynkit help`;
 * - the completion completes commands, the options of a command, models, methods (with
 *   MATLAB's names) and the values of --header (run by bash, with dynkit on the PATH).
 * A check is skipped, with the reason, when man, groff or bash is not installed. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_cli_run.h"
#include "test_util.h"

#define PAGE DYNKIT_SOURCE_DIR "/docs/dynkit.1"
#define COMPLETION DYNKIT_SOURCE_DIR "/completions/dynkit.bash"

static int have(const char *cmd)
{
    char full[512];
    snprintf(full, sizeof full, "command -v %s >/dev/null 2>&1", cmd);
    return system(full) == 0;
}

static void test_page_renders_without_warnings(void **state)
{
    (void)state;
    if (!have("man")) {
        print_message("SKIP: man is not installed (Debian's man-db)\n");
        skip();
    }
    int status;
    char *out = cli_capture("MANWIDTH=80 LC_ALL=C man --warnings -l '" PAGE "' 2>&1 >/dev/null",
                            &status);
    CHECK(status == 0 && out[0] == '\0', "man --warnings: exit %d:\n%s", status, out);
    free(out);
    out = cli_capture("MANWIDTH=80 LC_ALL=C man -l '" PAGE "' 2>/dev/null", &status);
    CHECK(status == 0 && strstr(out, "EXIT STATUS") && strstr(out, "DATA FILES") &&
              strstr(out, "EXAMPLES"),
          "the rendered page lacks a section:\n%.500s", out);
    free(out);
    if (have("groff")) {
        out = cli_capture("groff -ww -z -man '" PAGE "' 2>&1", &status);
        CHECK(status == 0 && out[0] == '\0', "groff -ww: exit %d:\n%s", status, out);
        free(out);
    }
}

/* "--max-step" as written in roff: "\-\-max\-step". */
static void roff_option(const char *opt, char *buf, size_t size)
{
    size_t n = 0;
    for (const char *p = opt; *p && n + 3 < size; p++) {
        if (*p == '-')
            buf[n++] = '\\';
        buf[n++] = *p;
    }
    buf[n] = '\0';
}

static void test_every_option_is_in_the_page(void **state)
{
    (void)state;
    static const char *const commands[] = {"",        "run",    "models",  "methods",
                                           "info",    "inverse", "report", "animate",
                                           "plot",    "verify",  "sweep",  "linearize",
                                           "derive",  "equilibria", "lyapunov", "steady",
                                           "continue", "bvp"};
    char *page = cli_read_file(PAGE, NULL);
    CHECK(strlen(page) > 1000, "cannot read %s", PAGE);
    char missing[2048] = "";
    size_t used = 0;
    int checked = 0;
    for (size_t c = 0; c < sizeof commands / sizeof commands[0]; c++) {
        cli_result r = cli("%s --help", commands[c]);
        CHECK(r.status == 0, "dynkit %s --help: exit %d", commands[c], r.status);
        for (const char *p = r.out; *p; p++) {
            /* an option: "--name" or a short "-x" followed by ", " (as in "-o, --output") */
            const int start = p == r.out || !(p[-1] == '-' || p[-1] == '_' ||
                                              (p[-1] >= 'a' && p[-1] <= 'z') ||
                                              (p[-1] >= 'A' && p[-1] <= 'Z'));
            size_t len = 0;
            if (start && p[0] == '-' && p[1] == '-' && p[2] >= 'a' && p[2] <= 'z') {
                len = 2;
                while ((p[len] >= 'a' && p[len] <= 'z') || (p[len] >= '0' && p[len] <= '9') ||
                       (p[len] == '-' && p[len + 1] >= 'a' && p[len + 1] <= 'z'))
                    len++;
            } else if (start && p[0] == '-' && p[1] >= 'a' && p[1] <= 'z' && p[2] == ',') {
                len = 2;
            }
            if (!len)
                continue;
            char opt[64], roff[160];
            snprintf(opt, sizeof opt, "%.*s", (int)(len < 63 ? len : 63), p);
            roff_option(opt, roff, sizeof roff);
            checked++;
            if (!strstr(page, roff) && !strstr(missing, opt) && used < sizeof missing)
                used += (size_t)snprintf(missing + used, sizeof missing - used, " %s (%s)", opt,
                                         commands[c][0] ? commands[c] : "dynkit");
            p += len - 1;
        }
        cli_free(&r);
    }
    free(page);
    CHECK(checked > 60, "only %d options found in the help texts", checked);
    CHECK(missing[0] == '\0', "options of --help missing from docs/dynkit.1:%s", missing);
}

static void test_exit_statuses_documented(void **state)
{
    (void)state;
    cli_result r = cli("help");
    CHECK(r.status == 0 && strstr(r.out, "Exit status: 0 success; 1 ") && strstr(r.out, "2 a bad"),
          "dynkit help does not give the exit statuses:\n%s", r.out);
    cli_free(&r);
    r = cli("help run");
    cli_result h = cli("run --help");
    CHECK(r.status == 0 && strcmp(r.out, h.out) == 0, "dynkit help run differs from run --help");
    cli_free(&r);
    cli_free(&h);
    r = cli("help nosuch");
    CHECK(r.status == 2, "dynkit help nosuch: exit %d", r.status);
    cli_free(&r);
    char *page = cli_read_file(PAGE, NULL);
    CHECK(strstr(page, ".SH EXIT STATUS") && strstr(page, "128+N"),
          "the page has no EXIT STATUS section");
    free(page);
}

/* Complete the words (the last one being completed) with the completion, dynkit on PATH. */
static char *complete(const char *words)
{
    char cmd[2048];
    const char *bin = DYNKIT_CLI;
    const char *slash = strrchr(bin, '/');
    snprintf(cmd, sizeof cmd,
             "cd '%s' && PATH='%.*s':\"$PATH\" bash --norc --noprofile -c '"
             "source \"%s\"; COMP_WORDS=(%s); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _dynkit; "
             "printf \"%%s\\n\" \"${COMPREPLY[@]}\"' 2>&1",
             cli_tmpdir, (int)(slash - bin), bin, COMPLETION, words);
    int status;
    char *out = cli_capture(cmd, &status);
    CHECK(status == 0, "completion of %s: exit %d: %s", words, status, out);
    return out;
}

/* 1 if the line item is in the list of lines. */
static int has_line(const char *lines, const char *item)
{
    size_t n = strlen(item);
    for (const char *p = lines; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
        if (strncmp(p, item, n) == 0 && (p[n] == '\n' || p[n] == '\0'))
            return 1;
    return 0;
}

static void test_bash_completion(void **state)
{
    (void)state;
    if (!have("bash")) {
        print_message("SKIP: bash is not installed\n");
        skip();
    }
    static const struct {
        const char *words, *expect[4];
    } cases[] = {
        {"dynkit r", {"run", "report", NULL}},
        {"dynkit run \"\"", {"pendulum", "plane-quat", "robertson", NULL}},
        {"dynkit run pendulum --ou", {"--output", "--outputs", NULL}},
        {"dynkit run pendulum -m ode", {"ode45", "ode23", "ode15s", "ode23s"}},
        {"dynkit run pendulum --header \"\"", {"names", "units", "none", NULL}},
        {"dynkit run pendulum --init d", {"dphi=", NULL}},
        {"dynkit verify --q", {"--quick", NULL}},
        {"dynkit help an", {"animate", NULL}},
        {"dynkit plot vanderpol --ti", {"--title", NULL}},
        {"dynkit lin", {"linearize", NULL}},
        {"dynkit de", {"derive", NULL}},
        {"dynkit linearize pendulum --ma", {"--matrix", NULL}},
        {"dynkit linearize pendulum --jacobian r", {"richardson", NULL}},
        {"dynkit linearize pendulum --set \"\"", {"l=", "g=", NULL}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *out = complete(cases[i].words);
        for (int k = 0; k < 4 && cases[i].expect[k]; k++)
            CHECK(has_line(out, cases[i].expect[k]), "completing '%s': no %s in:\n%s",
                  cases[i].words, cases[i].expect[k], out);
        free(out);
    }
    /* plot also takes a sweep's table, .csv or .json; run takes models only */
    static const char *const tables[] = {"grid.csv", "grid.json"};
    for (size_t i = 0; i < 2; i++) {
        FILE *f = fopen(cli_path(tables[i]), "w");
        CHECK(f, "cannot write %s", tables[i]);
        fclose(f);
    }
    char *out = complete("dynkit plot gr");
    CHECK(has_line(out, "grid.csv") && has_line(out, "grid.json"),
          "completing 'dynkit plot gr': not the tables in:\n%s", out);
    free(out);
    out = complete("dynkit run gr");
    CHECK(!has_line(out, "grid.csv") && !has_line(out, "grid.json"),
          "completing 'dynkit run gr' offers a table:\n%s", out);
    free(out);
    for (size_t i = 0; i < 2; i++)
        unlink(cli_path(tables[i]));
}

static int teardown(void **state)
{
    (void)state;
    return cli_teardown_files(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_page_renders_without_warnings),
        cmocka_unit_test(test_every_option_is_in_the_page),
        cmocka_unit_test(test_exit_statuses_documented),
        cmocka_unit_test(test_bash_completion),
    };
    return cmocka_run_group_tests(tests, cli_setup, teardown);
}
