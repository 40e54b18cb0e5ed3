/* SPDX-License-Identifier: BSD-3-Clause */
// peer_boost.cpp — Boost.Odeint (header-only) as a peer in the benchmark suite (suite.h).
//
// Measures, on the same right-hand sides as every other solver (bench_systems.h, inlined
// into a functor, so Boost's templates see them as dynkit_inline does):
// - fixed step: runge_kutta4, euler, and Heun's method as an explicit_generic_rk with the
//   classical coefficients, each with std::array<double, N> (sizes known to the compiler) and
//   with std::vector<double>, through integrate_n_steps.
// - adaptive: runge_kutta_dopri5, runge_kutta_cash_karp54 and runge_kutta_fehlberg78 with
//   make_controlled(tol, tol) and integrate_adaptive from t0 to t1 (std::array). Boost's
//   error checker is the maximum over components of |err_i| / (tol + tol (|y_i| + h |y'_i|));
//   its first step is BOOST_H0 (Boost has no automatic first step).
// C++17; the only C++ in the project, built only when Boost is found.
#include <array>
#include <cstdio>
#include <cstring>
#include <new>
#include <vector>

// gcc 12 reports the steppers' scratch arrays (uninitialized by design) as maybe used
// uninitialized when make_controlled copies a stepper: a warning about Boost's code, located
// in its headers, that -isystem does not silence once inlined here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/numeric/odeint.hpp>
#include <boost/version.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "suite.h"

namespace odeint = boost::numeric::odeint;

