#pragma once
// Internal to the native reader (native_read.cpp): a stored HDF5 element type in words, for its
// "stored as TYPE, expected ..." messages (sentences of core/error_words.h).

#include <hdf5.h>

#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack::native_detail {

// "int64", "float32", "a string", ... for messages about a stored type: a type's name, or words.
inline Wording describe_type(hid_t type) {
  const H5T_class_t type_class = H5Tget_class(type);
  const std::string bits = std::to_string(8 * H5Tget_size(type));
  switch (type_class) {
    case H5T_INTEGER:
      return {Sentence::kText, {(H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + bits}};
    case H5T_FLOAT:
      return {Sentence::kText, {"float" + bits}};
    case H5T_STRING:
      return {Sentence::kNativeTypeString, {}};
    case H5T_COMPOUND:
      return {Sentence::kNativeTypeCompound, {}};
    case H5T_ARRAY:
      return {Sentence::kNativeTypeArray, {}};
    case H5T_ENUM:
      return {Sentence::kNativeTypeEnum, {}};
    default:
      return {Sentence::kNativeTypeNonNumeric, {}};
  }
}

// "stored as TYPE, expected ..." (`sentence`, then `expected`), the type in words when it is.
struct StoredType {
  Wording reason;
  std::vector<WordedValue> words;
};
inline StoredType stored_as(Sentence sentence, const Wording& type, const std::string& shown,
                            std::vector<std::string> expected = {}) {
  expected.insert(expected.begin(), shown);
  StoredType stored{{sentence, std::move(expected)}, {}};
  if (type.sentence != Sentence::kText) stored.words.push_back({shown, type});
  return stored;
}

}  // namespace aggpack::native_detail
