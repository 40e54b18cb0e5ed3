/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interface of the .ode translator (src/lang): the translation context (an arena,
 * the error exit, notes), the expression tree, the model as read from the file, and the
 * passes: source lines (source.c), expressions (expr_parse.c), statements (ode_parse.c),
 * names and order (check.c), derivatives (deriv.c), C text (emit_c.c).
 *
 * Every allocation comes from the context's arena and is released at once at the end of
 * dyn_ode_to_c; an error or an exhausted memory leaves through lang_fail / lang_oom
 * (longjmp back to dyn_ode_to_c), so the passes never check for failure themselves.
 */
#ifndef DYNKIT_LANG_INTERNAL_H
#define DYNKIT_LANG_INTERNAL_H

#include <setjmp.h>
#include <stddef.h>
#include <stdio.h>

#include "dynkit/lang.h"

/* ---- limits (each refused with a message naming it) ---- */
#define LANG_MAX_TEXT (16u << 20)     /* bytes of a model file */
#define LANG_MAX_LINE 100000          /* characters of one logical line */
#define LANG_MAX_EXPANDED 200000      /* lines after the expansion of arrays */
#define LANG_MAX_RANGE 100000         /* elements of one array range [j1..j2] */
#define LANG_MAX_DEPTH 200            /* nesting of an expression */
#define LANG_MAX_SYMBOLS 200000       /* declared names */
#define LANG_MAX_ARGS 20              /* arguments of a user function (XPPAUT: 20) */
#define LANG_MAX_JAC_STATES 400       /* analytic Jacobian up to this many states */
#define LANG_MAX_INLINE 64            /* nesting of inlined calls in derivatives */
#define LANG_MAX_MEMORY ((size_t)1 << 29) /* bytes of the translator's own memory */
#define LANG_MAX_COPIES 500000        /* nodes copied by inlining function bodies */
#define LANG_MAX_OUTPUT ((size_t)1 << 28) /* bytes of C text */
#define LANG_MAX_WORK 100000000L /* visits of expression nodes (expanding calls, deriving,
                                  * writing C): 1 to 3 s */
#define LANG_MAX_TABLE 1000000            /* points of the lookup tables */
#define LANG_MAX_SUM_STACK 65536          /* doubles of the network sums' arrays (on the stack) */
#define LANG_MAX_ALG 100                  /* algebraic variables (a dense Newton system) */

typedef struct lpos {
    int line, col; /* 1-based; 0 when not tied to a place */
} lpos;

/* ---- growable arrays in the arena ---- */
typedef struct lvec {
    void *data;
    int n, cap;
} lvec;

/* ---- expression tree ---- */
typedef enum node_kind {
    N_NUM,    /* num */
    N_NAME,   /* unresolved name (after parsing) */
    N_TIME,   /* t */
    N_STATE,  /* y[index] */
    N_PARAM,  /* p[index] (parameters, then derived parameters) */
    N_FIX,    /* fixed temporary index */
    N_ARG,    /* argument index of the enclosing user function */
    N_NEG,    /* -a */
    N_NOT,    /* not a */
    N_BIN,    /* a op b */
    N_FUN,    /* built-in function op of args */
    N_UFUN,   /* user function index of args */
    N_IF,     /* if(a)then(b)else(c) */
    N_DFIX,   /* derivative of fixed temporary index with respect to state op (a local) */
    N_UFUN_D, /* partial derivative op (argument) of user function index, of args */
    N_SUM,    /* sum(a,b)of(c): unrolled by check.c before names are resolved */
    N_SUMIDX, /* i', the index of a sum */
    N_ALG,    /* algebraic variable index (solved from the 0= equations) */
    N_NOISE,  /* noise slot index (lang_noise): held over a step, written by the solver */
    N_DELAY,  /* delay(x, lag): state index (name: as written) at t - args[0] */
    N_VOLT    /* the value of Volterra integral index (lang_volt), written by the solver;
               * index -1 inside an integrand: the time t of the integral (t' is N_TIME) */
} node_kind;

typedef enum bin_op {
    OP_ADD, OP_SUB, OP_OR,                   /* XPPAUT priority 4 */
    OP_MUL, OP_DIV, OP_AND,                  /* priority 6 (also unary minus and not) */
    OP_POW, OP_GT, OP_LT, OP_GE, OP_LE, OP_EQ, OP_NE /* priority 7 */
} bin_op;