namespace
{

constexpr double kFirstStep = 1e-3; // adaptive runs: Boost needs an initial step

// The right-hand side as a functor the compiler inlines (how Boost.Odeint is used).
template <int N, class Par, void (*Eval)(const double *, double *, const Par *)> struct System {
    static constexpr int n = N;
    const Par *par;
    long *calls; // counted calls (adaptive), or nullptr
    static System make(const bench_sys *s, long *c)
    {
        return System{static_cast<const Par *>(s->par), c};
    }
    template <class S> void operator()(const S &x, S &dxdt, double) const
    {
        if (calls)
            ++*calls;
        Eval(x.data(), dxdt.data(), par);
    }
};

// Diagnostic: the same right-hand side behind a function pointer chosen at run time, as a
// compiled library has to call it: how much of Boost's speed is the inlined functor.
using EvalPtr = void (*)(const double *, double *, const void *);
void vdp_any(const double *y, double *d, const void *p)
{
    bench_vdp_eval(y, d, static_cast<const bench_vdp_par *>(p));
}
void plane_any(const double *y, double *d, const void *p)
{
    bench_plane_eval(y, d, static_cast<const bench_plane_par *>(p));
}
void arenstorf_any(const double *y, double *d, const void *p)
{
    bench_arenstorf_eval(y, d, static_cast<const bench_arenstorf_par *>(p));
}
template <int N> struct PtrSystem {
    static constexpr int n = N;
    EvalPtr eval;
    const void *par;
    long *calls;
    static PtrSystem make(const bench_sys *s, long *c)
    {
        const EvalPtr e = s->id == BENCH_PLANE       ? plane_any
                          : s->id == BENCH_ARENSTORF ? arenstorf_any
                                                     : vdp_any;
        return PtrSystem{e, s->par, c};
    }
    template <class S> void operator()(const S &x, S &dxdt, double) const
    {
        if (calls)
            ++*calls;
        eval(x.data(), dxdt.data(), par);
    }
};

void vdp_eval(const double *y, double *d, const bench_vdp_par *p) { bench_vdp_eval(y, d, p); }
void plane_eval(const double *y, double *d, const bench_plane_par *p) { bench_plane_eval(y, d, p); }
void arenstorf_eval(const double *y, double *d, const bench_arenstorf_par *p)
{
    bench_arenstorf_eval(y, d, p);
}
using VdpSys = System<2, bench_vdp_par, vdp_eval>;
using PlaneSys = System<12, bench_plane_par, plane_eval>;
using ArenstorfSys = System<4, bench_arenstorf_par, arenstorf_eval>;

// One solver: a system, a state type and what to do with them.
struct Base {
    const bench_sys *sys;
    long calls = 0;
    explicit Base(const bench_sys *s) : sys(s) {}
    virtual ~Base() = default;
    virtual int run(double arg, long steps, double *y, bench_counts *counts) = 0;
};

template <class State> State make_state(int n)
{
    if constexpr (std::is_same_v<State, std::vector<double>>)
        return State(static_cast<size_t>(n));
    else
        return State{};
}

template <class Sys, class State> auto heun_stepper()
{
    using Stepper = odeint::explicit_generic_rk<2, 2, State, double, State, double>;
    const boost::array<double, 1> a1 = {{1.0}};
    const typename Stepper::coef_a_type a = boost::fusion::make_vector(a1);
    const typename Stepper::coef_b_type b = {{0.5, 0.5}};
    const typename Stepper::coef_c_type c = {{0.0, 1.0}};
    return Stepper(a, b, c);
}

template <class Sys, class State> struct Fixed final : Base {
    bench_method method;
    Fixed(const bench_sys *s, bench_method m) : Base(s), method(m) {}
    int run(double h, long steps, double *y, bench_counts *counts) override
    {
        State x = make_state<State>(sys->n);
        std::memcpy(x.data(), sys->y0, sizeof(double) * static_cast<size_t>(sys->n));
        const Sys f = Sys::make(sys, nullptr);
        if (method == BENCH_RK4) {
            odeint::runge_kutta4<State> st;
            odeint::integrate_n_steps(st, f, x, sys->t0, h, static_cast<size_t>(steps));
        } else if (method == BENCH_EULER) {
            odeint::euler<State> st;
            odeint::integrate_n_steps(st, f, x, sys->t0, h, static_cast<size_t>(steps));
        } else {
            auto st = heun_stepper<Sys, State>();
            odeint::integrate_n_steps(st, f, x, sys->t0, h, static_cast<size_t>(steps));
        }
        std::memcpy(y, x.data(), sizeof(double) * static_cast<size_t>(sys->n));
        if (counts) {
            counts->rhs = steps * (method == BENCH_RK4 ? 4 : method == BENCH_HEUN ? 2 : 1);
            counts->jac = 0;
            counts->steps = steps;
        }
        return 0;
    }
};

enum class Pair { Dopri5, CashKarp54, Fehlberg78 };

template <class Sys, class State> struct Adaptive final : Base {
    Pair pair;
    Adaptive(const bench_sys *s, Pair p) : Base(s), pair(p) {}
    template <class Stepper> long integrate(Stepper stepper, double tol, State &x)
    {
        const Sys f = Sys::make(sys, &calls);
        auto controlled = odeint::make_controlled(tol, tol, stepper);
        return static_cast<long>(
            odeint::integrate_adaptive(controlled, f, x, sys->t0, sys->t1, kFirstStep));
    }
    int run(double tol, long, double *y, bench_counts *counts) override
    {
        State x = make_state<State>(sys->n);
        std::memcpy(x.data(), sys->y0, sizeof(double) * static_cast<size_t>(sys->n));
        calls = 0;
        long steps;
        if (pair == Pair::Dopri5)
            steps = integrate(odeint::runge_kutta_dopri5<State>(), tol, x);
        else if (pair == Pair::CashKarp54)
            steps = integrate(odeint::runge_kutta_cash_karp54<State>(), tol, x);
        else
            steps = integrate(odeint::runge_kutta_fehlberg78<State>(), tol, x);
        std::memcpy(y, x.data(), sizeof(double) * static_cast<size_t>(sys->n));
        if (counts) {
            counts->rhs = calls;
            counts->jac = 0;
            counts->steps = steps;
        }
        return 0;
    }
};

int run_solver(void *ctx, double arg, long steps, double *y, bench_counts *counts)
{
    try {
        return static_cast<Base *>(ctx)->run(arg, steps, y, counts);
    } catch (...) {
        return 1;
    }
}

void destroy_solver(void *ctx) { delete static_cast<Base *>(ctx); }

template <class Sys> Base *new_fixed(const bench_sys *s, bench_method m, bool vec)
{
    if (vec)
        return new (std::nothrow) Fixed<Sys, std::vector<double>>(s, m);
    return new (std::nothrow) Fixed<Sys, std::array<double, Sys::n>>(s, m);
}

template <class Sys> Base *new_adaptive(const bench_sys *s, Pair p)
{
    return new (std::nothrow) Adaptive<Sys, std::array<double, Sys::n>>(s, p);
}

int add(bench_solver *out, int *count, int max, Base *b, const char *label, int flags, int order,
        double calls_per_step)
{
    if (!b)
        return 1;
    if (*count >= max) {
        delete b;
        return 1;
    }
    bench_solver *s = &out[(*count)++];
    std::memset(s, 0, sizeof *s);
    std::snprintf(s->label, sizeof s->label, "%s", label);
    s->peer = "Boost";
    s->flags = flags;
    s->order = order;
    s->step_factor = 1.0;
    s->calls_per_step = calls_per_step;
    s->ctx = b;
    s->run = run_solver;
    s->destroy = destroy_solver;
    return 0;
}

int boost_solvers(const bench_sys *sys, bench_task task, bench_method m, bench_solver *out, int max)
{
    int count = 0;
    if (task == BENCH_TASK_FIXED) {
        const char *name = m == BENCH_RK4     ? "runge_kutta4"
                           : m == BENCH_EULER ? "euler"
                                              : "Heun (explicit_generic_rk)";
        const double cps = m == BENCH_RK4 ? 4 : m == BENCH_HEUN ? 2 : 1;
        for (int vec = 0; vec < 2; vec++) {
            Base *b = nullptr;
            if (sys->id == BENCH_VDP)
                b = new_fixed<VdpSys>(sys, m, vec);
            else if (sys->id == BENCH_PLANE)
                b = new_fixed<PlaneSys>(sys, m, vec);
            else if (sys->id == BENCH_ARENSTORF)
                b = new_fixed<ArenstorfSys>(sys, m, vec);
            char label[80];
            std::snprintf(label, sizeof label, "Boost %s, std::%s", name, vec ? "vector" : "array");
            if (add(out, &count, max, b, label, BENCH_SAME, 0, cps))
                break;
        }
        return count;
    }
    if (task != BENCH_TASK_ADAPTIVE)
        return 0;
    const struct {
        const char *label;
        Pair pair;
        int order;
    } list[] = {{"Boost runge_kutta_dopri5", Pair::Dopri5, 5},
                {"Boost runge_kutta_cash_karp54", Pair::CashKarp54, 5},
                {"Boost runge_kutta_fehlberg78", Pair::Fehlberg78, 8}};
    for (const auto &e : list) {
        Base *b = nullptr;
        if (sys->id == BENCH_VDP)
            b = new_adaptive<VdpSys>(sys, e.pair);
        else if (sys->id == BENCH_ARENSTORF)
            b = new_adaptive<ArenstorfSys>(sys, e.pair);
        else if (sys->id == BENCH_PLANE)
            b = new_adaptive<PlaneSys>(sys, e.pair);
        if (!b)
            continue;
        if (add(out, &count, max, b, e.label, 0, e.order, 0.0))
            break;
    }
    // diagnostic: dopri5 with the right-hand side through a pointer
    Base *b = nullptr;
    if (sys->id == BENCH_VDP)
        b = new_adaptive<PtrSystem<2>>(sys, Pair::Dopri5);
    else if (sys->id == BENCH_ARENSTORF)
        b = new_adaptive<PtrSystem<4>>(sys, Pair::Dopri5);
    else if (sys->id == BENCH_PLANE)
        b = new_adaptive<PtrSystem<12>>(sys, Pair::Dopri5);
    add(out, &count, max, b, "diagnostic: Boost runge_kutta_dopri5, rhs by pointer", BENCH_DIAG, 5,
        0.0);
    return count;
}

const char *boost_version() { return "Boost " BOOST_LIB_VERSION " (Odeint)"; }

} // namespace

extern "C" const bench_peer bench_peer_boost = {"boost", boost_version, boost_solvers};
