/* SPDX-License-Identifier: BSD-3-Clause */
/* The check of the C text the .ode translator writes (src/lang/emit_out.c states the rule):
 * a tokenizer of C that accepts only
 *   - string and character literals, each on one line, with only printable ASCII inside
 *     (every other byte must be an escape);
 *   - numbers (pp-numbers);
 *   - punctuators;
 *   - identifiers that are C keywords, names the translator's own text uses (the list
 *     below), or names it makes from a prefix and numbers (v_3, ud1_2, dk_event0, ...);
 *   - comments that are the translator's own (the list below with every run of digits
 *     as #, or one of the comments of the constant text tool_text, the solver of
 *     algebraic equations);
 *   - directives #include <header> of the list, #line NUMBER "literal", and the others
 *     as tokens under the same rules.
 * A user-written name as an identifier, a path in a comment, a byte that is no token: each
 * fails, with what and where in why. Used by fuzz/fuzz_emit.c and tests/test_lang_emit.c.
 */
#ifndef DYNKIT_EMIT_CHECK_H
#define DYNKIT_EMIT_CHECK_H

#include <ctype.h>
#include <stdio.h>
#include <string.h>

/* Every identifier the translator's own text writes: a new one (a field of dyn_model, a
 * helper) goes here too, or this check fails on every model. */
static const char *const emit_check_idents[] = {
    /* C keywords the text uses */
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
    "enum", "extern", "for", "if", "inline", "int", "long", "return", "signed", "sizeof",
    "static", "struct", "switch", "unsigned", "void", "while",
    /* directives */
    "include", "line", "define", "ifdef", "ifndef", "endif", "elif", "defined", "undef",
    /* libc and libm */
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "exp",
    "log", "log10", "sqrt", "fabs", "floor", "ceil", "erf", "erfc", "pow", "fmod",
    "isfinite", "isnan", "isinf", "NAN", "INFINITY", "HUGE_VAL", "DBL_EPSILON", "NULL",
    "snprintf", "memcpy", "memset", "size_t", "fmax", "fmin", "abs", "labs",
    /* dynkit/model.h */
    "dyn_model", "dyn_var", "dyn_param", "dyn_event", "dynkit_model", "DYN_SAMPLES_GRID",
    "name", "title", "description", "n_states", "states", "y0", "n_params", "params",
    "par_size", "n_outputs", "outputs", "rhs", "compute_outputs", "prepare", "warn", "t0",
    "t1", "step", "method", "n_inputs", "inputs", "set_input", "jacobian", "n_events",
    "events", "samples", "initial_state", "rtol", "atol", "phase_x", "phase_y", "source",
    "t_trans", "every", "bound", "jac_banded", "jac_lower", "jac_upper", "jacobian_band",
    "time_unit", "phase_window", "n_noise", "noise_kinds", "noise_offset", "noise_class",
    /* tables of random numbers, drawn in prepare (dynkit/sde.h) */
    "seed_offset", "dyn_table_random", "uint64_t",
    "jac_pattern", "jacobian_sparse", "xppaut_globals",
    "delay",
    /* delay models (dynkit/delay.h, src/lang/emit_delay.c) */
    "dyn_history", "dyn_history_value", "dyn_delay_model", "max_delay", "attach", "history",
    "n_lags", "lags", "lag", "dk_hist", "dk_delay", "dk_attach", "dk_history", "dk_lags",
    "dk_delay_model",
    /* Volterra integrals (dynkit/volterra.h, src/lang/integrals.c) */
    "volterra", "dyn_volterra_model", "n_int", "mu", "conv", "is_int", "ints_offset",
    "max_points", "integrand", "kernel", "dk_volt_integrand", "dk_volt_kernel", "dk_volt_mu",
    "dk_volt_conv", "dk_volt_is_int", "dk_volterra_model", "t_now", "ip", "g", "kv", "pw",
    /* Markov states and gill (dynkit/sde.h, src/lang/markov.c) */
    "jump", "dk_jump", "dyn_markov_step", "dyn_gillespie_step", "bad", "h",
    /* boundary conditions (src/lang/bdry.c) */
    "n_bdry", "bdry", "bdry_text", "dk_bdry", "dk_bdry_text", "yl", "yr", "hom",
    "dyn_hom_bcs", "dk_bdry_hom", "dk_hom",
    /* the translator's own names */
    "t", "y", "p", "par", "dydt", "out", "J", "err", "errlen", "names", "k", "i", "j", "s",
    "x", "u", "n", "m", "q", "v", "z", "type", "period", "w", "r", "rb", "lo", "dx", "dk_model",
    "dk_rhs", "dk_outputs", "dk_prepare", "dk_jacobian", "dk_jacobian_band",
    "dk_initial_state", "dk_noise_kinds", "dk_states", "dk_y0", "dk_params", "dk_outputs_vars", "dk_events",
    "dk_jacobian_sparse", "dk_jac_colptr", "dk_jac_rowind",
    "dk_heav", "dk_sign", "dk_mod", "dk_max", "dk_min", "dk_not", "dk_sq", "dk_pow",
    "dk_conv", "dk_conv_at", "dk_table", "dk_table_at", "dk_table_slope", "dk_alg_solve",
    "dk_alg_keep", "dk_alg_residual", "dk_alg_jacobian", "DK_ALG_M", "DK_ALG_N", "DK_ALG_W",
    "DK_ALG_G", "DK_ALG_S", "DK_ALG_T", "DK_ALG_TP", "DK_ALG_YP", "DK_ALG_PATH",
    "DK_ALG_FAILED", "DK_ALG_EXACT_JACOBIAN", "dynkit", "model", "h", "math", "stddef",
    "stdio", "string",
    /* the solver of algebraic equations (src/lang/alg_solver.c) */
    "a", "b", "c", "d", "e", "f", "big", "contract", "it", "last", "move", "parts", "r0", "r1",
    "rounding", "sj", "tp", "w0", "wj", "ys", "dk_alg_lu_solve", "dk_alg_newton",
    /* inputs of mechanisms (dynkit/input.h) */
    "_Static_assert", "dyn_input_table", "dyn_input_table_at", "dyn_input_table_set",
    "dyn_interp", "dk_input", "dk_set_input", "dk_inputs_vars", "table", "rows", "interp",
    "input"};

