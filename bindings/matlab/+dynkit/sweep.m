function result = sweep(model, varargin)
%SWEEP  Many runs of a dynkit model, one row each, as `dynkit sweep MODEL`.
%   r = dynkit.sweep(model, 'vary', struct('dphi', {{0.1, 1.9, 50}}), ...
%                    'reduce', 'event:turn,max:height', 'tspan', [0 5])
%   runs the model (a built-in name or a model file: .ode, .mech, .c) once per row of the
%   run table and reduces each run to numbers. The runs (one of):
%     'vary', struct(NAME, {{A, B, N}})  N values from A to B (the ends exactly A, B),
%             struct(NAME, [V1 V2 ...])  the values listed; several fields make the full
%                                        grid, the last field varying fastest
%     'sample', struct(NAME, 'uniform(A,B)') with 'runs', N and 'seed', S: random values
%     'from', 'FILE.csv'                  one run per row of a table
%   'reduce': 'final' (default), 'max:NAME', 'min:NAME', 'mean:NAME', 'event:NAME',
%   'count:NAME', ... (a string with commas, or a cell of strings); 'threads', N.
%   The run options are dynkit run's, as in dynkit.run: 'method', 'tspan' [t0 t1],
%   'step', 'set' struct, 'init' struct, 'rtol', 'atol', 'max_step', 'first_step',
%   'max_steps', 'end' ('exact' or 'grid'), 'events' (a cell: 'NAME' or 'NAME:stop').
%   r has one field per column (a column vector each: run, the varied names, the
%   reductions, and status, the library's number, when a run failed: 0 ok,
%   3 nonfinite, 7 step-size, 8 max-steps), names and units (cells, the columns'
%   order), and model, method, step, rtol, atol, tspan. The dynkit tool computes it:
%   the same numbers as the command, bit for bit (it writes them as a .mat file).
%   See also dynkit.run.
  if nargin < 1 || ~ischar(model)
    error('dynkit:argument', 'dynkit.sweep: give the model (a name or a model file) first');
  end
  if mod(numel(varargin), 2) ~= 0
    error('dynkit:argument', 'dynkit.sweep: options come as name-value pairs');
  end
  matfile = [tempname() '.mat'];
  args = {'sweep', model, '--quiet', '--output', matfile};
  for k = 1:2:numel(varargin)
    args = [args, option(varargin{k}, varargin{k + 1})];
  end
  dynkit_tool(args);
  result = load(matfile);
  delete(matfile);
end

function args = option(name, value)
  % the command line's words of one name-value pair
  if ~ischar(name)
    error('dynkit:argument', 'dynkit.sweep: an option''s name must be a string');
  end
  known = {'vary', 'sample', 'runs', 'seed', 'from', 'reduce', 'threads', 'method', ...
           'tspan', 'step', 'set', 'init', 'rtol', 'atol', 'max_step', 'first_step', ...
           'max_steps', 'end', 'events'};
  if ~any(strcmp(name, known))
    error('dynkit:argument', 'dynkit.sweep: unknown option ''%s'' (accepted: %s)', name, ...
          strjoin(known, ', '));
  end
  flag = ['--' strrep(name, '_', '-')];
  switch name
    case 'first_step'
      flag = '--initial-step';
  end
  args = {};
  if isstruct(value)
    fields = fieldnames(value);
    for k = 1:numel(fields)
      args = [args, {flag, [fields{k} '=' values(value.(fields{k}))]}];
    end
  elseif strcmp(name, 'events')
    if ischar(value)
      value = {value};
    end
    for k = 1:numel(value)
      args = [args, {'--event', value{k}}];
    end
  elseif strcmp(name, 'tspan')
    args = {flag, [number(value(1)) ':' number(value(end))]};
  elseif iscell(value)
    args = {flag, strjoin(value, ',')};
  else
    args = {flag, values(value)};
  end
end

function s = values(v)
  % a value, a list V1,V2,... or, from a cell {A, B, N}, the range A:B:N
  if ischar(v)
    s = v;
  elseif iscell(v) && numel(v) == 3
    s = sprintf('%s:%s:%d', number(v{1}), number(v{2}), v{3});
  elseif isnumeric(v) && ~isempty(v)
    parts = arrayfun(@number, v(:)', 'UniformOutput', false);
    s = strjoin(parts, ',');
  else
    error('dynkit:argument', 'dynkit.sweep: a value must be a number, a list, {A, B, N} or a string');
  end
end

function s = number(x)
  % the shortest of %.15g, %.16g, %.17g that reads back to x
  for digits = 15:17
    s = sprintf('%.*g', digits, x);
    if str2double(s) == x
      return;
    end
  end
end