typedef enum fun_id {
    F_SIN, F_COS, F_TAN, F_ASIN, F_ACOS, F_ATAN, F_ATAN2, F_SINH, F_COSH, F_TANH, F_EXP,
    F_LN, F_LOG10, F_SQRT, F_ABS, F_HEAV, F_SIGN, F_MOD, F_FLR, F_CEIL, F_MAX, F_MIN, F_ERF,
    F_ERFC, F_COUNT,
    /* not names of the language: a table's value and slope at its argument (index: the
     * table) */
    F_TABLE, F_TABLE_SLOPE,
    F_SPECIAL /* element args[0] (a whole number) of the network sum index */
} fun_id;

typedef struct node {
    node_kind kind;
    int op;           /* bin_op, fun_id, or the state of N_DFIX / argument of N_UFUN_D */
    double num;
    int index;
    int nargs;
    struct node **args;
    const char *name; /* as written (N_NAME, N_FUN, N_UFUN) */
    lpos pos;
    int paren;        /* written inside parentheses */
} node;

/* ---- the model as read from the file ---- */
typedef struct lang_doc {
    const char *unit;        /* NULL: not given */
    const char *description; /* NULL: not given */
} lang_doc;

typedef struct lang_state {
    const char *name;
    lpos pos;
    node *rhs;
    node *init;  /* NULL: 0 */
    lpos init_pos;
    node *history; /* a delay model's x(0)= formula (of t): the state before t0; NULL: 0
                    * (XPPAUT 6.11 reads 0 before t0 when only `init` gives a value) */
    int is_int;    /* an integral equation x(t) = rhs (volt, integrals.c), not x' = rhs */
    lang_doc doc;
} lang_state;

typedef struct lang_param {
    const char *name;
    lpos pos;
    double value;
    lang_doc doc;
} lang_param;

typedef struct lang_formula { /* derived parameter, fixed temporary, aux output */
    const char *name;
    lpos pos;
    node *expr;
    lang_doc doc;
    int mark;                 /* scratch of the ordering passes */
} lang_formula;

typedef struct lang_func {
    const char *name;
    lpos pos;
    int nargs;
    const char **argnames;
    node *body;
    int mark;
    int uses_state, uses_time; /* directly or through other functions */
    int uses_fix;              /* reads fixed temporaries (or algebraic variables): given
                                * them as arguments after its own (check.c) */
    int uses_table;            /* calls a table (directly or through other functions; set by
                                * lang_check's passes over the functions) */
} lang_func;

typedef struct lang_assign {
    const char *name;
    lpos pos;
    int state;
    node *value;
} lang_assign;

typedef struct lang_event {
    const char *name;
    const char *description;
    lpos pos;
    int direction; /* +1 rising, -1 falling, 0 both */
    int terminal;
    node *cond;
    int nassign;   /* > 0: a global with a reset */
    lang_assign *assign;
    int is_global;
} lang_event;

/* A lookup table (XPPAUT's `table`): npts values at x = lo + k (hi - lo) / (npts - 1),
 * from a formula of t (expr, computed with the parameters by prepare) or from a file
 * (values); a function of one argument by linear interpolation, extrapolated linearly
 * beyond [lo, hi] as XPPAUT does. Its values live in the parameter array from offset on. */
typedef struct lang_table {
    const char *name;
    lpos pos;
    long npts;
    double lo, hi;
    node *expr;           /* formula of t, or NULL */
    const double *values; /* (npts) from the file, or NULL */
    const char *file;     /* as written */
    int offset;           /* index of the first value in p (set by lang_check) */
} lang_table;

/* A network sum (XPPAUT's `special NAME=conv(type,n,m,w,root)`): NAME(j), j = 0..n-1, is
 * sum_{i=-m..m} w[m+i] u(j+i), u the block of n states or fixed quantities from root on,
 * beyond its ends 0 (type 0), mirrored (even) or wrapped (periodic); w a table of 2m+1
 * points. fconv(type,n,m,w,root,vroot,f) sums w[m+i] f(u(j+i), v(j)) instead, f a user
 * function of two arguments, v the block from vroot on. mmult(m,n,w,u): NAME(j) =
 * sum_{i<m} w[i+m j] u(i); sparse(n,m,w,l,u): NAME(j) = sum_{i<m} w[j m+i] u(l[j m+i]), l a
 * table of indices into the states from u on. Computed after the fixed quantities of each
 * function that uses it. */
