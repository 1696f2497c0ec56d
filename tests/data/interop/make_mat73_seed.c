/* The v7.3 seed of the `mat` fuzz target (tests/fuzz/corpus/mat/small_v73.mat), written by
 * libmatio: Octave 7 cannot write v7.3 (make_mat_fixtures.m). Not built by the project; to make
 * it again:
 *
 *   gcc make_mat73_seed.c -lmatio -o /tmp/make_mat73_seed
 *   /tmp/make_mat73_seed ../../fuzz/corpus/mat/small_v73.mat
 *
 * samples is [2 x 3], samples(t, c) = 100 t + c (column-major here, as MATLAB holds it). */
#include <matio.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  mat_t* mat = Mat_CreateVer(argv[1], NULL, MAT_FT_MAT73);
  if (!mat) return 1;
  double samples[6] = {101, 201, 102, 202, 103, 203};
  size_t dims[2] = {2, 3};
  matvar_t* variable = Mat_VarCreate("samples", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, samples, 0);
  const int status = Mat_VarWrite(mat, variable, MAT_COMPRESSION_NONE);
  Mat_VarFree(variable);
  Mat_Close(mat);
  return status == 0 ? 0 : 1;
}
