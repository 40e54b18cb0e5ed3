/* SPDX-License-Identifier: BSD-3-Clause */
/* The symbol table of a model file: names folded to one case, as XPPAUT folds them (`A` and
 * `a` are one name), in an open-addressing hash table (FNV-1a of the folded name, linear
 * probing, doubled at half full); a repeated name refused with the line of its first
 * declaration, except an aux's name beside another kind's (XPPAUT 6.11's rule). Used by
 * the statement parsers and by check.c; calls nothing of theirs. */
#include <ctype.h>
#include <stdint.h>

#include "lang/lang_internal.h"

void lang_fold(char *dst, const char *src, size_t size)
{
    size_t i = 0;
    for (; src[i] && i + 1 < size; i++)
        dst[i] = (char)tolower((unsigned char)src[i]);
    dst[i] = '\0';
}

static uint32_t hash_folded(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (uint32_t)tolower((unsigned char)*s)) * 16777619u;
    return h;
}

int lang_same_name(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
    return *a == *b;
}

lang_sym *lang_lookup(lang_ctx *c, const char *name)
{
    lang_model *m = &c->m;
    if (!m->symcap)
        return NULL;
    uint32_t i = hash_folded(name) & (uint32_t)(m->symcap - 1);
    while (m->syms[i].key) {
        if (lang_same_name(m->syms[i].key, name))
            return &m->syms[i];
        i = (i + 1) & (uint32_t)(m->symcap - 1);
    }
    return NULL;
}

const char *lang_sym_kind_name(sym_kind k)
{
    switch (k) {
    case SYM_STATE: return "a state";
    case SYM_PARAM: return "a parameter";
    case SYM_NUMBER: return "a number";
    case SYM_DERIVED: return "a derived parameter";
    case SYM_FIX: return "a fixed quantity";
    case SYM_AUX: return "an aux output";
    case SYM_FUNC: return "a function";
    case SYM_TABLE: return "a table";
    case SYM_SPECIAL: return "a network sum";
    case SYM_ALG: return "an algebraic variable";
    case SYM_NOISE: return "a noise (wiener)";
    case SYM_VOLT: return "an integral";
    default: return "a name";
    }
}

void lang_declare(lang_ctx *c, const char *name, lpos pos, sym_kind kind, int index)
{
    lang_model *m = &c->m;
    lang_sym *old = lang_lookup(c, name);
    /* XPPAUT's rule (measured with 6.11): an aux's name is a label of its output column and
     * no formula reads it, so it may repeat the name of a state, a parameter, a number, a
     * fixed quantity or a function, which the formulas then mean, in either order */
    const int label = (kind == SYM_AUX) != (old && old->kind == SYM_AUX);
    const sym_kind other = kind == SYM_AUX ? (old ? old->kind : SYM_NONE) : kind;
    if (old && label &&
        (other == SYM_STATE || other == SYM_PARAM || other == SYM_NUMBER || other == SYM_FIX ||
         other == SYM_FUNC)) {
        lang_note(c, pos, "aux '%s' shares its name with %s: it names an output column only, "
                  "and formulas mean the %s, as in XPPAUT", name, lang_sym_kind_name(other),
                  other == SYM_STATE ? "state" : other == SYM_FUNC ? "function"
                  : other == SYM_FIX ? "fixed quantity" : other == SYM_PARAM ? "parameter"
                                                                            : "number");
        if (kind != SYM_AUX) { /* the later declaration takes the name */
            old->kind = kind;
            old->index = index;
            old->pos = pos;
        }
        return;
    }
    if (old)
        lang_fail(c, pos, "'%s' is already declared as %s on line %d (XPPAUT's names ignore "
                  "case)", name, lang_sym_kind_name(old->kind), old->pos.line);
    if (m->nsyms >= LANG_MAX_SYMBOLS)
        lang_fail(c, pos, "too many names (more than %d)", LANG_MAX_SYMBOLS);
    if (2 * (m->nsyms + 1) > m->symcap) {
        const int cap = m->symcap ? 2 * m->symcap : 64;
        lang_sym *t = lang_alloc(c, (size_t)cap * sizeof *t);
        for (int k = 0; k < m->symcap; k++)
            if (m->syms[k].key) {
                uint32_t i = hash_folded(m->syms[k].key) & (uint32_t)(cap - 1);
                while (t[i].key)
                    i = (i + 1) & (uint32_t)(cap - 1);
                t[i] = m->syms[k];
            }
        m->syms = t;
        m->symcap = cap;
    }
    uint32_t i = hash_folded(name) & (uint32_t)(m->symcap - 1);
    while (m->syms[i].key)
        i = (i + 1) & (uint32_t)(m->symcap - 1);
    m->syms[i] = (lang_sym){name, kind, index, pos};
    m->nsyms++;
}