enum { LANG_CONV_ZERO, LANG_CONV_EVEN, LANG_CONV_PERIODIC };
enum { LANG_SUM_CONV, LANG_SUM_FCONV, LANG_SUM_MMULT, LANG_SUM_SPARSE, LANG_SUM_GILL };
typedef struct lang_special {
    const char *name;
    lpos pos;
    int kind;      /* LANG_SUM_* */
    int type, n, m;
    int ulen;      /* elements of u's block: n (conv), m (mmult), the states from u (sparse) */
    const char *table_name, *root_name;
    lpos table_pos, root_pos;
    int table;     /* resolved by lang_check */
    int root_kind; /* N_STATE or N_FIX */
    int root;      /* index of the block's first element */
    /* fconv: v's block and f (vroot_name NULL for conv) */
    const char *vroot_name, *func_name;
    lpos vroot_pos, func_pos;
    int vroot_kind, vroot, func;
    /* sparse: the table of indices */
    const char *index_name;
    lpos index_pos;
    int index_table;
    /* gill (markov.c): the m = ulen reaction rates are the fixed quantities from root on,
     * NAME(0) the waiting time and NAME(1..m) the reaction that happened (n = m + 1), drawn
     * from the uniform noise slots slot and slot + 1 */
    int slot;
} lang_special;

/* A Markov state (XPPAUT's `markov NAME N`, then N rows of N {formula}; markov.c): a state
 * whose value is one of 0 .. n-1, held over a step (derivative 0; a map keeps it), which
 * jumps at the start of each step (dyn_model.jump) by the rates of its row. rate[i n + j]
 * is the fixed quantity, without a name, of the rate from i to j (-1 on the diagonal). */
typedef struct lang_markov {
    const char *name;
    lpos pos;
    int n;
    int *rate;
    int rows;  /* rows read so far */
    int state; /* its index among the states, and its uniform noise slot (lang_markov_finish) */
    int slot;
} lang_markov;

/* A noise slot (dynkit/sde.h): a `wiener NAME` (kind DYN_NOISE_WIENER), or one call of
 * normal(m, s) (DYN_NOISE_NORMAL, read as m + s*slot) or ran(x) (DYN_NOISE_UNIFORM,
 * x*slot). Their values follow the rest of the parameter array. */
/* A Volterra integral (XPPAUT's int{...}, int[mu]{K#u}; integrals.c): its value at t is
 * int_t0^t (t-t')^-mu K(t-t') g(t, t') dt', K = 1 without '#'. In g, t' is N_TIME and t is
 * N_VOLT -1; states and fixed quantities are read at t'. */
typedef struct lang_volt {
    lpos pos;
    double mu;
    node *kernel;    /* K, a formula of the lag t and the parameters, or NULL */
    node *integrand; /* g */
} lang_volt;

typedef struct lang_noise {
    const char *name; /* the wiener's name, or "normal" / "ran" */
    lpos pos;
    int kind;
} lang_noise;

/* A pending `init name=...` or `name(0)=...`, resolved once every state is known. */
typedef struct lang_init {
    const char *name;
    lpos pos;
    node *value;
    int x0; /* written x(0)= (a delay model's history too), not init */
} lang_init;

/* A pending `#: NAME [UNIT] text` line. */
typedef struct lang_docline {
    const char *name;
    lpos pos;
    lang_doc doc;
} lang_docline;

typedef enum sym_kind {
    SYM_NONE,
    SYM_STATE,
    SYM_PARAM,
    SYM_NUMBER,
    SYM_DERIVED,
    SYM_FIX,
    SYM_AUX,
    SYM_FUNC,
    SYM_TABLE,
    SYM_SPECIAL,
    SYM_ALG,
    SYM_NOISE,
    SYM_VOLT,
    SYM_RESERVED
} sym_kind;

typedef struct lang_sym {
    const char *key; /* case folded */
    sym_kind kind;
    int index;
    lpos pos;
} lang_sym;

