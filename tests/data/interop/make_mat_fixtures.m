% The MATLAB .mat fixtures of the .mat reader's tests (tests/core/formats/mat_import_test.cpp,
% tests/cli/import_formats_cli_test.cpp) and of the `mat` fuzz target's seeds. Written by GNU
% Octave (Debian `octave`), which is not a dependency of the build or the tests: the .mat files
% are committed. To make them again, from this folder:
%
%   octave-cli --no-gui -q make_mat_fixtures.m
%   cp tactile_v6.mat tactile_v7.mat one_array.mat ../../fuzz/corpus/mat/
%
% Octave 7 cannot write v7.3 ("save -v7.3 is not yet implemented"; its -hdf5 layout is not
% MATLAB's), so the v7.3 file of the tests is written at test time by libmatio itself.
%
% Every value says where it sits, so a transposed or shifted read shows: samples(t, c) is
% 100 * t + c, s.pressure(t, r, c) is 100 * t + 10 * r + c (1-based, as MATLAB counts).
T = 6; C = 4;
samples = zeros(T, C);
for t = 1:T
  for c = 1:C
    samples(t, c) = 100 * t + c;
  end
end
rate = 250;
classes = {
  'Punch';
  'Punch';
  'none';
  'Stroke';
  'Stroke';
  ''};
class_index = int32([1; 1; 0; 2; 2; 0]);
names = ['Punch '; 'Stroke'];
s.pressure = zeros(T, 2, 2, 'single');
for t = 1:T
  for r = 1:2
    for c = 1:2
      s.pressure(t, r, c) = 100 * t + 10 * r + c;
    end
  end
end
s.rate = 50;
counts = int16([-3 7 300]);
touched = logical([1 0 1]);
waves = [1+2i 3-4i];
sparse_map = sparse([1 0; 0 2]);
save('-v6', 'tactile_v6.mat', 'samples', 'rate', 'classes', 'class_index', 'names', 's', ...
     'counts', 'touched', 'waves', 'sparse_map');
save('-v7', 'tactile_v7.mat', 'samples', 'rate', 'classes', 'class_index', 'names', 's', ...
     'counts', 'touched', 'waves', 'sparse_map');
% One array and a rate: what an import reads without --dataset.
pressure = samples;
fs = 100;
save('-v7', 'one_array.mat', 'pressure', 'fs');
