/* SPDX-License-Identifier: BSD-3-Clause */
/* Command-line parsing helpers: numbers (with multiples of pi, or angles in degrees), counts,
 * options (-o and -m are --output and --method). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"
#include "util/escape.h"

/* "dynkit: <kind>: " (nothing when kind is NULL) and the message on stderr, its control
 * bytes escaped (escape.h): a message quotes names, lines and values from files. */
static void print_message(const char *kind, const char *fmt, va_list ap)
{
    va_list copy;
    va_copy(copy, ap);
    const int len = vsnprintf(NULL, 0, fmt, copy);
    va_end(copy);
    char *msg = len >= 0 ? malloc((size_t)len + 1) : NULL;
    char *shown = msg ? malloc(4 * (size_t)len + 8) : NULL;
    if (shown) {
        vsnprintf(msg, (size_t)len + 1, fmt, ap);
        const char *text = cli_terminal_text(msg, 1, shown, 4 * (size_t)len + 8);
        if (kind)
            fprintf(stderr, "dynkit: %s: %s", kind, text);
        else
            fputs(text, stderr);
    } else {
        fputs("dynkit: error: out of memory\n", stderr);
    }
    free(msg);
    free(shown);
}

void cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    print_message("error", fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void cli_warning(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    print_message("warning", fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void cli_note(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    print_message("note", fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void cli_stderr(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    print_message(NULL, fmt, ap);
    va_end(ap);
}

int cli_usage_error(const char *command, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    print_message("error", fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry 'dynkit %s%s--help'.\n", command ? command : "", command ? " " : "");
    return CLI_USAGE;
}

/* "pi" or "*pi" at *p: advance past it and return 1. */
static int take_pi(const char **p)
{
    const char *s = *p;
    if (*s == '*')
        s++;
    if (s[0] == 'p' && s[1] == 'i') {
        *p = s + 2;
        return 1;
    }
    return 0;
}

/* 1 for a hexadecimal number at p ("0x10", "-0X1p3"), which strtod reads and the command
 * line does not: its numbers are decimal (docs/cli.md, "Numbers"). */
static int is_hex(const char *p)
{
    while (isspace((unsigned char)*p))
        p++;
    if (*p == '-' || *p == '+')
        p++;
    return p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
}

/* One decimal number at p (strtod's syntax without its hexadecimal form): 0 and *v, *end past it; -1 when there is none,
 * when it is not finite (inf, nan), or when it is out of the range of doubles (1e400, and
 * 1e-400, which would round to 0). Subnormal numbers (1e-310) are accepted. */
static int read_double(const char *p, char **end, double *v)
{
    if (is_hex(p))
        return -1;
    errno = 0;
    *v = strtod(p, end);
    if (*end == p || !isfinite(*v))
        return -1;
    if (errno == ERANGE && (*v == 0.0 || fabs(*v) >= 1.0))
        return -1;
    return 0;
}

int cli_parse_number(const char *text, double *out)
{
    if (!text || !*text)
        return -1;
    const char *p = text;
    double value;
    int sign = 1;
    if ((p[0] == '-' || p[0] == '+') && p[1] == 'p') {
        sign = p[0] == '-' ? -1 : 1;
        p++;
    }
    if (p[0] == 'p') {
        value = sign;
    } else {
        char *end;
        if (read_double(p, &end, &value))
            return -1;
        p = end;
    }
    if (strncmp(p, "deg", 3) == 0) { /* an angle in degrees: 45deg */
        value *= DYN_PI / 180.0;
        p += 3;
    } else if (take_pi(&p)) {
        value *= DYN_PI;
    }
    if (*p == '/') {
        /* the divisor follows the same rule as the number: 1/inf and 1/1e400 are refused
         * like inf and 1e400 */
        char *end;
        double div;
        if (read_double(p + 1, &end, &div) || div == 0.0)
            return -1;
        const double q = value / div;
        if (q == 0.0 && value != 0.0)
            return -1; /* the quotient rounds to 0: out of the range of doubles */
        value = q;
        p = end;
    }
    if (*p != '\0' || !isfinite(value))
        return -1;
    *out = value;
    return 0;
}

int cli_parse_count(const char *text, long min, long *out)
{
    double v;
    char *end;
    if (!text || !*text || is_hex(text))
        return -1;
    errno = 0;
    v = strtod(text, &end);
    if (*end != '\0' || errno == ERANGE || !(v >= (double)min) || v > 9.2e18 || v != floor(v))
        return -1;
    *out = (long)v;
    return 0;
}

/* The short forms: -o for --output, -m for --method (each takes the next argument). */
static int short_form(const char *arg, const char *name)
{
    return (strcmp(arg, "-o") == 0 && strcmp(name, "output") == 0) ||
           (strcmp(arg, "-m") == 0 && strcmp(name, "method") == 0);
}

int cli_option(int argc, char **argv, int *i, const char *name, const char **value)
{
    const char *arg = argv[*i];
    size_t len = strlen(name);
    if (short_form(arg, name)) {
        if (*i + 1 >= argc)
            return -1;
        *value = argv[++*i];
        return 1;
    }
    if (strncmp(arg, "--", 2) != 0 || strncmp(arg + 2, name, len) != 0)
        return 0;
    if (arg[2 + len] == '=') {
        *value = arg + 3 + len;
        return 1;
    }
    if (arg[2 + len] != '\0')
        return 0;
    if (*i + 1 >= argc)
        return -1;
    *value = argv[++*i];
    return 1;
}

int cli_flag(const char *arg, const char *name)
{
    return strncmp(arg, "--", 2) == 0 && strcmp(arg + 2, name) == 0;
}

int cli_is_help(const char *arg) { return strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0; }

int cli_unknown_option(const char *command, const char *arg, const char *const *options, int n)
{
    char word[64];
    snprintf(word, sizeof word, "%s%.*s", strncmp(arg, "--", 2) == 0 ? "" : "--",
             (int)strcspn(arg, "="), arg);
    const char *near = dyn_lang_nearest(word, options, n);
    if (near)
        return cli_usage_error(command, "unknown option '%s' (did you mean '%s'?)", arg, near);
    return cli_usage_error(command, "unknown option '%s'", arg);
}