typedef struct lang_model {
    lvec states;   /* lang_state */
    lvec params;   /* lang_param */
    lvec numbers;  /* lang_param (constants) */
    lvec derived;  /* lang_formula */
    lvec fixes;    /* lang_formula */
    lvec auxs;     /* lang_formula */
    lvec funcs;    /* lang_func */
    lvec events;   /* lang_event */
    lvec tables;   /* lang_table */
    lvec specials; /* lang_special */
    /* differential-algebraic systems (XPPAUT's `solv NAME=guess` and `0=expr`): the
     * algebraic variables (expr: the initial guess, a formula of the parameters, or NULL
     * for 0) and the equations that determine them, as many of each */
    lvec algs;     /* lang_formula */
    lvec algeqs;   /* lang_formula (name: NULL) */
    lvec inits;    /* lang_init */
    lvec noises;   /* lang_noise */
    lvec markovs;  /* lang_markov */
    int noise_class; /* dyn_noise_class of the right-hand side (noise.c) */
    lvec docs;     /* lang_docline */
    /* symbol table: open addressing on the case-folded name */
    lang_sym *syms;
    int nsyms, symcap;
    /* orders computed by check.c */
    int *fix_order;     /* fixes in dependency order */
    int *derived_order; /* derived parameters in dependency order */
    /* text */
    const char *name, *title, *description;
    /* options */
    double t0, total, dt, rtol, atol, bound, trans;
    long nout;
    lpos nout_pos;
    const char *method;
    int has_meth;
    int meth_every_dt;       /* XPPAUT ignores nout with this meth (see ode_parse.c) */
    const char *meth_name;   /* meth's value as written */
    const char *xp, *yp;
    lpos xp_pos, yp_pos;
    /* XPPAUT's Poincaré map (@ poimap, poivar, poipln, poisgn, poistop; dyn_poincare) */
    int poimap, poisgn, poistop;
    const char *poivar;
    lpos poivar_pos, poimap_pos;
    double poipln;
    /* @ xlo, xhi, ylo, yhi (window: all four 0 when none given), and `#: t [UNIT]` */
    double window[4];
    const char *time_unit;
    /* the band of the Jacobian (XPPAUT's @ bandlo, bandup): has_band when either is given */
    int has_band, band_lo, band_up;
    lpos band_pos;
    /* the band was found in the exact Jacobian's pattern, not declared (emit_c.c) */
    int band_found;
    /* a discrete map: an x(t+1)= equation (map_eq) or meth=discrete (map_meth), at map_pos;
     * dt_pos: where dt was given (a map steps by 1, as XPPAUT's do) */
    int map_eq, map_meth;
    lpos map_pos, dt_pos, total_pos;
    /* no analytic Jacobian is written (the stiff methods use differences): set by front
     * ends whose right-hand sides are long chains of fixed quantities (src/mbs) */
    int no_jacobian;
    /* inputs: parameters that a time table attached by set_input overrides (dyn_model.inputs;
     * src/mbs's `input` lines): n_inputs of them, input_param[k] the parameter of input k,
     * param_input[i] the input of parameter i or -1 (NULL when there are none) */
    int n_inputs;
    int *input_param, *param_input;
    /* delay equations: delay(x, lag) calls read (n_delays), @ delay= (max_delay, 0: not
     * given) */
    int n_delays;
    /* random numbers of the tables' formulas (ran(), normal()), drawn once in prepare */
    int n_table_draws;
    double max_delay;
    int max_delay_given; /* an @ delay= line (delay=0 among them) */
    /* Volterra integrals (integrals.c): lang_volt, and @ vmaxpts (0: not given) */
    lvec volts;
    long vmaxpts;
    /* XPPAUT's boundary conditions (bdry.c): lang_formula, name the condition as written;
     * bdry_hom: int per condition, k for XPPAUT's hom_bcs(k) (its expression the number 0,
     * the projection written by the solver), -1 for any other condition */
    lvec bdrys;
    lvec bdry_hom;
    /* AUTO's settings of the @ lines (ntst, ds, parmax, autoxmin, ...): lang_auto_option,
     * in the file's order; a run does not use them, dynkit continue reads them
     * (dyn_ode_auto_options) */
    lvec auto_opts;
} lang_model;

