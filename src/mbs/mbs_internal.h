/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interface of the mechanism front end (src/mbs): a mechanism file read into
 * coordinates, bodies, loads and constraints on top of src/lang's model (statements of
 * mbs_parse.c), then the equations of motion by TMT (mbs_derive.c) written into that model
 * as fixed quantities, so that src/lang's checks and C text do the rest. See
 * docs/mechanisms.md for the file's syntax and the method's equations. */
#ifndef DYNKIT_MBS_INTERNAL_H
#define DYNKIT_MBS_INTERNAL_H

#include "lang/lang_internal.h"

#define MBS_MAX_ROT 12 /* elementary rotations of one body */
#define MBS_MAX_CHAIN 24 /* elementary rotations of a body and its parents' joints */
#define MBS_DEFAULT_ALPHA 10.0 /* Baumgarte's rate [1/s] unless `stabilize` says */

/* An input is an expression of the file, kept as a fixed quantity of the model (not a
 * name of the file) so that lang_check resolves it; -1: none (zero). */
typedef struct mbs_coord {
    const char *name, *speed, *unit;
    lpos pos;
    int q, u; /* state indices of the coordinate and its speed */
    lpos speed_pos;
    node *speed_init;
    lang_doc speed_doc;
    int kin;      /* input: q' as a formula of the speeds (`rate` line), -1: q' = its speed */
    lpos kin_pos;
    int jointed;  /* the body whose joint it moves, plus 1 (0: none) */
} mbs_coord;

/* A speed declared by `speeds` (a generalized speed other than a coordinate's rate) */
typedef struct mbs_speed {
    const char *name;
    lpos pos;
    node *init;
    lang_doc doc;
} mbs_speed;

enum { MBS_NO_JOINT, MBS_REVOLUTE, MBS_PRISMATIC, MBS_SPHERICAL, MBS_FREE };

typedef struct mbs_body {
    const char *name;
    lpos pos;
    int point;          /* a point mass: no inertia, no orientation */
    int mass;           /* input */
    int inertia[6];     /* inputs: Ixx, Iyy, Izz, Ixy, Ixz, Iyz about the mass centre in B, or
                         * about the point `about` */
    int about[3];       /* inputs: the point of B (from the mass centre) the inertia is
                         * given about (inertia=(...) about (x, y, z) | pivot), -1: the
                         * mass centre */
    lpos about_pos;
    int at[3];          /* inputs: the mass centre in N */
    int nrot;
    int axis[MBS_MAX_ROT];  /* 0 x, 1 y, 2 z, 3 a joint's axis axisv */
    int angle[MBS_MAX_ROT]; /* inputs */
    int quat[4];        /* inputs: Euler parameters (w, x, y, z) in place of rotations, or -1 */
    /* a joint to a parent (mbs_joint.c): the rotations above are the joint's own, from the
     * parent's frame to the body's; the mass centre is the parent's, plus the joint's
     * point jp and the translation shift (in the parent's frame), minus the pivot (the
     * joint's point in the body's frame) */
    int joint;          /* MBS_NO_JOINT: placed by at (x, y, z) rot ... */
    int parent;         /* -1: the ground */
    int jp[3], shift[3], pivot[3]; /* inputs, -1: 0 */
    int axisv[3];       /* inputs: the axis (ax, ay, az) of a rotation with axis 3 */
    int slide, slide_axis; /* a prismatic joint's displacement (input) and axis (0-3) */
    int frame;          /* 1: it has a frame B (rigid bodies; points placed by a rotating joint) */
    /* derived (mbs_derive.c) */
    node *x[3], *R[9];  /* symbolic: position, N->B rotation */
    node *Rf[9];        /* R as fixed quantities */
    node **Jv, **Jw;    /* (3 n) fixed quantities: column k at 3 k */
    double *Jv0, *Jw0;  /* (3 n) their values at the initial state */
    node *v[3], *w[3], *gv[3], *gw[3];
    node **Jws, *ws[3]; /* symbolic J_w and w (before they are fixed), for the children */
    /* the elementary rotations from N to B, the parent's chain and the joint's (-1: not
     * elementary rotations only), so that a child's R is a product of elementary
     * rotations rather than of the parent's matrix; chained: the parent's are among them */
    int cn, chained;
    int caxis[MBS_MAX_CHAIN];
    node *cangle[MBS_MAX_CHAIN];
    node *vs[3];        /* v as formulas of the states (before it is fixed), for wheels */
} mbs_body;

