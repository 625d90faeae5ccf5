// A model's parameters from a caller's arguments, and its table and repr (model_args.h).
#include "refracta/media/model_args.h"

#include "refracta/media/turbulence.h"

#include <set>
#include <sstream>

namespace refracta {

std::vector<double> param_values_from(const std::string& type, const std::vector<ParamSpec>& specs,
                                      const std::vector<double>& positional, const NamedValues& named) {
  if (positional.size() > specs.size()) {
    throw_invalid(type, " takes at most ", specs.size(), " positional parameters (got ", positional.size(), ")");
  }
  std::vector<double> values = default_values(specs);
  std::set<std::string> given;
  for (size_t i = 0; i < positional.size(); ++i) {
    values[i] = positional[i];
    given.insert(specs[i].name);
  }
  for (const auto& [name, value] : named) {
    size_t index = specs.size();
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].name == name) index = i;
    }
    if (index == specs.size()) {
      std::string names;
      for (size_t i = 0; i < specs.size(); ++i) names += (i > 0 ? ", " : "") + specs[i].name;
      throw_invalid(type, ": unknown parameter '", name, "' (parameters: ", names, ")");
    }
    if (given.count(name)) throw_invalid(type, ": parameter '", name, "' given twice");
    if (!value.number) throw_invalid(type, ": ", name, " must be a number (got ", value.given, ")");
    values[index] = *value.number;
  }
  return values;
}

FieldPtr with_params(const IndexField& field, const NamedValues& named) {
  std::vector<double> values = field.param_values();
  for (const auto& [name, value] : named) {
    const size_t index = field.param_index(name);
    if (!value.number) throw_invalid(field.type_name(), ": ", name, " must be a number (got ", value.given, ")");
    values[index] = *value.number;
  }
  return field.with_param_values(values);
}

std::string param_table(const std::vector<ParamSpec>& specs) {
  std::ostringstream out;
  out.precision(15);  // the default as the model holds it (six digits showed n0's 1.000277 as 1.00028)
  out << "\n\nParameters (name [unit] default, optimiser bounds: meaning):\n";
  for (const auto& s : specs) {
    out << "    " << s.name << " [" << s.unit << "] " << s.default_value << ", [" << s.lower << ", " << s.upper
        << "]: " << s.doc << "\n";
  }
  out << "\nThe optimiser bounds are where edit.solve searches; the model itself takes any physical value (a "
         "value it refuses is named).\n";
  return out.str();
}

std::vector<std::string> param_names(const IndexField& field) {
  std::vector<std::string> names;
  for (const auto& s : field.param_specs()) names.push_back(s.name);
  return names;
}

std::vector<std::pair<std::string, double>> named_param_values(const IndexField& field) {
  std::vector<std::pair<std::string, double>> out;
  const auto values = field.param_values();
  for (size_t i = 0; i < values.size(); ++i) out.emplace_back(field.param_specs()[i].name, values[i]);
  return out;
}

std::vector<std::pair<std::string, std::pair<double, double>>> param_bounds(const IndexField& field) {
  std::vector<std::pair<std::string, std::pair<double, double>>> out;
  for (const auto& s : field.param_specs()) out.push_back({s.name, {s.lower, s.upper}});
  return out;
}

std::string field_repr(const IndexField& field) {
  std::ostringstream out;
  out.precision(8);
  out << field.type_name() << "(";
  const auto& specs = field.param_specs();
  const auto values = field.param_values();
  for (size_t i = 0; i < specs.size(); ++i) out << (i ? ", " : "") << specs[i].name << "=" << values[i];
  if (const auto turbulence = field.turbulence()) {  // else a turbulent air printed as its calm one
    out << (specs.empty() ? "" : ", ") << "turbulence=<layer: scale " << turbulence->scale << ", depth "
        << turbulence->depth << " m>";
  }
  out << ")";
  return out.str();
}

std::shared_ptr<TemperatureProfile> make_temperature_profile(const std::vector<double>& heights,
                                                             std::vector<double> temperatures, double pressure,
                                                             double humidity, double wavelength) {
  if (temperatures.size() != heights.size()) {
    throw_invalid("TemperatureProfile: heights and temperatures must have the same length (", heights.size(), " vs ",
                  temperatures.size(), ")");
  }
  temperatures.insert(temperatures.end(), {pressure, humidity, wavelength});
  return std::make_shared<TemperatureProfile>(TemperatureProfile::Config{heights}, temperatures);
}

std::vector<HotSpot> spots_for_model(const char* model, std::vector<HotSpot> spots, bool with_depth,
                                     double default_depth) {
  for (size_t i = 0; i < spots.size(); ++i) {
    if (!with_depth && !std::isnan(spots[i].depth)) {
      throw_invalid(model, ": hot_spots[", i, "] has depth ", spots[i].depth,
                    "; a LogisticProfile spot takes its vertical width from a_hot (leave depth None)");
    }
    if (with_depth && std::isnan(spots[i].depth)) spots[i].depth = default_depth;
  }
  return spots;
}

}  // namespace refracta