/* one AUTO setting of an @ line: its name in lower case (ode_parse.c's list), the value as
 * written, where the value is */
typedef struct lang_auto_option {
    const char *name;
    const char *value;
    lpos pos;
} lang_auto_option;

/* ---- one logical line: text and where each character came from ---- */
typedef struct lang_line {
    char *text;
    int len;
    lpos *pos; /* len + 1 entries (the last one: end of line) */
} lang_line;

/* ---- the context ---- */
typedef struct lang_block lang_block;
struct lang_lexer;

typedef struct lang_ctx {
    jmp_buf *fail;        /* where lang_fail and lang_oom go */
    int status;           /* 2 error in the file, 1 out of memory */
    lang_block *blocks;
    const char *path;
    const char *text;
    size_t len;
    size_t *line_start;   /* offsets of physical lines */
    int nlines;
    dyn_lang_diag *diag;
    dyn_lang_note_fn note;
    void *note_ctx;
    lang_model m;
    int depth;            /* recursion guard of the parser and the derivative */
    size_t bytes;         /* memory taken by the arena */
    long copies;          /* nodes copied by lang_subst */
    long work;            /* nodes visited (LANG_WORK) */
    struct node *zero, *one; /* shared constants of the derivatives (never changed) */
    unsigned helpers;     /* emit_c.c: the dk_ helpers the C text uses */
    unsigned char *fused; /* emit_c.c: user functions (and partials) the C text calls */
    char *out;            /* the C text being written (malloc'd; freed on failure) */
    size_t out_len, out_cap;
    const dyn_lang_table_file *table_files; /* named by the caller (dyn_ode_to_c_tables) */
    int n_table_files;
    unsigned char *table_file_used;
    /* A front end's own statements (src/mbs): called with the lexer after the first word w
     * of a statement that is not an equation; returns 0 (handled, the line is done), 1
     * (handled, the file is done) or -1 (not its statement: read it as .ode). */
    int (*stmt_hook)(struct lang_ctx *c, struct lang_lexer *lx, const char *w, lpos wpos);
    void *hook_ctx;
    int no_arrays; /* lines are not expanded as arrays: [ ] holds units (src/mbs) */
    int in_bdry;   /* parsing a bdry line: NAME' is the state NAME at the right end */
} lang_ctx;

/* arena, errors, notes (diag.c) */
void *lang_alloc(lang_ctx *c, size_t n);
char *lang_strndup(lang_ctx *c, const char *s, size_t n);
char *lang_strdup(lang_ctx *c, const char *s);
char *lang_printf(lang_ctx *c, const char *fmt, ...);
void lang_free_all(lang_ctx *c);
_Noreturn void lang_oom(lang_ctx *c);
_Noreturn void lang_fail(lang_ctx *c, lpos p, const char *fmt, ...);
void lang_note(lang_ctx *c, lpos p, const char *fmt, ...);
/* A note that is a warning (DYN_LANG_WARNING): the file's line was left out. */
void lang_warn(lang_ctx *c, lpos p, const char *fmt, ...);
void *lvec_push(lang_ctx *c, lvec *v, size_t elem);
/* One more visit of an expression node at p; past LANG_MAX_WORK the translation stops with
 * a message naming the bound. */
_Noreturn void lang_work_exceeded(lang_ctx *c, lpos p);
#define LANG_WORK(c, p)                                                                      \
    do {                                                                                     \
        if (++(c)->work > LANG_MAX_WORK)                                                     \
            lang_work_exceeded((c), (p));                                                    \
    } while (0)
#define LVEC_AT(v, type, i) (((type *)(v).data)[i])

/* table files (table_file.c): the file of `table NAME FILE` opened for reading, where
 * the rules allow (a regular file beside the model file or named by the caller), else
 * lang_fail naming what is accepted; *shown is the path opened, for messages. Then
 * lang_check_table_files fails when a file was named for a table the model does not read
 * from a file. */
FILE *lang_open_table_file(lang_ctx *c, const char *table, const char *file, lpos pos,
                           const char **shown);
void lang_check_table_files(lang_ctx *c);

/* the symbol table (symbols.c) */
void lang_fold(char *dst, const char *src, size_t size);
int lang_same_name(const char *a, const char *b); /* 1: one name, case ignored */
lang_sym *lang_lookup(lang_ctx *c, const char *name);
void lang_declare(lang_ctx *c, const char *name, lpos pos, sym_kind kind, int index);
const char *lang_sym_kind_name(sym_kind k);

