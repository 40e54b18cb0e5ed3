% dynkit.ode45 against GNU Octave's ode45, measured in the same run (docs/performance.md):
% van der Pol (mu = 1) over [0, 20] at RelTol 1e-6 and 1e-9 (AbsTol 1e-3 of it) with the
% same function handle, and the built-in model vanderpol through dynkit.run (native right-hand
% side, dp45 at the same tolerances). The best of 3 runs each.
% Usage: octave-cli --eval "addpath([pwd '/build/matlab']); run('bench/octave_ode45.m')"
1;
function s = best(f)
  s = inf;
  for k = 1:3
    tic; out = f(); s = min(s, toc); %#ok (an output: ode45 plots without one)
  end
end
f = @(t, y) [y(2); (1 - y(1)^2) * y(2) - y(1)];
printf('| RelTol | Octave ode45 [ms] | dynkit.ode45 [ms] | ratio | dynkit.run, model [ms] | ratio |\n');
printf('|---|---|---|---|---|---|\n');
for tol = [1e-6 1e-9]
  o = odeset('RelTol', tol, 'AbsTol', tol * 1e-3);
  to = best(@() ode45(f, [0 20], [2 0], o));
  td = best(@() dynkit.ode45(f, [0 20], [2 0], o));
  tm = best(@() dynkit.run('vanderpol', 'method', 'dp45', 'tspan', [0 20], 'rtol', tol, ...
                           'atol', tol * 1e-3, 'init', struct('y1', 2, 'y2', 0)));
  printf('| %g | %.1f | %.1f | %.1fx | %.2f | %.0fx |\n', tol, to * 1e3, td * 1e3, to / td, ...
         tm * 1e3, to / tm);
end
