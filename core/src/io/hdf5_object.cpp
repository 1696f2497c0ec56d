#include "hdf5_object.h"

#include <cstring>

namespace tactile::hdf5 {

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {

herr_t keep_innermost(unsigned index, const H5E_error2_t* error, void* data) {
  // Walking upward, index 0 is the function that detected the error: the message
  // that says what is actually wrong ("truncated file: eof = ...").
  if (index == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
  return 0;
}

}  // namespace

std::string last_error() {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &message);
  H5Eclear2(H5E_DEFAULT);
  return message;
}

void fail(const std::string& where, const std::string& what) {
  const std::string detail = last_error();
  throw Error(where, detail.empty() ? what : what + " (" + detail + ")");
}

void Object::close(const std::string& where) {
  if (id_ < 0) return;
  const herr_t status = closer_ != nullptr ? closer_(id_) : 0;
  id_ = H5I_INVALID_HID;
  if (status < 0) fail(where, "cannot close");
}

Object checked(hid_t id, Object::Closer closer, const std::string& where, const std::string& what) {
  if (id < 0) fail(where, what);
  return Object(id, closer);
}

bool has_link(hid_t location, const std::string& name) {
  return H5Lexists(location, name.c_str(), H5P_DEFAULT) > 0;
}

bool has_attribute(hid_t location, const std::string& name) {
  return H5Aexists(location, name.c_str()) > 0;
}

Object open_group(hid_t location, const std::string& name, const std::string& where) {
  if (!has_link(location, name)) throw Error(where, "missing group");
  return checked(H5Gopen2(location, name.c_str(), H5P_DEFAULT), H5Gclose, where,
                 "cannot open group");
}

Object open_dataset(hid_t location, const std::string& name, const std::string& where) {
  if (!has_link(location, name)) throw Error(where, "missing dataset");
  return checked(H5Dopen2(location, name.c_str(), H5P_DEFAULT), H5Dclose, where,
                 "cannot open dataset");
}

Object untimed_dataset_properties(const std::string& where) {
  Object properties =
      checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, where, "cannot create property list");
  if (H5Pset_obj_track_times(properties.id(), false) < 0) fail(where, "cannot turn off time stamps");
  return properties;
}

Object create_group(hid_t location, const std::string& name, bool track_order,
                    const std::string& where) {
  Object properties = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, where, "property list");
  // No modification times in object headers: the same recording writes the same bytes.
  if (H5Pset_obj_track_times(properties.id(), false) < 0) fail(where, "cannot turn off time stamps");
  // Tracking creation order lets a reader list streams in the order they were written.
  if (track_order && H5Pset_link_creation_order(properties.id(),
                                                H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0)
    fail(where, "cannot track link order");
  return checked(H5Gcreate2(location, name.c_str(), H5P_DEFAULT, properties.id(), H5P_DEFAULT),
                 H5Gclose, where, "cannot create group");
}

Object string_type() {
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "", "cannot copy string type");
  if (H5Tset_size(type.id(), H5T_VARIABLE) < 0 || H5Tset_cset(type.id(), H5T_CSET_UTF8) < 0)
    fail("", "cannot make a UTF-8 string type");
  return type;
}

//---- Attributes

namespace {

Object attribute_creation_properties(const std::string& where) {
  Object properties =
      checked(H5Pcreate(H5P_ATTRIBUTE_CREATE), H5Pclose, where, "cannot create property list");
  // Metadata keys may be any UTF-8 text.
  if (H5Pset_char_encoding(properties.id(), H5T_CSET_UTF8) < 0)
    fail(where, "cannot set UTF-8 names");
  return properties;
}

void write_attribute(hid_t location, const std::string& name, hid_t file_type, hid_t memory_type,
                     const void* value, const std::string& where) {
  const std::string place = where + " attribute " + name;
  Object space = checked(H5Screate(H5S_SCALAR), H5Sclose, place, "cannot create dataspace");
  Object properties = attribute_creation_properties(place);
  Object attribute = checked(
      H5Acreate2(location, name.c_str(), file_type, space.id(), properties.id(), H5P_DEFAULT),
      H5Aclose, place, "cannot create attribute");
  if (H5Awrite(attribute.id(), memory_type, value) < 0) fail(place, "cannot write attribute");
}

Object open_scalar_attribute(hid_t location, const std::string& name, const std::string& place) {
  if (!has_attribute(location, name)) throw Error(place, "missing attribute");
  Object attribute = checked(H5Aopen(location, name.c_str(), H5P_DEFAULT), H5Aclose, place,
                             "cannot open attribute");
  Object space = checked(H5Aget_space(attribute.id()), H5Sclose, place, "cannot read dataspace");
  if (H5Sget_simple_extent_npoints(space.id()) != 1) throw Error(place, "expected a single value");
  return attribute;
}

void read_numeric_attribute(hid_t location, const std::string& name, hid_t memory_type, void* value,
                            const std::string& where) {
  const std::string place = where + " attribute " + name;
  Object attribute = open_scalar_attribute(location, name, place);
  Object type = checked(H5Aget_type(attribute.id()), H5Tclose, place, "cannot read type");
  const H5T_class_t type_class = H5Tget_class(type.id());
  if (type_class != H5T_INTEGER && type_class != H5T_FLOAT) throw Error(place, "expected a number");
  if (H5Aread(attribute.id(), memory_type, value) < 0) fail(place, "cannot read attribute");
}

}  // namespace

