/* SPDX-License-Identifier: BSD-3-Clause */
/* Common subexpressions of a derived mechanism: every subtree that occurs more than once
 * among the fixed quantities the derivation wrote becomes a fixed quantity of its own,
 * computed once (value numbering by hash-consing: structurally equal trees get one number;
 * Cocke, "Global common subexpression elimination", SIGPLAN Notices 5 (1970); Aho, Sethi
 * and Ullman, "Compilers", section 6.1). The symbolic derivatives of expanded kinematics
 * (the Jacobians, the convective terms) repeat the same products of sines and cosines many
 * times; without this the C text of a mechanism such as the benchmark bicycle grows to
 * megabytes. */
#include <stdint.h>
#include <string.h>

#include "mbs/mbs_internal.h"

typedef struct cse_ent {
    const node *rep; /* a tree of this number */
    int *kids;       /* its children's numbers */
    unsigned hash;
    int uses;        /* occurrences (counted once per distinct parent tree) */
    int fix;         /* the fixed quantity that holds it, or -1 */
} cse_ent;

typedef struct cse {
    lang_ctx *c;
    cse_ent *ent;
    int nent, entcap;
    int *table; /* entry numbers by hash, -1 empty; size tcap (a power of 2) */
    int tcap;
    const node **pkey; /* node pointer -> number (pointer-shared trees are numbered once) */
    int *pval;
    int pcap, npkey;
    int *order; /* the new order of the fixed quantities */
    int norder, ordercap;
    int count;
} cse;

static unsigned mix(unsigned h, uint64_t v)
{
    h ^= (unsigned)(v ^ (v >> 32));
    return h * 0x9e3779b1u + 0x7f4a7c15u;
}

static unsigned ptr_hash(const node *e)
{
    const uint64_t v = (uint64_t)(uintptr_t)e;
    return (unsigned)((v >> 4) * 0x9e3779b97f4a7c15ull >> 32);
}

static void grow_ptr(cse *s)
{
    const int cap = s->pcap ? 2 * s->pcap : 1 << 14;
    const node **k = lang_alloc(s->c, (size_t)cap * sizeof *k);
    int *v = lang_alloc(s->c, (size_t)cap * sizeof *v);
    memset(k, 0, (size_t)cap * sizeof *k);
    for (int i = 0; i < s->pcap; i++)
        if (s->pkey[i]) {
            unsigned h = ptr_hash(s->pkey[i]) & (unsigned)(cap - 1);
            while (k[h])
                h = (h + 1) & (unsigned)(cap - 1);
            k[h] = s->pkey[i];
            v[h] = s->pval[i];
        }
    s->pkey = k;
    s->pval = v;
    s->pcap = cap;
}

static void grow_table(cse *s)
{
    const int cap = s->tcap ? 2 * s->tcap : 1 << 14;
    int *t = lang_alloc(s->c, (size_t)cap * sizeof *t);
    memset(t, 0xff, (size_t)cap * sizeof *t);
    for (int i = 0; i < s->nent; i++) {
        unsigned h = s->ent[i].hash & (unsigned)(cap - 1);
        while (t[h] >= 0)
            h = (h + 1) & (unsigned)(cap - 1);
        t[h] = i;
    }
    s->table = t;
    s->tcap = cap;
}

static int same(const cse_ent *a, const node *e, const int *kids)
{
    const node *r = a->rep;
    if (r->kind != e->kind || r->op != e->op || r->index != e->index || r->nargs != e->nargs ||
        memcmp(&r->num, &e->num, sizeof r->num) != 0)
        return 0;
    if ((r->kind == N_NUM || r->kind == N_NAME) && (r->name != e->name) &&
        (!r->name || !e->name || strcmp(r->name, e->name)))
        return 0;
    return e->nargs == 0 || memcmp(a->kids, kids, (size_t)e->nargs * sizeof *kids) == 0;
}