typedef struct mbs_attach {
    int body; /* -1: the ground */
    int p[3]; /* inputs: the point in the body frame (in N for the ground) */
} mbs_attach;

typedef struct mbs_spring {
    const char *name;
    lpos pos;
    mbs_attach a, b;
    int k, l0, c; /* inputs */
    /* law=F: the tension F(x, v) of the stretch x = l - l0 and its rate v, a function of the
     * file; energy=G: its integral G(x), added to the potential. Names as written, then the
     * functions' indices (-1: none) */
    const char *law_name, *energy_name;
    lpos law_pos, energy_pos;
    int law, energy;
} mbs_spring;

typedef struct mbs_load {
    const char *name;
    lpos pos;
    int body, torque, in_body;
    int at[3], f[3]; /* inputs */
} mbs_load;

typedef struct mbs_constraint {
    const char *name, *unit;
    lpos pos;
    int expr;       /* input: expression = 0 */
    int prescribed; /* coordinate index (prescribe), or -1 */
    int aux;        /* index of its multiplier among the outputs */
    int wheel, part; /* a wheel's contact (mbs_wheel.c): its index and 0 x, 1 y, 2 z; or -1 */
    node *sym;      /* its expression when derived (a wheel's), else NULL: the input */
} mbs_constraint;

/* wheel NAME on BODY radius=R axis=(x, y, z) [at (x, y, z)]: a thin disk rolling without
 * slip on the ground z = 0 (mbs_wheel.c) */
typedef struct mbs_wheel {
    const char *name;
    lpos pos;
    int body;
    int radius, axis[3], at[3]; /* inputs; the axis and the centre in the body's frame */
} mbs_wheel;

/* A shape to draw (mbs_geom.c): kind a dyn_mech_shape_kind */
typedef struct mbs_shape {
    int kind;
    const char *name, *color; /* color: "#rrggbb" or NULL */
    lpos pos;
    mbs_attach a, b; /* a: its body and point (at); b: a rod's other end */
    int v[3];        /* inputs (-1: none): sizes, or an arrow's direction, or a normal */
    int size;        /* input (-1: none): a frame's or the ground's size */
    int axis;        /* a cylinder's axis 0..2 */
    int in_body;     /* an arrow's direction in the body's frame */
    int con;         /* an arrow's constraint */
    int avec[3];     /* inputs (-1: none): a cylinder's axis as a vector of the body's frame */
    int wheel;       /* a wheel's disk, or an arrow at its contact point (-1: none) */
} mbs_shape;

typedef struct mbs_named {
    const char *name;
    lpos pos;
} mbs_named;

typedef struct mbs_model {
    lvec coords;  /* mbs_coord */
    lvec bodies;  /* mbs_body */
    lvec springs; /* mbs_spring */
    lvec loads;   /* mbs_load */
    lvec cons;    /* mbs_constraint */
    lvec wheels;  /* mbs_wheel */
    int gravity[3];
    double alpha; /* Baumgarte's rate [1/s] of the holonomic constraints */
    int aux_kinetic, aux_potential, aux_energy; /* output indices, -1: not written */
    int ninputs;
    lvec input_names; /* mbs_named: parameters a table of inputs overrides (`input`) */
    lvec speeds;      /* mbs_speed: generalized speeds of a `speeds` line (none: the rates) */
    lvec shapes;      /* mbs_shape: geometry to draw (mbs_geom.c) */
    node **expanded; /* expanded inputs, by fixed quantity (mbs_derive.c) */
    int *order;      /* the order of the fixed quantities, growing */
    /* dynkit derive: the formulas themselves instead of fixed quantities, kept here */
    int symbolic;
    node **M, **F;    /* (n x n), (n) */
    node **con_D, **con_c; /* (m x n) rows, (m) convective terms: D q'' + c = 0 */
    int *con_speeds;  /* (m) 1: a constraint on the speeds */
    int regularized;  /* 1: M is singular at the initial state, M + D'D is solved */
    int norder, ordercap;
    /* dyn_mech_constraints_to_c: each constraint's output is its value on the speeds h
     * (D u + h_t) instead of its multiplier, its unit "holonomic" or "speeds" */
    int values;
    int unchecked; /* the constraints need not hold at the initial state */
} mbs_model;

