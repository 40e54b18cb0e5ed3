% SPDX-License-Identifier: BSD-3-Clause
% Load a MATLAB file written by `dynkit run --output FILE.mat` or `dynkit sweep --output
% FILE.mat` (a variable per column) with load() and print what it holds, for
% tests/test_formats.c to compare with the CSV of the same run or sweep bit for bit:
%   shape ROWS COLS / names NAME... / units UNIT... / meta KEY=VALUE...
%   row BITS...   one line per row, each value's IEEE 754 bits in hex (num2hex, exact)
% Usage: octave-cli --norc --quiet load_table.m FILE.mat
args = argv();
load(args{end});
if exist('t', 'var')
  table = [t, y];
  if exist('outputs', 'var')
    table = [table, outputs];
  end
  states = columns(y);
else  % a sweep's table: a variable per column, named as the column
  s = load(args{end});
  table = zeros(rows(s.(names{1})), numel(names));
  for k = 1:numel(names)
    table(:, k) = s.(names{k});
  end
  states = NaN;
end
if !exist('step', 'var')  % not written when the samples are not on a grid
  step = NaN;
end
printf('shape %d %d\n', rows(table), columns(table));
printf('names'); printf(' %s', names{:}); printf('\n');
printf('units'); printf(' %s', units{:}); printf('\n');
printf('meta model=%s method=%s step=%.17g states=%d class=%s\n', model, method, step, ...
       states, class(table));
for k = 1:rows(table)
  printf('row'); printf(' %s', cellstr(num2hex(table(k, :)))'{:}); printf('\n');
end