static const char *const emit_check_comments[] = {
    ("/* C text generated by dynkit from a model file (dk_model.source names it; see \"The "
     ".ode\n * format\" in docs/model-files.md). Edit the model file, not this text. */"),
    "/* user functions and their partial derivatives */", "/* d/d y[#] */",
    "/* d/d w[#] */", "/* r and J = dr/dw, exact */", "/* algebraic variables */",
    "/* states */", "/* p: the last solution */", "/* the initial guesses */",
    "/* the largest magnitudes so far */", "/* the earliest time solved */",
    "/* the time of the last solution */", "/* its state */",
    "/* continuation along a segment (up to # states) */",
    "/* no solution near the branch (dynkit/lang.h) */"};

static const char *const emit_check_headers[] = {"<math.h>", "<stddef.h>", "<stdio.h>",
                                                 "<string.h>", "<dynkit/model.h>",
                                                 "<dynkit/input.h>", "<dynkit/delay.h>",
                                                 "<dynkit/volterra.h>", "<dynkit/sde.h>"};

/* name is prefix digits [suffix digits]: v_3, ud1_2, dk_event0 */
static int emit_check_made(const char *s, size_t n)
{
    static const char *const one[] = {"v_", "u_", "a_", "b_", "sp_", "spu_", "spv_",
                                      "dk_event", "dk_reset", "dk_table_file"};
    static const char *const two[] = {"ud", "dv"};
    for (size_t k = 0; k < sizeof one / sizeof *one; k++) {
        const size_t l = strlen(one[k]);
        if (n > l && strncmp(s, one[k], l) == 0) {
            size_t i = l;
            while (i < n && isdigit((unsigned char)s[i]))
                i++;
            if (i == n)
                return 1;
        }
    }
    for (size_t k = 0; k < sizeof two / sizeof *two; k++) {
        if (n < 5 || strncmp(s, two[k], 2) != 0)
            continue;
        size_t i = 2, d1;
        while (i < n && isdigit((unsigned char)s[i]))
            i++;
        d1 = i - 2;
        if (d1 == 0 || i >= n || s[i] != '_')
            continue;
        size_t j = ++i;
        while (i < n && isdigit((unsigned char)s[i]))
            i++;
        if (i == n && i > j)
            return 1;
    }
    return 0;
}

static int emit_check_ident(const char *s, size_t n)
{
    for (size_t k = 0; k < sizeof emit_check_idents / sizeof *emit_check_idents; k++)
        if (strlen(emit_check_idents[k]) == n && strncmp(s, emit_check_idents[k], n) == 0)
            return 1;
    return emit_check_made(s, n);
}