/* the file read and checked, its names resolved, nothing derived (mbs_translate.c) */
mbs_model *mbs_read(lang_ctx *c);
/* statements (mbs_parse.c, which calls mbs_joint.c and mbs_geom.c; the syntax they share
 * is mbs_syntax.h): the hook of lang_parse_model, and the end of the file */
int mbs_statement(lang_ctx *c, lang_lexer *lx, const char *w, lpos wpos);
void mbs_finish_parse(lang_ctx *c, mbs_model *mb);
/* joints (mbs_joint.c): the kind a word names (MBS_NO_JOINT: none), and a joint's words
 * after it into b, the next body */
int mbs_joint_kind(const char *word);
void mbs_parse_joint(lang_ctx *c, lang_lexer *lx, mbs_body *b, int kind);
/* the geometry statements (mbs_geom.c): 0 when w is one (the line is read), else -1; and
 * a shape of a kind with nothing given (-1 everywhere: none, or the ground) */
mbs_shape mbs_shape_init(int kind);
int mbs_geom_statement(lang_ctx *c, lang_lexer *lx, const char *w, lpos wpos);
/* the `input` parameters into the model's inputs, after lang_check */
void mbs_resolve_laws(lang_ctx *c, mbs_model *mb);
void mbs_resolve_inputs(lang_ctx *c, mbs_model *mb);
/* a declared unit that does not read (mbs_units.c): 1 with the offset in text of what is
 * wrong and why (an unknown symbol with the nearest known one, nesting deeper than 200
 * parentheses, ...), else 0 */
int mbs_unit_error(lang_ctx *c, const char *text, int *offset, const char **why);
#define MBS_UNIT_SYMBOLS                                                                     \
    "units are products of the symbols kg, m, s, A, K, mol, cd, 1, rad, sr, deg, g, min, h, " \
    "Hz, N, Pa, J, W, C, V, ohm, F, T, Wb, H, rpm, l, L with powers ^k (no prefixes)"
/* the units of the formulas against the declared ones, after lang_check (mbs_units.c) */
void mbs_check_units(lang_ctx *c, mbs_model *mb);
/* the equations of motion, after lang_check (mbs_derive.c) */
void mbs_derive(lang_ctx *c, mbs_model *mb);
/* cos and sin of a rotation's angle, whole quarter turns (pi - a) taken out exactly
 * (mbs_angle.c) */
void mbs_cos_sin(lang_ctx *c, node *angle, node **cs, node **sn);
/* every subtree repeated among the derived quantities (fixed quantities from nfix0 on)
 * made a fixed quantity of its own, computed once (mbs_cse.c) */
void mbs_cse(lang_ctx *c, mbs_model *mb, int nfix0);
/* a wheel's contact with the ground (mbs_wheel.c), from the body's mass centre G, rotation
 * R (N->B), velocity vG and angular velocity wB (in B) as formulas of the states, and the
 * wheel's radius r, axis a and centre o (in B): the height of its lowest point P and the
 * velocity (x, y) of the body's point at P */
void mbs_wheel_contact(lang_ctx *c, node *const G[3], node *const R[9], node *const vG[3],
                       node *const wB[3], node *r, node *const a[3], node *const o[3],
                       node **height, node *slip[2]);
/* a wheel's contact with the ground as a constraint height = 0 named NAME_z, with its
 * output (mbs_parse.c; when the coordinates do not keep the wheel on the ground) */
void mbs_wheel_normal(lang_ctx *c, mbs_model *mb, int wheel, node *height);
/* the formulas of mb->symbolic as readable text, malloc'd (mbs_text.c) */
char *mbs_text(lang_ctx *c, const mbs_model *mb);
/* one formula as text in the file's names (in the context's arena) */
const char *mbs_formula_text(lang_ctx *c, const node *e);

#endif /* DYNKIT_MBS_INTERNAL_H */
