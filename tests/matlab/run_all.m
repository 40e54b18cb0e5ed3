% The MEX functions of +dynkit in GNU Octave, against the seed's integrators, Octave's
% own ode45, exact solutions and `dynkit run` (ctest octave_mex). Each check prints a line;
% a failed check raises an error, which makes octave exit with a non-zero status.
1;
function check(ok, what)
  if ~ok
    error('dynkit:test', 'FAILED: %s', what);
  end
  printf('ok: %s\n', what);
end

% the homework's convention, against the seed's Octave code (differences of rounding only)
[t1, y1] = dynkit.integrate('rk4', @vanderpoldemo, [0 15], 0.01, [2 0], 1);
[t2, y2] = Integrate_RungeKutta4(@vanderpoldemo, [0 15], 0.01, [2 0], 1);
check(isequal(size(y1), size(y2)) && max(abs(t1 - t2)) < 1e-12, 'rk4: the seed''s samples');
check(max(abs(y1(:) - y2(:))) < 1e-11, sprintf('rk4 as the seed''s (%.2g)', max(abs(y1(:) - y2(:)))));
[t1, y1] = dynkit.integrate('heun', @vanderpoldemo, [0 15], 0.01, [2 0], 1);
[t2, y2] = Integrate_ModifiedEuler(@vanderpoldemo, [0 15], 0.01, [2 0], 1);
check(max(abs(y1(:) - y2(:))) < 1e-11, sprintf('modified Euler as the seed''s (%.2g)', max(abs(y1(:) - y2(:)))));

% ode45 against the exact solution, beside Octave's ode45 at the same tolerances
f = @(t, y) [y(2); -y(1)];
for tol = [1e-6 1e-9]
  o = odeset('RelTol', tol, 'AbsTol', tol * 1e-3);
  [t, y] = dynkit.ode45(f, [0 20], [1 0], o);
  [to, yo] = ode45(f, [0 20], [1 0], o);
  e = max(abs(y(:, 1) - cos(t))); eo = max(abs(yo(:, 1) - cos(to)));
  check(e < 10 * eo + 1e-14, sprintf('ode45 at %g: error %.2g, Octave''s %.2g', tol, e, eo));
end
% output at the times of tspan, the five outputs and events
ts = linspace(0, 5, 11);
[t, y] = dynkit.ode45(f, ts, [1 0], odeset('RelTol', 1e-10, 'AbsTol', 1e-12));
check(isequal(t(:)', ts) && max(abs(y(:, 1)' - cos(ts))) < 1e-8, 'ode45 at the times of tspan');
o = odeset('RelTol', 1e-10, 'AbsTol', 1e-12, 'Events', @(t, y) deal([y(1); y(2)], [1; 0], [-1; 0]));
[t, y, te, ye, ie] = dynkit.ode45(f, [0 10], [1 0], o);
check(abs(t(end) - pi / 2) < 1e-9 && ie(end) == 1 && abs(te(end) - pi / 2) < 1e-9, ...
      'a terminal event ends the run at pi/2');
check(any(ie == 2) == 0 || all(abs(te(ie == 2)) < pi / 2), 'the second event before it');
sol = dynkit.ode45(f, [0 1], [1 0], odeset('RelTol', 1e-10, 'AbsTol', 1e-12));
check(isstruct(sol) && strcmp(sol.solver, 'ode45') && size(sol.y, 1) == 2 && ...
      numel(sol.x) == size(sol.y, 2) && abs(sol.y(1, end) - cos(1)) < 1e-8, 'sol as a struct');
[t, y] = dynkit.ode23(f, [0 2], [1 0], odeset('RelTol', 1e-8, 'AbsTol', 1e-10));
check(abs(y(end, 1) - cos(2)) < 1e-6, 'ode23');
[t, y] = dynkit.dop853(f, [0 2], [1 0], odeset('RelTol', 1e-12, 'AbsTol', 1e-14));
check(abs(y(end, 1) - cos(2)) < 1e-11, 'dop853');
rob = @(t, y) [-0.04*y(1) + 1e4*y(2)*y(3); 0.04*y(1) - 1e4*y(2)*y(3) - 3e7*y(2)^2; 3e7*y(2)^2];
[t, y] = dynkit.ode15s(rob, [0 40], [1 0 0], odeset('RelTol', 1e-6, 'AbsTol', 1e-10));
check(abs(sum(y(end, :)) - 1) < 1e-8 && abs(y(end, 1) - 0.7158) < 1e-3, ...
      sprintf('ode15s on Robertson: y1(40) = %.5f (0.71583 published)', y(end, 1)));

% a model through the library's entry, the same numbers as dynkit run
src = getenv('DYNKIT_SOURCE_DIR');
r = dynkit.run('vanderpol', 'method', 'rk4', 'step', 0.01, 'tspan', [0 15]);
[st, out] = system([src '/build/dynkit run vanderpol --method rk4 --step 0.01 --tspan 0:15 --final 2>/dev/null']);
if st ~= 0 % another build directory: the tool beside the MEX file
  exe = fullfile(fileparts(fileparts(which('dynkit_mex'))), 'dynkit');
  [st, out] = system([exe ' run vanderpol --method rk4 --step 0.01 --tspan 0:15 --final']);
