// A model's parameters from a caller's arguments, and what a field reports about them: the values
// from positional and named arguments over the defaults (the rules and error texts of every model's
// constructor and of with_params), the hot spots and turbulence a model takes, the parameter table of
// its documentation and its repr. The bindings pass Python's arguments through these, so every model
// reads its parameters the same way.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/fields.h"
#include "refracta/media/hot_spot.h"

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace refracta {

// A caller's value for a parameter: its number, or nullopt where it was not one (a string, a bool,
// None...), with `given` its repr for the message "<type>: <name> must be a number (got <given>)",
// raised once the name is known to be a parameter.
struct ParamInput {
  std::optional<double> number;
  std::string given;
};
// Arguments by name, in the order given.
using NamedValues = std::vector<std::pair<std::string, ParamInput>>;

// The values of `specs` from their defaults, the first ones replaced by `positional` (in order), then
// each named one. Throws std::invalid_argument (naming `type`) for too many positional values, an
// unknown name, a name given twice, or a value that is not a number.
std::vector<double> param_values_from(const std::string& type, const std::vector<ParamSpec>& specs,
                                      const std::vector<double>& positional, const NamedValues& named);

// The same model with the named parameters changed (validated by the model).
FieldPtr with_params(const IndexField& field, const NamedValues& named);

// "\n\nParameters (name [unit] default, optimiser bounds: meaning):" and a line per parameter.
std::string param_table(const std::vector<ParamSpec>& specs);

// The parameters' names, (name, value) and (name, (lower, upper)) pairs, in order.
std::vector<std::string> param_names(const IndexField& field);
std::vector<std::pair<std::string, double>> named_param_values(const IndexField& field);
std::vector<std::pair<std::string, std::pair<double, double>>> param_bounds(const IndexField& field);

// "Type(name=value, ...)" with 8 significant digits.
std::string field_repr(const IndexField& field);

// A TemperatureProfile of temperatures [K] at heights [m] (the same count), pressure [Pa] at the
// lowest height, relative humidity and wavelength [nm].
std::shared_ptr<TemperatureProfile> make_temperature_profile(const std::vector<double>& heights,
                                                             std::vector<double> temperatures, double pressure,
                                                             double humidity, double wavelength);

// Spots given to a model: PhysicalAtmosphere's take a missing depth (NaN) from `default_depth` (its
// surface layer's); LogisticProfile's must have none (their vertical width is a_hot).
std::vector<HotSpot> spots_for_model(const char* model, std::vector<HotSpot> spots, bool with_depth,
                                     double default_depth);

// Whether a model's Config carries hot spots (and turbulence with them), and whether it can switch
// its hot layer off (LogisticProfile's height-only part).
template <class Config, class = void>
struct HasHotSpots : std::false_type {};
template <class Config>
struct HasHotSpots<Config, std::void_t<decltype(std::declval<Config&>().hot_spots)>> : std::true_type {};
template <class Config, class = void>
struct HasHotLayerOff : std::false_type {};
template <class Config>
struct HasHotLayerOff<Config, std::void_t<decltype(std::declval<Config&>().hot_layer_off)>> : std::true_type {};

// What a model's constructor takes: parameters by position and by name, and, when given (even as
// empty or null), hot spots and turbulence.
struct ModelArgs {
  std::vector<double> positional;
  NamedValues named;
  std::optional<std::vector<HotSpot>> hot_spots;
  std::optional<std::shared_ptr<const Turbulence>> turbulence;
};

// A model (ModelField or AirModelField) from its arguments: the spots' parameters follow the model's
// own; a model without hot spots refuses hot_spots and turbulence.
template <class Field>
std::shared_ptr<Field> make_model(const ModelArgs& args) {
  using Config = typename Field::Config;
  const std::vector<ParamSpec> specs = Field::param_specs_for({});
  std::vector<double> values = param_values_from(Field::model_name(), specs, args.positional, args.named);
  Config config{};
  if constexpr (HasHotSpots<Config>::value) {
    if (args.hot_spots) {
      double depth = 0.0;
      for (size_t i = 0; i < specs.size(); ++i) {
        if (specs[i].name == "surface_depth") depth = values[i];
      }
      constexpr bool with_depth = Field::ModelType::kSpotsHaveDepth;
      config.hot_spots = spots_for_model(Field::model_name(), *args.hot_spots, with_depth, depth);
      for (const ParamSpec& spec : Field::param_specs_for(config)) {
        if (spec.name.rfind("hot_spot", 0) == 0) values.push_back(spec.default_value);
      }
    }
    if (args.turbulence) config.turbulence = *args.turbulence;
  } else {
    if (args.hot_spots) throw_invalid(Field::model_name(), " takes no hot_spots");
    if (args.turbulence) throw_invalid(Field::model_name(), " takes no turbulence");
  }
  return std::make_shared<Field>(config, values);
}

// A model's hot spots with their current parameter values (depth NaN where spots have none).
template <class Field>
std::vector<HotSpot> model_hot_spots(const Field& field) {
  constexpr bool with_depth = Field::ModelType::kSpotsHaveDepth;
  const size_t first = Field::param_specs_for(typename Field::Config{}).size();
  std::vector<HotSpot> spots = hot_spots_from(field.config().hot_spots, field.param_values(), first, with_depth);
  if (!with_depth) {
    for (HotSpot& spot : spots) spot.depth = std::nan("");
  }
  return spots;
}

// What rebuilds a model with hot spots: its parameter values, its spots as made, its turbulence and
// whether its hot layer is off (a pickle's state).
struct ModelState {
  std::vector<double> values;
  std::vector<HotSpot> hot_spots;
  std::shared_ptr<const Turbulence> turbulence;
  bool hot_layer_off = false;
};

template <class Field>
ModelState model_state(const Field& field) {
  ModelState state{field.param_values(), field.config().hot_spots, field.config().turbulence, false};
  if constexpr (HasHotLayerOff<typename Field::Config>::value) state.hot_layer_off = field.config().hot_layer_off;
  return state;
}

template <class Field>
std::shared_ptr<Field> model_from_state(const ModelState& state) {
  typename Field::Config config{};
  config.hot_spots = state.hot_spots;
  config.turbulence = state.turbulence;
  if constexpr (HasHotLayerOff<typename Field::Config>::value) config.hot_layer_off = state.hot_layer_off;
  return std::make_shared<Field>(config, state.values);
}

}  // namespace refracta
