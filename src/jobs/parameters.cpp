#include "meander/parameters.h"

#include "meander/error.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <optional>

namespace meander {

namespace {

// The text as a message quotes it, cut short.
std::string shown(std::string_view text) {
  return text.size() > 40 ? std::string(text.substr(0, 40)) + "..." : std::string(text);
}

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

[[noreturn]] void refuse_number(const Parameter& p, bool integer, std::string_view got) {
  std::string range = integer ? "an integer" : "a number";
  if (std::isfinite(p.min) && std::isfinite(p.max)) range += " in [" + number_text(p.min) + ", " + number_text(p.max) + "]";
  else if (std::isfinite(p.min)) range += " >= " + number_text(p.min);
  throw ParameterError(p.name, ": expected " + range + ", got " + shown(got));
}

// A length's text split into its number and the millimetres in its unit (1 without one).
std::pair<std::string_view, double> split_unit(const Parameter& p, std::string_view text) {
  size_t letters = text.size();
  while (letters > 0 && std::isalpha(static_cast<unsigned char>(text[letters - 1]))) --letters;
  const std::string_view unit = text.substr(letters);
  if (!p.length || unit.empty() || letters == 0) return {text, 1};
  static constexpr std::pair<std::string_view, double> units[] = {{"mm", 1}, {"cm", 10}, {"m", 1000}, {"in", 25.4}};
  for (const auto& [name, millimetres] : units)
    if (unit == name) return {text.substr(0, letters), millimetres};
  throw ParameterError(p.name, ": unknown unit '" + shown(unit) + "' in " + shown(text) + " (expected mm, cm, m or in)");
}

template <class T> T number(const Parameter& p, std::string_view text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) refuse_number(p, std::is_integral_v<T>, text);
  check_parameter(p, double(value), std::is_integral_v<T>);
  return value;
}

// Each enum's names, as its parameter lists them.
std::span<const std::string_view> names(Quadrangulation) { return parameters::quad_choices; }
std::span<const std::string_view> names(TreeStrategy) { return parameters::tree_choices; }
std::span<const std::string_view> names(Smoothing) { return parameters::smooth_choices; }
std::span<const std::string_view> names(WireMethod) { return parameters::method_choices; }
std::span<const std::string_view> names(WireShape) { return parameters::shape_choices; }
std::span<const std::string_view> names(DuotoneRule) { return parameters::rule_choices; }
std::span<const std::string_view> names(TileStyle) { return parameters::tiles_choices; }

Quadrangulation parse(std::string_view text, Quadrangulation*) { return parse_quadrangulation(text); }
TreeStrategy parse(std::string_view text, TreeStrategy*) { return parse_tree_strategy(text); }
Smoothing parse(std::string_view text, Smoothing*) { return parse_smoothing(text); }
WireMethod parse(std::string_view text, WireMethod*) { return parse_wire_method(text); }
WireShape parse(std::string_view text, WireShape*) { return parse_wire_shape(text); }
DuotoneRule parse(std::string_view text, DuotoneRule*) { return parse_duotone_rule(text); }
TileStyle parse(std::string_view text, TileStyle*) { return parse_tile_style(text); }

std::string listed(std::span<const std::string_view> choices) {
  std::string list;
  for (size_t k = 0; k < choices.size(); ++k)
    list += std::string(k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(choices[k]);
  return list;
}

template <class Job> void check_numbers(const Job& job) {
  visit_parameters(job, [](const Parameter& p, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    if constexpr (std::is_arithmetic_v<V> && !std::is_same_v<V, bool>) check_parameter(p, double(value), std::is_integral_v<V>);
    else if constexpr (std::is_same_v<V, std::optional<double>>) {
      if (value && std::isfinite(p.max)) check_parameter(p, *value, false);
      else if (value && !(*value > 0 && std::isfinite(*value)))
        throw ParameterError(p.name, " must be a positive number or " + std::string(p.choices[0]) + " (got " +
                                         number_text(*value) + ")");
    }
  });
}

} // namespace

bool has_unit(std::string_view text) {
  return !text.empty() && std::isalpha(static_cast<unsigned char>(text.back())) &&
         text.find_first_of("0123456789") != std::string_view::npos;
}

void check_unit(const Parameter& p, std::string_view text, bool sized, std::string_view model_size) {
  if (p.length && !p.millimetres && !sized && has_unit(text))
    throw ParameterError(p.name, ": " + std::string(text) + " carries a unit, which needs " + std::string(model_size) +
                                     " (without it, lengths are in the model's own units)");
}

double millimetres(std::string_view name, std::string_view text) {
  double value = 0;
  set_parameter(Parameter{.name = name, .min = 0, .length = true}, text, value);
  return value;
}

void check_parameter(const Parameter& p, double value, bool integer) {
  if (!std::isfinite(value) || value < p.min || value > p.max || (integer && value != std::floor(value)))
    refuse_number(p, integer, number_text(value));
}

template <class T> void set_parameter(const Parameter& p, std::string_view text, T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    if (text != "true" && text != "false") throw ParameterError(p.name, ": expected true or false, got " + shown(text));
    value = text == "true";
  } else if constexpr (std::is_same_v<T, double>) {
    const auto [digits, millimetres] = split_unit(p, text);
    value = number<T>(p, digits) * millimetres;
  } else if constexpr (std::is_arithmetic_v<T>) {
    value = number<T>(p, text);
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    if (text == p.choices[0]) {
      value.reset();
      return;
    }
    const auto [digits, millimetres] = split_unit(p, text);
    double r = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), r);
    const bool ranged = std::isfinite(p.max);
    if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(r) ||
        (ranged ? r < p.min || r > p.max : !(r > 0)))
      throw ParameterError(p.name, ": expected " +
                                       (ranged ? "a number in [" + number_text(p.min) + ", " + number_text(p.max) + "]"
                                               : std::string("a positive number")) +
                                       " or " + std::string(p.choices[0]) + ", got " + shown(text));
    value = r * millimetres;
  } else if constexpr (std::is_same_v<T, std::array<Color8, 2>>) {
    value = parse_duotone_colors(text); // its refusals name the parameter
  } else if constexpr (std::is_same_v<T, Paper>) {
    try {
      const Paper named = parse_paper(text);
      value.width = named.width, value.height = named.height;
    } catch (const UsageError& e) {
      throw ParameterError(p.name, std::string(": ") + e.what());
    }
  } else {
    if (std::find(p.choices.begin(), p.choices.end(), text) == p.choices.end())
      throw ParameterError(p.name, ": unknown value '" + shown(text) + "' (expected " + listed(p.choices) + ")");
    value = parse(text, static_cast<T*>(nullptr));
  }
}

