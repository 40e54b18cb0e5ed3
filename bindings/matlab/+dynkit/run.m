function result = run(model, varargin)
%RUN  Run a dynkit model: a built-in one or a model file (.ode, .mech, .c).
%   r = dynkit.run(model) runs it with its defaults, as `dynkit run MODEL`;
%   r = dynkit.run(model, 'method', 'rk4', 'step', 0.01, 'tspan', [0 15], ...
%                  'init', struct('y1', 2), 'set', struct('mu', 1), ...
%                  'rtol', 1e-8, 'atol', 1e-10)
%   takes `dynkit run`'s options as name-value pairs. r has fields t (a column),
%   y (a row per sample), names and units of the columns t, states..., status and
%   message. The run goes through the library's one entry (dyn_run): every kind of
%   model (noise, delays, Volterra integrals, resets) runs as on the command line,
%   with the same numbers.
%   See also dynkit.ode45, dynkit.integrate.
  if mod(numel(varargin), 2) ~= 0
    error('dynkit:argument', 'dynkit.run: options come as name-value pairs');
  end
  opts = struct();
  for k = 1:2:numel(varargin)
    opts.(varargin{k}) = varargin{k + 1};
  end
  result = dynkit_mex('run', model, opts);
end
