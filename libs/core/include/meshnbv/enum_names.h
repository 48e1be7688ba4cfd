// Names of enumerators for options (CLI flags, JSON keys, VTK and MeshLab
// parameters all use the same words): one table per enum gives both the
// parser, with an error listing the accepted words, and the name.
#pragma once

#include <string>
#include <utility>

#include "meshnbv/error.h"

namespace meshnbv::detail {

template <class E, std::size_t N>
using EnumTable = std::pair<const char*, E>[N];

// The enumerator called `name`; otherwise Error("unknown <what> 'name'
// (expected a, b or c)").
template <class E, std::size_t N>
E parse_enum(const std::string& name, const EnumTable<E, N>& table, const char* what) {
  for (const auto& [word, value] : table)
    if (name == word) return value;
  std::string expected;
  for (std::size_t i = 0; i < N; ++i)
    expected += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].first);
  throw Error("unknown " + std::string(what) + " '" + name + "' (expected " + expected + ")");
}

// The word of `value` (the first entry of the table if it is not listed).
template <class E, std::size_t N>
std::string enum_name(E value, const EnumTable<E, N>& table) {
  for (const auto& [word, v] : table)
    if (v == value) return word;
  return table[0].first;
}

}  // namespace meshnbv::detail