template <class T> std::string parameter_text(const Parameter& p, const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_arithmetic_v<T>) {
    return number_text(value);
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return value ? number_text(*value) : std::string(p.choices[0]);
  } else if constexpr (std::is_same_v<T, Paper>) {
    return number_text(value.width) + "x" + number_text(value.height) + "mm";
  } else if constexpr (std::is_same_v<T, std::array<Color8, 2>>) {
    char text[16];
    std::snprintf(text, sizeof text, "#%02x%02x%02x,#%02x%02x%02x", value[0][0], value[0][1], value[0][2], value[1][0],
                  value[1][1], value[1][2]);
    return text;
  } else {
    for (std::string_view name : names(value))
      if (parse(name, static_cast<T*>(nullptr)) == value) return std::string(name);
    return {};
  }
}

#define MEANDER_PARAMETER_TYPE(...)                                                                                   \
  template void set_parameter<__VA_ARGS__>(const Parameter&, std::string_view, __VA_ARGS__&);                        \
  template std::string parameter_text<__VA_ARGS__>(const Parameter&, const __VA_ARGS__&);
MEANDER_PARAMETER_TYPE(int)
MEANDER_PARAMETER_TYPE(int64_t)
MEANDER_PARAMETER_TYPE(uint64_t)
MEANDER_PARAMETER_TYPE(double)
MEANDER_PARAMETER_TYPE(bool)
MEANDER_PARAMETER_TYPE(Quadrangulation)
MEANDER_PARAMETER_TYPE(TreeStrategy)
MEANDER_PARAMETER_TYPE(Smoothing)
MEANDER_PARAMETER_TYPE(WireMethod)
MEANDER_PARAMETER_TYPE(WireShape)
MEANDER_PARAMETER_TYPE(DuotoneRule)
MEANDER_PARAMETER_TYPE(TileStyle)
MEANDER_PARAMETER_TYPE(std::optional<double>)
MEANDER_PARAMETER_TYPE(std::array<Color8, 2>)
MEANDER_PARAMETER_TYPE(Paper)
#undef MEANDER_PARAMETER_TYPE

void check_parameters(const CurveJob& job) { check_numbers(job); }
void check_parameters(const WireJob& job) {
  check_numbers(job);
  if (job.shape == WireShape::ribbon && job.min_thickness > 0)
    throw ParameterError(parameters::min_thickness.name, " applies to wires: a ribbon is a band with no thickness to measure");
  if (job.bridges && job.shape == WireShape::ribbon)
    throw ParameterError(parameters::bridges.name, " apply to wires: a ribbon lies on the surface, which holds it");
}
void check_parameters(const DuotoneJob& job) {
  check_numbers(job);
  if (job.min_thickness > 0 && !job.shell)
    throw ParameterError(parameters::shell_min_thickness.name, " applies to a shell (--shell): the painted surface has no thickness");
  if (job.clearance > 0 && !job.shell)
    throw ParameterError(parameters::clearance.name, " applies to a shell (--shell): the pieces of a two-colour print");
}
void check_parameters(const ImageJob& job) {
  check_numbers(job);
  if (job.tone.max_spacing < job.tone.spacing)
    throw ParameterError(parameters::max_spacing.name, " must be at least the spacing (" + number_text(job.tone.spacing) +
                                                           " mm), got " + number_text(job.tone.max_spacing) + " mm");
}

} // namespace meander
