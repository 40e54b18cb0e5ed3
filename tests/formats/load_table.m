% SPDX-License-Identifier: BSD-3-Clause
% Load a MATLAB file written by `dynkit run --output FILE.mat` with load() and print what it
% holds, for tests/test_formats.c to compare with the run's CSV bit for bit:
%   shape ROWS COLS / names NAME... / units UNIT... / meta KEY=VALUE...
%   row BITS...   one line per row, each value's IEEE 754 bits in hex (num2hex, exact)
% Usage: octave-cli --norc --quiet load_table.m FILE.mat
args = argv();
load(args{end});
table = [t, y];
if exist('outputs', 'var')
  table = [table, outputs];
end
if !exist('step', 'var')  % not written when the samples are not on a grid
  step = NaN;
end
printf('shape %d %d\n', rows(table), columns(table));
printf('names'); printf(' %s', names{:}); printf('\n');
printf('units'); printf(' %s', units{:}); printf('\n');
printf('meta model=%s method=%s step=%.17g states=%d class=%s\n', model, method, step, ...
       columns(y), class(y));
for k = 1:rows(table)
  printf('row'); printf(' %s', cellstr(num2hex(table(k, :)))'{:}); printf('\n');
end
