/* SPDX-License-Identifier: BSD-3-Clause */
/* A small streaming JSON writer (RFC 8259) for the data of the HTML pages: it places the
 * commas, writes numbers compactly (%.*g, null when not finite) and escapes strings so the
 * text can sit inside an HTML <script> element (escape.h). */
#include <math.h>
#include <string.h>

#include "util/escape.h"
#include "pages/pages.h"

void cli_json_init(cli_json *j, FILE *out, int digits)
{
    memset(j, 0, sizeof *j);
    j->out = out;
    j->digits = digits > 0 ? digits : 17;
}

/* Before a value: a comma when the enclosing array or object has items already. */
static void separate(cli_json *j)
{
    if (j->after_key) {
        j->after_key = 0;
        return;
    }
    if (j->depth <= 0 || j->depth > CLI_JSON_MAX_DEPTH)
        return;
    if (j->has_items[j->depth - 1])
        j->bad |= fputc(',', j->out) == EOF;
    j->has_items[j->depth - 1] = 1;
}

static void begin(cli_json *j, char bracket)
{
    separate(j);
    j->bad |= fputc(bracket, j->out) == EOF;
    if (j->depth < CLI_JSON_MAX_DEPTH)
        j->has_items[j->depth] = 0;
    j->depth++;
}

static void end(cli_json *j, char bracket)
{
    if (j->depth > 0)
        j->depth--;
    j->bad |= fputc(bracket, j->out) == EOF;
}

void cli_json_begin_object(cli_json *j) { begin(j, '{'); }
void cli_json_end_object(cli_json *j) { end(j, '}'); }
void cli_json_begin_array(cli_json *j) { begin(j, '['); }
void cli_json_end_array(cli_json *j) { end(j, ']'); }

void cli_json_key(cli_json *j, const char *key)
{
    separate(j);
    j->bad |= cli_json_escaped(j->out, key);
    j->bad |= fputc(':', j->out) == EOF;
    j->after_key = 1;
}

/* A number, null when not finite; negative zero as -0.0 (JSON readers take "-0" for 0). */
static void put_number(cli_json *j, double v)
{
    if (!isfinite(v))
        j->bad |= fputs("null", j->out) < 0;
    else if (v == 0.0 && signbit(v))
        j->bad |= fputs("-0.0", j->out) < 0;
    else
        j->bad |= fprintf(j->out, "%.*g", j->digits, v) < 0;
}

void cli_json_number(cli_json *j, double v)
{
    separate(j);
    put_number(j, v);
}

void cli_json_string(cli_json *j, const char *s)
{
    separate(j);
    j->bad |= cli_json_escaped(j->out, s);
}

void cli_json_bool(cli_json *j, int v)
{
    separate(j);
    j->bad |= fputs(v ? "true" : "false", j->out) < 0;
}

void cli_json_null(cli_json *j)
{
    separate(j);
    j->bad |= fputs("null", j->out) < 0;
}

void cli_json_raw(cli_json *j, const char *text, size_t len)
{
    separate(j);
    j->bad |= fwrite(text, 1, len, j->out) != len;
}

void cli_json_numbers(cli_json *j, const double *v, long n, long stride)
{
    cli_json_begin_array(j);
    for (long k = 0; k < n; k++) {
        if (k)
            j->bad |= fputc(',', j->out) == EOF;
        put_number(j, v[k * stride]);
    }
    cli_json_end_array(j);
}
