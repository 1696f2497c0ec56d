#pragma once
// MATLAB .mat files (v5, compressed or not, and v7.3) read through libmatio into the array
// path of array_files.h, so a .mat is imported as a .npz is (docs/IMPORT.md). Before libmatio
// reads anything, every size the file declares is checked: a v5 file's whole structure against
// the bytes it holds (compressed variables inflated as they are walked), a v7.3 variable's
// dimensions against kMaxImportedElements and what the file's bytes could inflate to.
//
// MATLAB stores arrays column-major: a [T x C] matrix is T samples of C channels, and it is
// returned as shape {T, C} in C order (values[t * C + c] is MATLAB's x(t+1, c+1)); any rank
// alike. Variables are named as MATLAB does, a struct's field as "s.field" (1x1 structs).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/formats/array_files.h"

namespace tactile {

// One variable or struct field as the file declares it.
struct MatVariable {
  std::string name;           // "pressure", "s.pressure"
  std::vector<int64_t> dims;  // MATLAB's order: {1000, 64}
  std::string type;           // "double", "int16", "logical", "char", "cell", "struct",
                              // "sparse", "complex double", "object", ...
  bool numeric() const;       // a real, dense number or logical array
};

// "s.pressure 1000x64 double", as refusals list them.
std::string mat_variable_line(const MatVariable& variable);

// Every variable of the file, in the file's order, each 1x1 struct followed by its fields.
std::vector<MatVariable> mat_variables(const std::string& path);
std::vector<std::string> mat_variable_names(const std::string& path);

// One variable (or "s.field"): a real numeric or logical array as numbers; a char matrix (one
// text per row, trailing blanks dropped), or a cell array of char vectors, as strings. Complex,
// sparse, objects and other cells are refused naming the variable and what it is.
ImportedArray read_mat_variable(const std::string& path, const std::string& name);

}  // namespace tactile
