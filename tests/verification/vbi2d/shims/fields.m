function f = fields(s)
  % MATLAB's fields() is fieldnames() (Octave has no fields)
  f = fieldnames(s);
end