/* names (check.c; lang_is_reserved: expr_parse.c) */
int lang_is_reserved(const char *name);
void lang_check(lang_ctx *c);
/* Flags in used (one per algebraic variable) for those e reads, directly or through fixed
 * quantities and functions; fix_seen and fun_seen (zeroed, one per fixed quantity and
 * function) mark what was visited. */
void lang_alg_uses(lang_ctx *c, const node *e, unsigned char *used, unsigned char *fix_seen,
                   unsigned char *fun_seen);

/* source lines (source.c): the text as logical lines with continuation joined and arrays
 * expanded; calls fn for each line in order (stops when fn returns non-zero). */
typedef int (*lang_line_fn)(lang_ctx *c, const lang_line *line, void *ctx);
void lang_lines(lang_ctx *c, lang_line_fn fn, void *ctx);
/* A line being written character by character, each with the place it came from (arena
 * memory; refused past 4 LANG_MAX_LINE): lang_lbuf_put appends one and keeps the text
 * NUL-terminated with room for one more place (the line's end). {0} is empty. */
typedef struct lang_lbuf {
    char *text;
    lpos *pos;
    int len, cap;
} lang_lbuf;
void lang_lbuf_put(lang_ctx *c, lang_lbuf *b, char ch, lpos p);
/* XPPAUT's first format (ode_old.c): when the first line is a positive number, the file's
 * lines rewritten as statements of the current format, each given to fn; returns 1, or 0
 * (nothing read) when the file is in the current format. */
int lang_old_format(lang_ctx *c, lang_line_fn fn, void *ctx);

/* expressions (expr_parse.c) */
typedef struct lang_lexer {
    lang_ctx *c;
    const lang_line *line;
    int i, end; /* current offset, end offset (exclusive) in line->text */
} lang_lexer;
node *lang_parse_expr(lang_lexer *lx);  /* one expression; stops before , ; } { or the end */
int lang_skip_blanks(lang_lexer *lx);   /* returns the next character or 0 at the end */
/* a name at the cursor (after blanks), its place in pos; else fails: WHAT, found ... */
const char *lang_read_name(lang_lexer *lx, lpos *pos, const char *what);
void lang_expect_char(lang_lexer *lx, int ch, const char *what); /* else fails: WHAT, found ... */
void lang_expect_end(lang_lexer *lx, const char *after); /* nothing but blanks left, else fails */
lpos lang_here(const lang_lexer *lx);
node *lang_node(lang_ctx *c, node_kind kind, lpos pos);
int lang_fun_lookup(const char *name, int *arity);
/* Resolve the call e (N_FUN) to a built-in function (sets e->op) or a user function (makes
 * it N_UFUN), checking the number of arguments; a name that is another kind of symbol
 * fails. Returns 0 when the name is not known at all (the caller reports it). */
int lang_resolve_call(lang_ctx *c, node *e);
const char *lang_fun_name(int f);
const char *lang_op_text(int op);
int lang_op_priority(int op);
int lang_is_ident_start(int ch);
int lang_is_ident_char(int ch);

/* statements (ode_parse.c) */
void lang_parse_model(lang_ctx *c);
/* 1 when w is a keyword of an .ode statement (par, aux, table, ...), case folded */
int lang_is_statement_keyword(const char *w);

/* noise (noise.c): what the right-hand side does with its Wiener slots, into
 * c->m.noise_class (dyn_noise_class, dynkit/sde.h) */
void lang_noise_classify(lang_ctx *c);
/* The default method of a model with noise: the file's meth=euler (Euler–Maruyama), else
 * rkmil when noise_class allows it, else euler; a note when the file's meth is another. */
const char *lang_noise_method(lang_ctx *c);

/* Markov states and Gillespie's method (markov.c): `markov NAME N` (the lexer after the
 * keyword), then each of the N rows as the next lines come (lang_markov_row: 1 when it took
 * the line as a row); lang_markov_finish, once the file is read, makes the chains states
 * (after the equations', as XPPAUT orders them) with their noise slots; `special
 * NAME=gill(0, r1, ..., rm)` (the lexer after '('); lang_emit_jump writes dk_jump (noise:
 * the index in p of the first noise slot; fixes: the emitter's writer of the fixed
 * quantities and sums that the n roots need, as the locals v_K and sp_K of the function
 * being written), lang_emit_gill the gill sum i into sp_I. */
