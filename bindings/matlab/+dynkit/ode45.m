function varargout = ode45(odefun, tspan, y0, options)
%ODE45  Solve y' = f(t, y) with dynkit's dp45, as MATLAB's ode45 (Dormand-Prince 5(4)).
%   [t, y] = dynkit.ode45(odefun, tspan, y0) integrates from tspan(1) to tspan(end);
%   y0 is the initial state, odefun(t, y) returns dy/dt as a column.
%   With tspan = [t0 t1] the rows are every step, with Refine (default 4) points in
%   each; with more times in tspan, the solution at exactly those times.
%   [t, y] = dynkit.ode45(odefun, tspan, y0, options) takes odeset's RelTol (1e-3),
%   AbsTol (1e-6), MaxStep, InitialStep, Refine, Stats ('on' prints the counts) and
%   Events: [value, isterminal, direction] = events(t, y), located on the dense output.
%   [t, y, te, ye, ie] = ... gives the events found: times, states, indices (1-based).
%   [t, y, te, ye, ie, stats] = ... gives nsteps, nfailed, nfevals, njacevals.
%   sol = dynkit.ode45(...) gives a struct with fields x, y (states by row), xe, ye, ie,
%   stats, solver, (Octave has no deval; MATLAB's deval reads it).
%   The method: dp45, Dormand and Prince's 5(4) pair with its 4th-order dense output.
%   See also dynkit.ode45, dynkit.ode23, dynkit.dop853, dynkit.ode15s,
%   dynkit.integrate, dynkit.run, odeset, deval.
  if nargin < 4
    options = [];
  end
  varargout = dynkit_ode('ode45', 'dp45', nargout, odefun, tspan, y0, options);
end
