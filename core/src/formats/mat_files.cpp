// MATLAB .mat variables read through libmatio (formats/mat_files.h). libmatio reads; this file
// decides what it may read: the v5 structure is walked first (mat_structure.cpp), a v7.3
// variable's declared sizes are checked against the file before its data is read, and what
// libmatio returns is turned from MATLAB's column-major order into C order.
#include "tactile/formats/mat_files.h"

#include <matio.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>

#include "mat_structure.h"
#include "tactile/error.h"

namespace tactile {

namespace {

// libmatio's last message, for a refusal, instead of lines on stderr.
thread_local std::string mat_message;

void keep_mat_message(int /*level*/, char* message) { mat_message = message ? message : ""; }

void quiet_matio() {
  static std::once_flag once;
  std::call_once(once, [] { Mat_LogInitFunc("tactile", keep_mat_message); });
}

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct MatVarFreer {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using MatHandle = std::unique_ptr<mat_t, MatCloser>;
using MatVarHandle = std::unique_ptr<matvar_t, MatVarFreer>;

// zlib's largest ratio is about 1032:1; HDF5's deflated chunks cannot hold more than this.
constexpr uint64_t kMatMostInflation = 1032;

// The file opened by libmatio, its structure checked first, and the opaque objects of a v5
// file (which libmatio lists without their names).
struct OpenMat {
  MatHandle mat;
  MatFileVersion version = MatFileVersion::v5;
  std::vector<MatOpaqueVariable> opaque;
};

OpenMat open_mat(const std::string& path) {
  quiet_matio();
  OpenMat opened;
  opened.version = mat_file_version(path);
  mat_ft expected = MAT_FT_MAT5;
  if (opened.version == MatFileVersion::v4) {
    check_mat_v4_structure(path);
    expected = MAT_FT_MAT4;
  } else if (opened.version == MatFileVersion::v5) {
    opened.opaque = check_mat_v5_structure(path);
  } else {
    check_mat_v73_structure(path);
    expected = MAT_FT_MAT73;
  }
  mat_message.clear();
  opened.mat.reset(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!opened.mat)
    throw Error(path, "libmatio cannot open it" + (mat_message.empty() ? "" : ": " + mat_message));
  if (Mat_GetVersion(opened.mat.get()) != expected)
    throw Error(path, "libmatio reads it as another MAT-file version than its header declares");
  return opened;
}

// "string object" for the opaque object the walk met under `name`.
std::string opaque_type(const std::vector<MatOpaqueVariable>& opaque, const std::string& name) {
  for (const MatOpaqueVariable& object : opaque)
    if (object.name == name) return object.class_name + " object";
  return "opaque object";
}

size_t mat_count(const matvar_t& variable) {
  size_t count = 1;
  for (int axis = 0; axis < variable.rank; ++axis) count *= variable.dims[axis];
  return count;
}

std::string mat_type_of(const matvar_t& variable) {
  std::string type;
  switch (variable.class_type) {
    case MAT_C_CELL:
      return "cell";
    case MAT_C_STRUCT:
      return "struct";
    case MAT_C_OBJECT:
      return "object";
    case MAT_C_CHAR:
      return "char";
    case MAT_C_SPARSE:
      return "sparse";
    case MAT_C_FUNCTION:
      return "function handle";
    case MAT_C_OPAQUE:
      return "opaque object";
    case MAT_C_DOUBLE:
      type = "double";
      break;
    case MAT_C_SINGLE:
      type = "single";
      break;
    case MAT_C_INT8:
      type = "int8";
      break;
    case MAT_C_UINT8:
      type = variable.isLogical ? "logical" : "uint8";
      break;
    case MAT_C_INT16:
      type = "int16";
      break;
    case MAT_C_UINT16:
      type = "uint16";
      break;
    case MAT_C_INT32:
      type = "int32";
      break;
    case MAT_C_UINT32:
      type = "uint32";
      break;
    case MAT_C_INT64:
      type = "int64";
      break;
    case MAT_C_UINT64:
      type = "uint64";
      break;
    default:
      return "empty";
  }
  return variable.isComplex ? "complex " + type : type;
}

// The declared sizes of a variable and everything it holds, before its data is read: each
// product within kMaxImportedElements, and no more bytes than the file could inflate to.
// (A v5 file has been walked whole already; this is what guards a v7.3 file, whose chunks
// may be unallocated or deflated, and it costs nothing on a v5 one.)
void check_mat_sizes(const matvar_t& variable, const std::string& path, const std::string& name,
                     uint64_t file_bytes, MatFileVersion version, int depth) {
  if (depth > 16) throw Error(path, "variable " + name + ": nested more than 16 deep");
  // libmatio reads a struct or cell whole, and in a v5 file a sparse array inside one made it
  // ask for 4 GB (the fuzzer's regressions/mat/sparse-field-makes-libmatio-allocate-4-gb.mat).
  // A v7.3 sparse array is three datasets whose sizes the HDF5 walk has bounded by the file's
  // bytes: a sparse field beside the one asked for is read and dropped, not refused.
  if (version == MatFileVersion::v5 && depth > 0 && variable.class_type == MAT_C_SPARSE)
    throw Error(path, "variable " + name +
                          ": a sparse array inside a struct or cell of a v5 file is not read (nor "
                          "are its struct's other fields: libmatio reads the struct whole)");
  uint64_t count = 1;
  for (int axis = 0; axis < variable.rank; ++axis) {
    const uint64_t extent = variable.dims[axis];
    if (extent != 0 && count > static_cast<uint64_t>(kMaxImportedElements) / extent)
      throw Error(path, "variable " + name + ": its dimensions declare more than " +
                            std::to_string(kMaxImportedElements) + " elements");
    count *= extent;
  }
  const uint64_t element_bytes = std::max<uint64_t>(Mat_SizeOfClass(variable.class_type), 1);
  if (count * element_bytes > file_bytes * kMatMostInflation + 4096)
    throw Error(path, "variable " + name + ": declares " + std::to_string(count) +
                          " elements, more than the file's " + std::to_string(file_bytes) +
                          " bytes can hold even compressed");
  if (!variable.data) return;
  if (variable.class_type == MAT_C_CELL) {
    auto** cells = static_cast<matvar_t**>(variable.data);
    for (uint64_t index = 0; index < count; ++index)
      if (cells[index])
        check_mat_sizes(*cells[index], path, name + "{" + std::to_string(index + 1) + "}",
                        file_bytes, version, depth + 1);
  } else if (variable.class_type == MAT_C_STRUCT) {
    const unsigned fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(&variable));
    auto** members = static_cast<matvar_t**>(variable.data);
    for (uint64_t index = 0; index < count * fields; ++index)
      if (members[index])
        check_mat_sizes(*members[index], path, name + "." + std::to_string(index), file_bytes,
                        version, depth + 1);
  }
}

// "s.a.b" -> {"s", "a", "b"}.
std::vector<std::string> mat_name_parts(const std::string& name) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t dot = name.find('.', start);
    parts.push_back(name.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

std::string mat_dims_text(const std::vector<int64_t>& dims) {
  std::string text;
  for (int64_t extent : dims) {
    if (!text.empty()) text += 'x';
    text += std::to_string(extent);
  }
  return text;
}

// `opaque`: the walk's opaque objects, whose class libmatio does not give.
MatVariable describe_mat(const matvar_t& variable, const std::string& name,
                         const std::vector<MatOpaqueVariable>& opaque = {}) {
  MatVariable described;
  described.name = name;
  for (int axis = 0; axis < variable.rank; ++axis)
    described.dims.push_back(static_cast<int64_t>(variable.dims[axis]));
  described.type =
      variable.class_type == MAT_C_OPAQUE ? opaque_type(opaque, name) : mat_type_of(variable);
  return described;
}

void list_mat(const matvar_t& variable, const std::string& name,
              const std::vector<MatOpaqueVariable>& opaque, std::vector<MatVariable>& out,
              int depth) {
  out.push_back(describe_mat(variable, name, opaque));
  if (variable.class_type != MAT_C_STRUCT || mat_count(variable) != 1 || !variable.data ||
      depth > 16)
    return;
  const unsigned fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(&variable));
  char* const* field_names = Mat_VarGetStructFieldnames(&variable);
  auto** members = static_cast<matvar_t**>(variable.data);
  for (unsigned field = 0; field < fields; ++field)
    if (members[field] && field_names && field_names[field])
      list_mat(*members[field], name + "." + field_names[field], opaque, out, depth + 1);
}

// The named field of a 1x1 struct (`name` for messages).
const matvar_t& mat_field(const matvar_t& variable, const std::string& field,
                          const std::string& path, const std::string& name) {
  if (variable.class_type != MAT_C_STRUCT)
    throw Error(path, "variable " + name + " is a " + mat_type_of(variable) +
                          ", not a struct with a field " + field);
  if (mat_count(variable) != 1)
    throw Error(path, "variable " + name + " is a " +
                          mat_dims_text(describe_mat(variable, name).dims) +
                          " struct array; only fields of a 1x1 struct are read");
  const unsigned fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(&variable));
  char* const* field_names = Mat_VarGetStructFieldnames(&variable);
  auto** members = static_cast<matvar_t**>(variable.data);
  std::string known;
  for (unsigned index = 0; index < fields && field_names && members; ++index) {
    if (!field_names[index]) continue;
    if (field == field_names[index] && members[index]) return *members[index];
    if (!known.empty()) known += ", ";
    known += field_names[index];
  }
  throw Error(path, "struct " + name + " has no field " + field +
                        " (fields: " + (known.empty() ? "none" : known) + ")");
}

// MATLAB's column-major values as C order: output index k runs over subscripts with the last
// fastest; `offset` follows in column-major strides.
template <typename T>
std::vector<double> c_order(const void* data, const std::vector<int64_t>& dims, size_t count) {
  const T* source = static_cast<const T*>(data);
  std::vector<double> values(count);
  const size_t rank = dims.size();
  std::vector<int64_t> stride(rank, 1), subscript(rank, 0);
  for (size_t axis = 1; axis < rank; ++axis) stride[axis] = stride[axis - 1] * dims[axis - 1];
  int64_t offset = 0;
  for (size_t index = 0; index < count; ++index) {
    values[index] = static_cast<double>(source[offset]);
    for (size_t axis = rank; axis-- > 0;) {
      offset += stride[axis];
      if (++subscript[axis] < dims[axis]) break;
      offset -= stride[axis] * dims[axis];
      subscript[axis] = 0;
    }
  }
  return values;
}

std::vector<double> mat_numbers(const matvar_t& variable, const std::vector<int64_t>& dims) {
  const size_t count = mat_count(variable);
  const void* data = variable.data;
  switch (variable.class_type) {
    case MAT_C_DOUBLE:
      return c_order<double>(data, dims, count);
    case MAT_C_SINGLE:
      return c_order<float>(data, dims, count);
    case MAT_C_INT8:
      return c_order<int8_t>(data, dims, count);
    case MAT_C_UINT8:
      return c_order<uint8_t>(data, dims, count);
    case MAT_C_INT16:
      return c_order<int16_t>(data, dims, count);
    case MAT_C_UINT16:
      return c_order<uint16_t>(data, dims, count);
    case MAT_C_INT32:
      return c_order<int32_t>(data, dims, count);
    case MAT_C_UINT32:
      return c_order<uint32_t>(data, dims, count);
    case MAT_C_INT64:
      return c_order<int64_t>(data, dims, count);
    case MAT_C_UINT64:
      return c_order<uint64_t>(data, dims, count);
    default:
      return {};
  }
}

void append_utf8(std::string& text, uint32_t code) {
  if (code < 0x80) {
    text += static_cast<char>(code);
  } else if (code < 0x800) {
    text += static_cast<char>(0xc0 | code >> 6);
    text += static_cast<char>(0x80 | (code & 0x3f));
  } else if (code < 0x10000) {
    text += static_cast<char>(0xe0 | code >> 12);
    text += static_cast<char>(0x80 | (code >> 6 & 0x3f));
    text += static_cast<char>(0x80 | (code & 0x3f));
  } else {
    text += static_cast<char>(0xf0 | (code >> 18 & 0x07));
    text += static_cast<char>(0x80 | (code >> 12 & 0x3f));
    text += static_cast<char>(0x80 | (code >> 6 & 0x3f));
    text += static_cast<char>(0x80 | (code & 0x3f));
  }
}

// A char matrix's rows, trailing blanks (MATLAB's padding) dropped.
std::vector<std::string> mat_rows(const matvar_t& variable, const std::string& path,
                                  const std::string& name) {
  if (variable.rank != 2)
    throw Error(path, "variable " + name + ": a char array of " + std::to_string(variable.rank) +
                          " dimensions (names are a char matrix or a cell array of char vectors)");
  const size_t rows = variable.dims[0], columns = variable.dims[1];
  // Rows of no characters hold no bytes: their count is bounded by nothing the file holds.
  if (columns == 0 && rows > 1)
    throw Error(path, "variable " + name + ": a " + std::to_string(rows) +
                          "x0 char matrix (names of no characters)");
  const size_t unit = variable.data_size > 0 ? static_cast<size_t>(variable.data_size) : 1;
  if (rows * columns > 0 && (!variable.data || variable.nbytes < rows * columns * unit))
    throw Error(path, "variable " + name + ": libmatio returned fewer characters than declared");
  std::vector<std::string> texts;
  for (size_t row = 0; row < rows; ++row) {
    std::string text;
    for (size_t column = 0; column < columns; ++column) {
      const size_t at = row + rows * column;
      uint32_t code = 0;
      if (unit == 1)
        code = static_cast<const uint8_t*>(variable.data)[at];
      else if (unit == 2)
        code = static_cast<const uint16_t*>(variable.data)[at];
      else
        code = static_cast<const uint32_t*>(variable.data)[at];
      append_utf8(text, code);
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
    texts.push_back(std::move(text));
  }
  return texts;
}

ImportedArray mat_array(const matvar_t& variable, const std::string& path, const std::string& name,
                        const std::vector<MatOpaqueVariable>& opaque) {
  const MatVariable described = describe_mat(variable, name, opaque);
  ImportedArray array;
  if (variable.class_type == MAT_C_CHAR) {
    array.text = true;
    array.strings = mat_rows(variable, path, name);
    array.shape = {static_cast<int64_t>(array.strings.size())};
    return array;
  }
  if (variable.class_type == MAT_C_CELL) {
    array.text = true;
    const size_t count = mat_count(variable);
    auto** cells = static_cast<matvar_t**>(variable.data);
    for (size_t index = 0; index < count; ++index) {
      const std::string cell = name + "{" + std::to_string(index + 1) + "}";
      const matvar_t* element = cells ? cells[index] : nullptr;
      if (!element || (element->class_type == MAT_C_EMPTY) || mat_count(*element) == 0) {
        array.strings.emplace_back();
        continue;
      }
      if (element->class_type != MAT_C_CHAR || element->rank != 2 || element->dims[0] != 1)
        throw Error(path, "variable " + cell + " is a " +
                              mat_variable_line(describe_mat(*element, cell, opaque)) +
                              ", not a char vector (a cell array of names is read as text)");
      array.strings.push_back(mat_rows(*element, path, cell).front());
    }
    array.shape = {static_cast<int64_t>(array.strings.size())};
    return array;
  }
  if (!described.numeric())
    throw Error(path, "variable " + mat_variable_line(described) +
                          " is not read: only real, dense numeric or logical arrays, char "
                          "matrices and cell arrays of char vectors are");
  const size_t count = mat_count(variable);
  if (count > 0 && (!variable.data ||
                    variable.nbytes < count * static_cast<size_t>(std::max(variable.data_size, 1))))
    throw Error(path, "variable " + name + ": libmatio returned fewer values than declared" +
                          (mat_message.empty() ? "" : " (" + mat_message + ")"));
  array.shape = described.dims;
  array.values = mat_numbers(variable, array.shape);
  return array;
}

}  // namespace

bool MatVariable::numeric() const {
  for (const char* known : {"double", "single", "int8", "uint8", "int16", "uint16", "int32",
                            "uint32", "int64", "uint64", "logical"})
    if (type == known) return true;
  return false;
}

std::string mat_variable_line(const MatVariable& variable) {
  // An opaque object has no dimensions of its own (they are in MATLAB's subsystem data).
  if (variable.dims.empty()) return variable.name + " " + variable.type;
  return variable.name + " " + mat_dims_text(variable.dims) + " " + variable.type;
}

std::vector<MatVariable> mat_variables(const std::string& path) {
  OpenMat opened = open_mat(path);
  std::vector<MatVariable> variables;
  size_t opaque_met = 0;
  while (true) {
    MatVarHandle variable(Mat_VarReadNextInfo(opened.mat.get()));
    if (!variable) break;
    std::string name = variable->name ? variable->name : "";
    // libmatio gives an opaque object no name: the walk met the same objects in the same order.
    if (variable->class_type == MAT_C_OPAQUE) {
      while (opaque_met < opened.opaque.size() && !opened.opaque[opaque_met].top_level)
        ++opaque_met;
      if (opaque_met < opened.opaque.size()) name = opened.opaque[opaque_met++].name;
    }
    // MATLAB's subsystem data (the last variable of a file holding objects) has no name, and
    // no name can ask for it.
    if (name.empty()) continue;
    list_mat(*variable, name, opened.opaque, variables, 0);
  }
  return variables;
}

std::vector<std::string> mat_variable_names(const std::string& path) {
  std::vector<std::string> names;
  for (const MatVariable& variable : mat_variables(path)) names.push_back(variable.name);
  return names;
}

ImportedArray read_mat_variable(const std::string& path, const std::string& name) {
  const std::vector<std::string> parts = mat_name_parts(name);
  OpenMat opened = open_mat(path);
  mat_t* mat = opened.mat.get();
  for (const MatOpaqueVariable& object : opened.opaque)
    if (object.top_level && object.name == parts.front())
      throw Error(path, "variable " + object.name + " (a MATLAB " + object.class_name +
                            " object of the " + object.type_system +
                            " type system) is not read: only real, dense numeric or logical "
                            "arrays, char matrices and cell arrays of char vectors are" +
                            (object.class_name == "string"
                                 ? " (save it as cellstr(" + object.name + ") instead)"
                                 : ""));
  MatVarHandle info(Mat_VarReadInfo(mat, parts.front().c_str()));
  if (!info) {
    std::string known;
    for (const MatVariable& variable : mat_variables(path)) {
      if (!known.empty()) known += ", ";
      known += mat_variable_line(variable);
    }
    throw Error(path, "no variable " + parts.front() + " (it holds " +
                          (known.empty() ? "none" : known) + ")");
  }
  std::error_code error;
  const uint64_t file_bytes = std::filesystem::file_size(path, error);
  // The declared sizes of the whole variable (every field) before libmatio reads its data.
  check_mat_sizes(*info, path, parts.front(), error ? 0 : file_bytes, opened.version, 0);
  const matvar_t* checked = info.get();
  std::string reached = parts.front();
  for (size_t part = 1; part < parts.size(); ++part) {
    checked = &mat_field(*checked, parts[part], path, reached);
    reached += "." + parts[part];
  }
  const MatVariable described = describe_mat(*checked, name, opened.opaque);
  if (checked->class_type != MAT_C_CHAR && checked->class_type != MAT_C_CELL &&
      !described.numeric())
    throw Error(path, "variable " + mat_variable_line(described) +
                          " is not read: only real, dense numeric or logical arrays, char "
                          "matrices and cell arrays of char vectors are");
  info.reset();
  mat_message.clear();
  MatVarHandle whole(Mat_VarRead(mat, parts.front().c_str()));
  if (!whole)
    throw Error(path, "variable " + parts.front() + ": libmatio cannot read it" +
                          (mat_message.empty() ? "" : ": " + mat_message));
  const matvar_t* variable = whole.get();
  for (size_t part = 1; part < parts.size(); ++part)
    variable = &mat_field(*variable, parts[part], path, name);
  return mat_array(*variable, path, name, opened.opaque);
}

}  // namespace tactile