void lang_markov_parse(lang_ctx *c, lang_lexer *lx, lpos kpos);
int lang_markov_row(lang_ctx *c, lang_lexer *lx);
void lang_markov_finish(lang_ctx *c);
void lang_gill_parse(lang_ctx *c, lang_lexer *lx, const char *name, lpos npos, lpos kpos);
void lang_emit_jump(lang_ctx *c, int noise, void (*fixes)(lang_ctx *, node *const *, int));
void lang_emit_gill(lang_ctx *c, int i, const lang_special *sp, int noise);

/* derivatives and simplification (deriv.c) */
typedef struct lang_dvar {
    int kind; /* N_STATE, N_ARG or N_ALG */
    int index;
    node **fixd;            /* N_STATE, N_ALG: derivatives of the fixed temporaries (NULL: zero) */
    unsigned char *used;    /* funcs * LANG_MAX_ARGS flags: partial derivatives used */
    int inline_depth;
} lang_dvar;
node *lang_num(lang_ctx *c, double v);
node *lang_deriv(lang_ctx *c, const node *e, const lang_dvar *v);
node *lang_subst(lang_ctx *c, node *body, node **args);
/* the simplifying constructors of the derivatives (0*x, 1*x, x+0, constant folding) */
node *lang_add(lang_ctx *c, node *a, node *b);
node *lang_sub(lang_ctx *c, node *a, node *b);
node *lang_mul(lang_ctx *c, node *a, node *b);
node *lang_div(lang_ctx *c, node *a, node *b);
node *lang_neg(lang_ctx *c, node *a);
node *lang_fun1(lang_ctx *c, int f, node *a);
int lang_is_num(const node *e, double v);
void lang_func_uses(lang_ctx *c, const node *e, int *state, int *time);
double lang_eval(lang_ctx *c, const node *e, const double *args, const double *pvals);
/* One frame of a model for lang_eval_frame (frame_eval.c): N_STATE reads y, N_PARAM params
 * (parameters, then derived parameters), N_FIX fix, N_TIME t, and N_ARG outside a function's
 * body the outputs; a missing array reads NaN. */
typedef struct lang_frame {
    const lang_model *m;
    double t;
    const double *y, *outputs, *params, *fix;
    int depth;
} lang_frame;
/* args: the arguments of the function whose body e belongs to, or NULL in a formula of the
 * model (then N_ARG k is the k-th output). Never fails: too deep a formula gives NaN. */
double lang_eval_frame(lang_frame *f, const node *e, const double *args);
/* XPPAUT's binary operator op (bin_op) and built-in function op (fun_id; b is the second
 * argument or 0) applied to numbers, as the C text gives them (eval_ops.c). */
double lang_apply_bin(int op, double a, double b);
double lang_apply_fun(int op, double a, double b);

/* C text (emit_c.c); the solver of the algebraic equations, a constant text (alg_solver.c) */
char *lang_emit_c(lang_ctx *c);
/* A translation from the text of a model file to C (translate.c): the context, the error
 * exit and the C text around front, which reads the file into c->m and checks it (the .ode
 * front end: lang_parse_model then lang_check); back writes the text instead of the C
 * (NULL: lang_emit_c), malloc'd. */
int lang_translate(const char *path, const char *text, size_t len,
                   const dyn_lang_table_file *tables, int n_tables, char **c_source,
                   dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx,
                   void (*front)(lang_ctx *c), char *(*back)(lang_ctx *c));
/* lang_translate with c->hook_ctx = front_ctx when front runs */
int lang_translate_with(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, char **c_source,
                        dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx,
                        void (*front)(lang_ctx *c), char *(*back)(lang_ctx *c),
                        void *front_ctx);
/* The .ode front end: the model's name from its path, lang_parse_model, the table files
 * checked, lang_check (translate.c) */
void lang_ode_front(lang_ctx *c);
/* The default name of a model from its path: the file name without the extension ext. */
const char *lang_base_name(lang_ctx *c, const char *path, const char *ext);
/* A context for the text of a file (calloc'd; NULL when out of memory): release with
 * lang_ctx_free (translate.c) */
