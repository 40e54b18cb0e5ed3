function varargout = ode15s(odefun, tspan, y0, options)
%ODE15S  Solve y' = f(t, y) with dynkit's rodas4, as MATLAB's ode15s (stiff problems).
%   [t, y] = dynkit.ode15s(odefun, tspan, y0) integrates from tspan(1) to tspan(end);
%   y0 is the initial state, odefun(t, y) returns dy/dt as a column.
%   With tspan = [t0 t1] the rows are every step, with Refine (default 4) points in
%   each; with more times in tspan, the solution at exactly those times.
%   [t, y] = dynkit.ode15s(odefun, tspan, y0, options) takes odeset's RelTol (1e-3),
%   AbsTol (1e-6), MaxStep, InitialStep, Refine, Stats ('on' prints the counts) and
%   Events: [value, isterminal, direction] = events(t, y), located on the dense output.
%   [t, y, te, ye, ie] = ... gives the events found: times, states, indices (1-based).
%   [t, y, te, ye, ie, stats] = ... gives nsteps, nfailed, nfevals, njacevals.
%   sol = dynkit.ode15s(...) gives a struct with fields x, y (states by row), xe, ye, ie,
%   stats, solver, (Octave has no deval; MATLAB's deval reads it).
%   The method: rodas4, a stiffly accurate Rosenbrock method of order 4 (Jacobian by differences).
%   See also dynkit.ode45, dynkit.ode23, dynkit.dop853, dynkit.ode15s,
%   dynkit.integrate, dynkit.run, odeset, deval.
  if nargin < 4
    options = [];
  end
  varargout = dynkit_ode('ode15s', 'rodas4', nargout, odefun, tspan, y0, options);
end
