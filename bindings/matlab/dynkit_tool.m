function [out, log] = dynkit_tool(args)
%DYNKIT_TOOL  Run the dynkit command-line tool with the arguments ARGS (a cell of strings).
%   [out, log] = dynkit_tool({'sweep', 'pendulum', ...}) returns its standard output and
%   standard error; a non-zero exit status is an error 'dynkit:tool' with the tool's
%   message. The tool is $DYNKIT_CLI, else the one built beside this folder
%   (<build>/dynkit for <build>/matlab), else the installed one (<prefix>/bin/dynkit for
%   <prefix>/share/dynkit/matlab), else dynkit on the PATH. Used by dynkit.sweep.
  here = fileparts(mfilename('fullpath'));
  candidates = {getenv('DYNKIT_CLI'), fullfile(here, '..', 'dynkit'), ...
                fullfile(here, '..', '..', '..', 'bin', 'dynkit')};
  exe = 'dynkit';
  for k = 1:numel(candidates)
    if ~isempty(candidates{k}) && exist(candidates{k}, 'file') == 2
      exe = candidates{k};
      break;
    end
  end
  line = quote(exe);
  for k = 1:numel(args)
    line = [line ' ' quote(args{k})];
  end
  errfile = [tempname() '.txt'];
  [status, out] = system([line ' 2> ' quote(errfile)]);
  log = '';
  fid = fopen(errfile, 'r');
  if fid >= 0
    log = fread(fid, Inf, 'char=>char')';
    fclose(fid);
    delete(errfile);
  end
  if status ~= 0
    msg = regexprep(log, '(^|\n)dynkit: error: ', '$1');
    msg = regexprep(msg, '\nTry ''dynkit [^\n]*', '');
    error('dynkit:tool', 'dynkit %s: %s (exit status %d)', args{1}, strtrim(msg), status);
  end
end

function q = quote(s)
  % one word for the shell: single quotes, a quote inside as '\''
  q = ['''' strrep(s, '''', '''\''''') ''''];
end