/* Whether the comment s[0..n) is one of the list (digits as #) or occurs in tool_text. */
static int emit_check_comment(const char *s, size_t n, const char *tool_text)
{
    char norm[512];
    size_t k = 0;
    for (size_t i = 0; i < n && k + 1 < sizeof norm; i++) {
        if (isdigit((unsigned char)s[i])) {
            norm[k++] = '#';
            while (i + 1 < n && isdigit((unsigned char)s[i + 1]))
                i++;
        } else {
            norm[k++] = s[i];
        }
    }
    norm[k] = '\0';
    if (n < sizeof norm - 1)
        for (size_t j = 0; j < sizeof emit_check_comments / sizeof *emit_check_comments; j++)
            if (strcmp(norm, emit_check_comments[j]) == 0)
                return 1;
    if (tool_text)
        for (const char *t = strstr(tool_text, "/*"); t; t = strstr(t + 2, "/*"))
            if (strncmp(t, s, n) == 0)
                return 1;
    return 0;
}

/* 0 when text (NUL-terminated) passes; else 1 with the reason and the place in why. */
static int emit_check(const char *text, const char *tool_text, char *why, size_t whylen)
{
    const char *s = text;
    int line_start = 1;
    int after_include = 0;
    while (*s) {
        const unsigned char ch = (unsigned char)*s;
        const size_t at = (size_t)(s - text);
        if (ch == '\n') {
            line_start = 1;
            s++;
            continue;
        }
        if (ch == ' ' || ch == '\t') {
            s++;
            continue;
        }
        const int was_start = line_start;
        line_start = 0;
        if (s[0] == '/' && s[1] == '*') {
            const char *e = strstr(s + 2, "*/");
            if (!e) {
                snprintf(why, whylen, "offset %zu: a comment that does not end", at);
                return 1;
            }
            if (!emit_check_comment(s, (size_t)(e + 2 - s), tool_text)) {
                snprintf(why, whylen, "offset %zu: a comment that is not the translator's: "
                         "%.*s", at, (int)(e + 2 - s) > 200 ? 200 : (int)(e + 2 - s), s);
                return 1;
            }
            s = e + 2;
            continue;
        }
        if (s[0] == '/' && s[1] == '/') {
            snprintf(why, whylen, "offset %zu: a // comment", at);
            return 1;
        }
        if (ch == '"' || ch == '\'') {
            const char *q = s + 1;
            while (*q && *q != (char)ch) {
                const unsigned char b = (unsigned char)*q;
                if (b < 32 || b >= 127) {
                    snprintf(why, whylen, "offset %zu: byte %u unescaped in a literal",
                             (size_t)(q - text), b);
                    return 1;
                }
                if (b == '?' && q[1] == '?') {
                    snprintf(why, whylen, "offset %zu: ?? (a trigraph) in a literal",
                             (size_t)(q - text));
                    return 1;
                }
                q += b == '\\' && q[1] ? 2 : 1;
            }
            if (*q != (char)ch) {
                snprintf(why, whylen, "offset %zu: a literal that does not end", at);
                return 1;
            }
            s = q + 1;
            continue;
        }
        if (isdigit(ch) || (ch == '.' && isdigit((unsigned char)s[1]))) {
            while (isalnum((unsigned char)*s) || *s == '.' || *s == '_' ||
                   ((*s == '+' || *s == '-') && (s[-1] == 'e' || s[-1] == 'E')))
                s++;
            continue;
        }
        if (isalpha(ch) || ch == '_') {
            const char *q = s;
            while (isalnum((unsigned char)*q) || *q == '_')
                q++;
            if (!emit_check_ident(s, (size_t)(q - s))) {
                snprintf(why, whylen, "offset %zu: identifier '%.*s' is not the translator's",
                         at, (int)(q - s) > 200 ? 200 : (int)(q - s), s);
                return 1;
            }
            if (after_include && (size_t)(q - s) == 7 && strncmp(s, "include", 7) == 0) {
                while (*q == ' ')
                    q++;
                size_t k = 0;
                for (; k < sizeof emit_check_headers / sizeof *emit_check_headers; k++) {
                    const size_t l = strlen(emit_check_headers[k]);
                    if (strncmp(q, emit_check_headers[k], l) == 0 && q[l] == '\n') {
                        q += l;
                        break;
                    }
                }
                if (k == sizeof emit_check_headers / sizeof *emit_check_headers) {
                    snprintf(why, whylen, "offset %zu: an #include of another header", at);
                    return 1;
                }
            }
            after_include = 0;
            s = q;
            continue;
        }
        if (ch == '#') {
            after_include = was_start;
            s++;
            continue;
        }
        if (ch < 128 && strchr("{}[]()<>;,.+-*/%!=&|?:~^", ch)) {
            s++;
            continue;
        }
        snprintf(why, whylen, "offset %zu: byte %u is no C token", at, ch);
        return 1;
    }
    return 0;
}

#endif /* DYNKIT_EMIT_CHECK_H */
