function y = round(x, n)
  % MATLAB's round(x, n): round to n decimals (Octave's builtin round takes one argument)
  if nargin < 2
    y = builtin('round', x);
  else
    y = builtin('round', x .* 10.^n) ./ 10.^n;
  end
end
