// Enums that cross the boundary as their names: a property of a bound class read through
// name(value) and set through parse(name), which throws (ValueError) for a name it does not know.
#pragma once

#include "refracta/bindings/bindings.h"

#include <optional>
#include <string>

namespace refracta {

// parse: a function or a captureless lambda (one that names another property in its messages).
template <class Class, class Owner, class Enum, class Parse>
Class& def_enum_property(Class& cls, const char* property, Enum Owner::*field, const char* (*name)(Enum), Parse parse,
                         const char* doc) {
  return cls.def_property(
      property, [field, name](const Owner& o) { return name(o.*field); },
      [field, parse](Owner& o, const std::string& value) { o.*field = parse(value); }, doc);
}

// A field that may be unset: None both ways.
template <class Class, class Owner, class Enum, class Parse>
Class& def_enum_property(Class& cls, const char* property, std::optional<Enum> Owner::*field, const char* (*name)(Enum),
                         Parse parse, const char* doc) {
  return cls.def_property(
      property,
      [field, name](const Owner& o) { return o.*field ? std::optional<std::string>(name(*(o.*field))) : std::nullopt; },
      [field, parse](Owner& o, const std::optional<std::string>& value) {
        o.*field = value ? std::optional<Enum>(parse(*value)) : std::nullopt;
      },
      doc);
}

}  // namespace refracta