lang_ctx *lang_ctx_new(const char *path, const char *text, size_t len,
                       const dyn_lang_table_file *tables, int n_tables, dyn_lang_diag *diag);
/* c's arena, c and the object that holds it (owner, may be NULL) freed; c may be NULL */
void lang_ctx_free(lang_ctx *c, void *owner);
/* The lines of c->text (c->path) indexed, then front(c), then the model's title and
 * description completed (translate.c); fails through c->fail as every pass. */
void lang_run_front(lang_ctx *c, void (*front)(lang_ctx *c));
const char *lang_alg_solver_text(void);

/* The C text's only writer (emit_out.c, where the rule is written): bytes from outside only
 * through lang_c_str, as an escaped string literal; code only from string literals of the
 * translator (LANG_C_CODE) and formats that convert numbers (LANG_C_CODEF; %s, %c, %p, %n
 * are refused). lang_c_take moves the text written so far out (the output starts empty),
 * lang_c_splice appends such a text again; lang_c_solver appends alg_solver.c's text. */
typedef struct lang_ctext {
    const char *text;
    size_t len;
} lang_ctext;
void lang_c_code_(lang_ctx *c, const char *literal, size_t n);
#define LANG_C_CODE(c, lit) lang_c_code_((c), "" lit "", sizeof("" lit "") - 1)
__attribute__((format(printf, 2, 3))) void lang_c_codef_(lang_ctx *c, const char *fmt, ...);
#define LANG_C_CODEF(c, ...) lang_c_codef_((c), __VA_ARGS__)
void lang_c_str(lang_ctx *c, const char *s);
void lang_c_num(lang_ctx *c, double v);
lang_ctext lang_c_take(lang_ctx *c);
void lang_c_discard(lang_ctx *c); /* the text written so far is dropped */
void lang_c_splice(lang_ctx *c, lang_ctext t);
void lang_c_solver(lang_ctx *c);

/* delay models (emit_delay.c): the helpers dk_hist and dk_delay (history pointer in p at
 * offset), the guard at the start of a function that returns a status (no history
 * attached), prepare's check of the constant lags against @ delay=, and the
 * dyn_delay_model dk_delay_model (expr writes a formula of t and p) */
/* Volterra integrals (integrals.c): the integrals of a logical line read into c->m.volts and
 * replaced in its text by names of their own; the integrands' names resolved (check.c);
 * the C of the integrands, the kernels and the dyn_volterra_model (emit_c.c), whose slots
 * in p start at offset (one per integral, then the integrands' time t). */
void lang_volt_line(lang_ctx *c, const lang_line *l);
int lang_volt_is_int_formula(lang_ctx *c, const lang_line *l, int from);
int lang_volt_model(const lang_model *m); /* has integrals or integral equations */
void lang_volt_finish(lang_ctx *c);       /* after the statements: the method */
void lang_volt_resolve(lang_ctx *c, void (*resolve)(lang_ctx *, node *, int kernel));
void lang_emit_volterra(lang_ctx *c, int offset, void (*expr)(lang_ctx *, const node *),
                        void (*fixes)(lang_ctx *, node *const *, int));
/* boundary conditions (bdry.c): a bdry line read; after its names are resolved, the
 * right end's states moved to indices n..2n-1 (checked); the C function dk_bdry and the
 * conditions' texts dk_bdry_text */
void lang_bdry_parse(lang_ctx *c, lang_lexer *lx, lpos wpos);
void lang_bdry_resolved(lang_ctx *c, lang_formula *f);
void lang_emit_bdry(lang_ctx *c, void (*expr)(lang_ctx *, const node *));
int lang_bdry_has_hom(const lang_model *m); /* a hom_bcs condition among them: dk_hom */
void lang_emit_delay_helper(lang_ctx *c, int offset);
void lang_emit_delay_guard(lang_ctx *c);
void lang_emit_delay_prepare(lang_ctx *c, void (*expr)(lang_ctx *, const node *));
void lang_emit_delay_model(lang_ctx *c, int offset, void (*expr)(lang_ctx *, const node *));

#endif /* DYNKIT_LANG_INTERNAL_H */