end
lines = strsplit(strtrim(out), "\n");
v = str2double(strsplit(lines{2}, ','));
check(st == 0 && isequal([r.t(end) r.y(end, :)], v), 'dynkit.run = dynkit run, bit for bit');
check(isequal(r.names, {'t', 'y1', 'y2'}) && strcmp(r.units{1}, 's'), 'names and units');
r = dynkit.run([src '/examples/models/lorenz.ode'], 'tspan', [0 1], 'set', struct('rho', 28), ...
               'init', struct('x', 1));
check(r.status == 0 && numel(r.t) > 10, 'a model file');

% dynkit.sweep against dynkit sweep's CSV (this build's tool, beside the MEX file), bit for
% bit, and the pendulum's energy: its highest point l^2 dphi0^2 / (2 g)
exe = fullfile(fileparts(fileparts(which('dynkit_mex'))), 'dynkit');
s = dynkit.sweep('pendulum', 'vary', struct('dphi', {{0.1, 1.9, 7}}, 'l', [1 2]), ...
                 'reduce', {'event:turn', 'max:height', 'final'}, 'tspan', [0 5]);
[st, out] = system([exe ' sweep pendulum --tspan 0:5 --vary dphi=0.1:1.9:7 --vary l=1,2 ' ...
                    '--reduce event:turn,max:height,final']);
lines = strsplit(strtrim(out), "\n");
ref = cell2mat(cellfun(@(l) str2double(strsplit(l, ',')), lines(2:end)', 'UniformOutput', false));
got = cell2mat(cellfun(@(n) s.(n), s.names, 'UniformOutput', false));
check(st == 0 && isequal(s.names, strsplit(lines{1}, ',')) && isequal(got, ref), ...
      'dynkit.sweep = dynkit sweep, bit for bit');
check(strcmp(s.units{strcmp(s.names, 'max_height')}, 'm') && strcmp(s.method, 'dp45'), ...
      'the sweep''s units and method');
top = s.l .^ 2 .* s.dphi .^ 2 / (2 * 9.81);
check(all(abs(s.max_height - top) <= 1e-3 * top), 'the sweep''s highest points from the energy');
s = dynkit.sweep('vanderpol', 'vary', struct('mu', [-1 1e300]), 'tspan', [0 1]);
check(s.status(1) == 0 && s.status(2) == 3 && isnan(s.final_y1(2)), ...
      'a failed run: nan and its status');
try
  dynkit.sweep('vanderpol', 'vary', struct('nope', [1 2]));
  check(false, 'a bad name in a sweep is refused');
catch err
  check(strcmp(err.identifier, 'dynkit:tool') && ~isempty(strfind(err.message, 'nope')), ...
        'a bad name in a sweep is refused, named');
end
try
  dynkit.sweep('vanderpol', 'tolerance', 1);
  check(false, 'an unknown option of dynkit.sweep is refused');
catch err
  check(~isempty(strfind(err.message, 'unknown option ''tolerance''')), ...
        'an unknown option of dynkit.sweep is refused');
end

% the README's lines (vanderpoldemo is the seed's, in tests/matlab)
txt = fileread([src '/README.md']);
blk = regexp(txt, '## MATLAB and GNU Octave.*?```\n(.*?)```', 'tokens', 'once');
clear t y r;
eval(blk{1});
check(size(y, 1) == 1501 && r.status == 0 && numel(r.t) == 1501, 'the README''s lines run');

% the octave snippets of docs/matlab.md
txt = fileread([src '/docs/matlab.md']);
blocks = regexp(txt, '```octave\n(.*?)```', 'tokens');
for snippet = 1:numel(blocks)
  clear r;
  eval(blocks{snippet}{1});
  check(true, sprintf('docs/matlab.md, octave snippet %d', snippet));
end

% bad input: errors with their identifiers, the odefun's own error again
try
  dynkit.ode45(@(t, y) [1; 2; 3], [0 1], [1 0]);
  check(false, 'a wrong size from odefun is refused');
catch err
  check(strcmp(err.identifier, 'dynkit:odefun'), 'a wrong size from odefun is refused');
end
try
  dynkit.ode45(@(t, y) error('mine:id', 'my own error'), [0 1], [1 0]);
  check(false, 'odefun''s error comes back');
catch err
  check(~isempty(strfind(err.message, 'my own error')), 'odefun''s error comes back');
end
try
  dynkit.ode45(f, [0 1], [NaN 0]);
  check(false, 'a non-finite y0 is refused');
catch err
  check(strcmp(err.identifier, 'dynkit:argument'), 'a non-finite y0 is refused');
end
try
  dynkit.run('pendulm');
  check(false, 'an unknown model is refused');
catch err
  check(~isempty(strfind(err.message, 'unknown model')), 'an unknown model is refused');
end
try
  dynkit.run('pendulum', 'set', struct('nope', 1));
  check(false, 'an unknown parameter is refused');
catch err
  check(~isempty(strfind(err.message, 'no parameter ''nope''')), 'an unknown parameter is refused');
end
printf('all checks passed\n');
