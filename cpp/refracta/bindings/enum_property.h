// Enums that cross the boundary as their names: a property of a bound class read through
// name(value) and set through parse(name), which throws (ValueError) for a name it does not know.
#pragma once

#include "refracta/bindings/bindings.h"

#include <optional>
#include <stdexcept>
#include <string>

namespace refracta {

// parse's message names the option it usually parses ("trace must be ..."); a property of another
// name parsed by it (RenderOptions.march, a trace method) says its own name instead.
inline std::invalid_argument renamed_error(const std::invalid_argument& error, const char* property) {
  const std::string message = error.what();
  const size_t space = message.find(' ');
  if (space == std::string::npos || message.compare(0, space, property) == 0) return error;
  return std::invalid_argument(property + message.substr(space));
}

template <class Owner, class Enum>
Enum parsed(Enum (*parse)(const std::string&), const std::string& value, const char* property) {
  try {
    return parse(value);
  } catch (const std::invalid_argument& error) {
    throw renamed_error(error, property);
  }
}

template <class Class, class Owner, class Enum>
Class& def_enum_property(Class& cls, const char* property, Enum Owner::*field, const char* (*name)(Enum),
                         Enum (*parse)(const std::string&), const char* doc) {
  return cls.def_property(
      property, [field, name](const Owner& o) { return name(o.*field); },
      [field, parse, property](Owner& o, const std::string& value) {
        o.*field = parsed<Owner>(parse, value, property);
      },
      doc);
}

// A field that may be unset: None both ways.
template <class Class, class Owner, class Enum>
Class& def_enum_property(Class& cls, const char* property, std::optional<Enum> Owner::*field, const char* (*name)(Enum),
                         Enum (*parse)(const std::string&), const char* doc) {
  return cls.def_property(
      property,
      [field, name](const Owner& o) { return o.*field ? std::optional<std::string>(name(*(o.*field))) : std::nullopt; },
      [field, parse, property](Owner& o, const std::optional<std::string>& value) {
        o.*field = value ? std::optional<Enum>(parsed<Owner>(parse, *value, property)) : std::nullopt;
      },
      doc);
}

}  // namespace refracta