/* the number of e (its children numbered first) */
static int number(cse *s, const node *e)
{
    while (e->kind == N_FIX) { /* a quantity that only names another value is that value */
        const node *x = LVEC_AT(s->c->m.fixes, lang_formula, e->index).expr;
        if (x->nargs)
            break;
        e = x;
    }
    unsigned ph = ptr_hash(e) & (unsigned)(s->pcap - 1);
    while (s->pkey[ph]) {
        if (s->pkey[ph] == e)
            return s->pval[ph];
        ph = (ph + 1) & (unsigned)(s->pcap - 1);
    }
    LANG_WORK(s->c, e->pos);
    int *kids = e->nargs ? lang_alloc(s->c, (size_t)e->nargs * sizeof *kids) : NULL;
    for (int i = 0; i < e->nargs; i++)
        kids[i] = number(s, e->args[i]);
    uint64_t bits;
    memcpy(&bits, &e->num, sizeof bits);
    unsigned h = mix(mix(mix(mix(2166136261u, (uint64_t)e->kind), (uint64_t)(unsigned)e->op),
                         (uint64_t)(unsigned)e->index),
                     bits);
    for (int i = 0; i < e->nargs; i++)
        h = mix(h, (uint64_t)(unsigned)kids[i]);
    if (2 * (s->nent + 1) > s->tcap)
        grow_table(s);
    unsigned th = h & (unsigned)(s->tcap - 1);
    int id = -1;
    while (s->table[th] >= 0) {
        const cse_ent *a = &s->ent[s->table[th]];
        if (a->hash == h && same(a, e, kids)) {
            id = s->table[th];
            break;
        }
        th = (th + 1) & (unsigned)(s->tcap - 1);
    }
    if (id < 0) {
        if (s->nent == s->entcap) {
            const int cap = s->entcap ? 2 * s->entcap : 1 << 13;
            cse_ent *n = lang_alloc(s->c, (size_t)cap * sizeof *n);
            if (s->nent)
                memcpy(n, s->ent, (size_t)s->nent * sizeof *n);
            s->ent = n;
            s->entcap = cap;
        }
        id = s->nent++;
        s->ent[id] = (cse_ent){e, kids, h, 0, -1};
        s->table[th] = id;
    }
    /* the pointer table may have grown while the children were numbered */
    if (2 * (s->npkey + 1) > s->pcap)
        grow_ptr(s);
    ph = ptr_hash(e) & (unsigned)(s->pcap - 1);
    while (s->pkey[ph])
        ph = (ph + 1) & (unsigned)(s->pcap - 1);
    s->pkey[ph] = e;
    s->pval[ph] = id;
    s->npkey++;
    return id;
}

/* occurrences: a tree's children are counted when the tree is met for the first time */
static void count(cse *s, const node *e)
{
    if (e->nargs == 0)
        return;
    const int id = number(s, e);
    if (s->ent[id].uses++ == 0)
        for (int i = 0; i < e->nargs; i++)
            count(s, e->args[i]);
}

static void push_order(cse *s, int k)
{
    if (s->norder == s->ordercap) {
        const int cap = 2 * s->ordercap + 64;
        int *o = lang_alloc(s->c, (size_t)cap * sizeof *o);
        if (s->norder)
            memcpy(o, s->order, (size_t)s->norder * sizeof *o);
        s->order = o;
        s->ordercap = cap;
    }
    s->order[s->norder++] = k;
}

static node *fix_ref(cse *s, int k)
{
    node *r = lang_node(s->c, N_FIX, (lpos){0, 0});
    r->index = k;
    return r;
}

/* e with its shared subtrees replaced by their fixed quantities (new ones written into the
 * order before the quantity being rewritten) */
static node *rewrite(cse *s, const node *e)
{
    if (e->nargs == 0)
        return (node *)e;
    const int id = number(s, e);
    if (s->ent[id].fix >= 0)
        return fix_ref(s, s->ent[id].fix);
    node *r = lang_node(s->c, e->kind, e->pos);
    *r = *e;
    r->args = lang_alloc(s->c, (size_t)e->nargs * sizeof *r->args);
    for (int i = 0; i < e->nargs; i++)
        r->args[i] = rewrite(s, e->args[i]);
    if (s->ent[id].uses < 2)
        return r;
    lang_ctx *c = s->c;
    lang_formula *f = lvec_push(c, &c->m.fixes, sizeof *f);
    f->name = lang_printf(c, "mbs_cse%d", s->count++);
    f->pos = (lpos){0, 0};
    f->expr = r;
    const int k = c->m.fixes.n - 1;
    s->ent[id].fix = k;
    push_order(s, k);
    return fix_ref(s, k);
}

void mbs_cse(lang_ctx *c, mbs_model *mb, int nfix0)
{
    cse s;
    memset(&s, 0, sizeof s);
    s.c = c;
    grow_ptr(&s);
    grow_table(&s);
    const int first = nfix0; /* mb->order[0..first) are the file's own quantities */
    for (int i = first; i < mb->norder; i++)
        count(&s, LVEC_AT(c->m.fixes, lang_formula, mb->order[i]).expr);
    s.ordercap = mb->norder + 64;
    s.order = lang_alloc(c, (size_t)s.ordercap * sizeof *s.order);
    memcpy(s.order, mb->order, (size_t)first * sizeof *s.order);
    s.norder = first;
    for (int i = first; i < mb->norder; i++) {
        const int k = mb->order[i];
        node *e = LVEC_AT(c->m.fixes, lang_formula, k).expr, *r = e;
        if (e->nargs) {
            const int id = number(&s, e);
            if (s.ent[id].fix >= 0) {
                r = fix_ref(&s, s.ent[id].fix); /* the same formula as an earlier one */
            } else {
                node *t = lang_node(c, e->kind, e->pos);
                *t = *e;
                t->args = lang_alloc(c, (size_t)e->nargs * sizeof *t->args);
                for (int a = 0; a < e->nargs; a++)
                    t->args[a] = rewrite(&s, e->args[a]);
                s.ent[id].fix = k;
                r = t;
            }
        }
        LVEC_AT(c->m.fixes, lang_formula, k).expr = r;
        push_order(&s, k);
    }
    mb->order = s.order;
    mb->norder = s.norder;
    mb->ordercap = s.ordercap;
}