void write_string_attribute(hid_t location, const std::string& name, const std::string& value,
                            const std::string& where) {
  Object type = string_type();
  const char* text = value.c_str();
  write_attribute(location, name, type.id(), type.id(), &text, where);
}

void write_double_attribute(hid_t location, const std::string& name, double value,
                            const std::string& where) {
  write_attribute(location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, where);
}

void write_int_attribute(hid_t location, const std::string& name, int64_t value,
                         const std::string& where) {
  write_attribute(location, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, where);
}

std::string read_string_attribute(hid_t location, const std::string& name,
                                  const std::string& where) {
  const std::string place = where + " attribute " + name;
  Object attribute = open_scalar_attribute(location, name, place);
  Object file_type = checked(H5Aget_type(attribute.id()), H5Tclose, place, "cannot read type");
  if (H5Tget_class(file_type.id()) != H5T_STRING) throw Error(place, "expected a string");
  if (H5Tis_variable_str(file_type.id()) > 0) {
    Object type = string_type();
    char* text = nullptr;
    if (H5Aread(attribute.id(), type.id(), &text) < 0) fail(place, "cannot read attribute");
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const size_t size = H5Tget_size(file_type.id());
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, place, "cannot copy string type");
  H5Tset_size(type.id(), size);
  H5Tset_strpad(type.id(), H5T_STR_NULLPAD);
  std::string value(size, '\0');
  if (H5Aread(attribute.id(), type.id(), value.data()) < 0) fail(place, "cannot read attribute");
  value.resize(std::strlen(value.c_str()));
  return value;
}

double read_double_attribute(hid_t location, const std::string& name, const std::string& where) {
  double value = 0.0;
  read_numeric_attribute(location, name, H5T_NATIVE_DOUBLE, &value, where);
  return value;
}

int64_t read_int_attribute(hid_t location, const std::string& name, const std::string& where) {
  int64_t value = 0;
  read_numeric_attribute(location, name, H5T_NATIVE_INT64, &value, where);
  return value;
}

namespace {

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

}  // namespace

std::vector<std::string> attribute_names(hid_t location, const std::string& where) {
  std::vector<std::string> names;
  hsize_t index = 0;
  if (H5Aiterate2(location, H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names) < 0)
    fail(where, "cannot list attributes");
  return names;
}

//---- Datasets

std::vector<hsize_t> dataset_shape(hid_t dataset, const std::string& where) {
  Object space = checked(H5Dget_space(dataset), H5Sclose, where, "cannot read dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (rank < 0) fail(where, "cannot read rank");
  std::vector<hsize_t> shape(static_cast<size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.id(), shape.data(), nullptr) < 0)
    fail(where, "cannot read shape");
  return shape;
}

H5T_class_t dataset_class(hid_t dataset, const std::string& where) {
  Object type = checked(H5Dget_type(dataset), H5Tclose, where, "cannot read type");
  return H5Tget_class(type.id());
}

void write_strings(hid_t location, const std::string& name, const std::vector<std::string>& values,
                   const std::string& where) {
  const hsize_t count = values.size();
  Object space = checked(H5Screate_simple(1, &count, nullptr), H5Sclose, where, "dataspace");
  Object type = string_type();
  Object properties = untimed_dataset_properties(where);
  Object dataset = checked(H5Dcreate2(location, name.c_str(), type.id(), space.id(), H5P_DEFAULT,
                                      properties.id(), H5P_DEFAULT),
                           H5Dclose, where, "cannot create dataset");
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& value : values) pointers.push_back(value.c_str());
  if (count > 0 &&
      H5Dwrite(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0)
    fail(where, "cannot write dataset");
}

std::vector<std::string> read_strings(hid_t location, const std::string& name,
                                      const std::string& where) {
  Object dataset = open_dataset(location, name, where);
  const std::vector<hsize_t> shape = dataset_shape(dataset.id(), where);
  if (shape.size() != 1) throw Error(where, "expected a 1-D dataset of strings");
  Object file_type = checked(H5Dget_type(dataset.id()), H5Tclose, where, "cannot read type");
  if (H5Tget_class(file_type.id()) != H5T_STRING) throw Error(where, "expected strings");
  const size_t count = shape[0];
  std::vector<std::string> values;
  values.reserve(count);
  if (count == 0) return values;
  if (H5Tis_variable_str(file_type.id()) > 0) {
    Object type = string_type();
    std::vector<char*> pointers(count, nullptr);
    if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0)
      fail(where, "cannot read dataset");
    for (char* text : pointers) values.emplace_back(text != nullptr ? text : "");
    Object space = checked(H5Dget_space(dataset.id()), H5Sclose, where, "dataspace");
    H5Dvlen_reclaim(type.id(), space.id(), H5P_DEFAULT, pointers.data());
    return values;
  }
  const size_t size = H5Tget_size(file_type.id());
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, where, "cannot copy string type");
  H5Tset_size(type.id(), size);
  H5Tset_strpad(type.id(), H5T_STR_NULLPAD);
  std::vector<char> buffer(size * count, '\0');
  if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
    fail(where, "cannot read dataset");
  for (size_t index = 0; index < count; ++index) {
    const char* begin = buffer.data() + index * size;
    values.emplace_back(begin, strnlen(begin, size));
  }
  return values;
}

}  // namespace tactile::hdf5
