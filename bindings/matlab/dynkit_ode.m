function out = dynkit_ode(solver, method, nout, odefun, tspan, y0, options)
%DYNKIT_ODE  The outputs of dynkit.ode45 and its siblings, as MATLAB's: [t, y],
%   [t, y, te, ye, ie], a sixth output with the counts, or one struct sol.
  [t, y, te, ye, ie, stats] = dynkit_mex('ivp', method, odefun, tspan, y0, options);
  if nout == 1
    out = {struct('solver', solver, 'x', t.', 'y', y.', 'xe', te.', 'ye', ye.', ...
                  'ie', ie.', 'stats', stats)};
  else
    all = {t, y, te, ye, ie, stats};
    out = all(1:max(nout, 1));
  end
end
