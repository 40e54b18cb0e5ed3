function [tout, yout] = integrate(method, odefun, tspan, Ts, y0, par)
%INTEGRATE  The homework's fixed-step integrators, in C.
%   [tout, yout] = dynkit.integrate(method, odefun, tspan, Ts, y0, par) is
%   Integrate_Euler, Integrate_ModifiedEuler, Integrate_RungeKutta2 and
%   Integrate_RungeKutta4 of TU Delft's "Advanced Dynamics" homework: the samples
%   tout = (tspan(1):Ts:tspan(end))', a row of yout per sample, odefun(t, y, par)
%   called with a column y and returning dy/dt. method is 'euler', 'heun' (modified
%   Euler), 'rk2' (midpoint), 'rk4' or any fixed-step method of `dynkit methods`.
%   Without par, odefun(t, y) is called.
%   Example (the seed's van der Pol):
%     [t, y] = dynkit.integrate('rk4', @vanderpoldemo, [0 15], 0.01, [2 0], 1);
%   See also dynkit.ode45, dynkit.run.
  if nargin < 6
    [tout, yout] = dynkit_mex('integrate', method, odefun, tspan, Ts, y0);
  else
    [tout, yout] = dynkit_mex('integrate', method, odefun, tspan, Ts, y0, par);
  end
end
