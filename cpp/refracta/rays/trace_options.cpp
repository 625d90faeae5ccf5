// Parsing and validation of TraceOptions.
#include "refracta/rays/trace_options.h"

#include "refracta/core/error.h"

namespace refracta {

namespace {
constexpr double kMinRelativeTol = 1e-15;  // of max_length: double round-off of a position
}  // namespace

TraceMethod parse_trace_method(const std::string& name) {
  if (name == "rk4") return TraceMethod::kRk4;
  if (name == "rk45") return TraceMethod::kRk45;
  if (name == "stratified") return TraceMethod::kStratified;
  throw_invalid("method must be 'rk4', 'rk45' or 'stratified' (got '", name, "')");
}

const char* trace_method_name(TraceMethod method) {
  switch (method) {
    case TraceMethod::kRk4: return "rk4";
    case TraceMethod::kRk45: return "rk45";
    case TraceMethod::kStratified: return "stratified";
  }
  return "?";
}

const char* trace_stop_name(TraceStop stop) {
  switch (stop) {
    case TraceStop::kMaxLength: return "max_length";
    case TraceStop::kStopHeight: return "stop_height";
    case TraceStop::kVisitor: return "stopped";
  }
  return "?";
}

void TraceOptions::validate() const {
  if (!(tol > 0.0) || !std::isfinite(tol)) throw_invalid("tol must be > 0 (got ", tol, ")");
  if (!(step >= 0.0) || !std::isfinite(step)) {
    throw_invalid("step must be > 0, or None for the default (got ", step, ")");
  }
  if (!(max_length > 0.0) || !std::isfinite(max_length)) {
    throw_invalid("max_length must be > 0 and finite (got ", max_length, ")");
  }
  if (stop_height && !std::isfinite(*stop_height)) {
    throw_invalid("stop_height must be finite (got ", *stop_height, ")");
  }
  if (max_steps <= 0) throw_invalid("max_steps must be > 0 (got ", max_steps, ")");
  if (ior_floor && !(*ior_floor > 0.0 && std::isfinite(*ior_floor))) {
    throw_invalid("ior_floor must be > 0 and finite (got ", *ior_floor, ")");
  }
  // Refused before any work: a path that needs more than max_steps steps (rk4: max_length / step;
  // rk45: at least max_length / step when a largest step is given; stratified: at least
  // max_length / node spacing, default 100 m) would run for minutes and fill memory with nodes.
  const double least_step = method == TraceMethod::kRk4          ? (step > 0 ? step : 0.3)
                            : method == TraceMethod::kStratified ? (step > 0 ? step : 100.0)
                                                                 : step;
  if (least_step > 0 && max_length / least_step > double(max_steps)) {
    throw_invalid(trace_method_name(method), " with step ", least_step, " m needs more than ", max_steps,
                  " steps for max_length ", max_length, " m (raise step or lower max_length)");
  }
  // rk45 and stratified aim at tol over the whole path. Below round-off of the positions (1e-15
  // of the path) rk45's error control divided by an underflowed allowance and the state became
  // NaN ("height -nan m"), and stratified split panels chasing noise into 10 million nodes.
  if (method != TraceMethod::kRk4 && std::isfinite(max_length) && tol < kMinRelativeTol * max_length) {
    throw_invalid(trace_method_name(method), ": tol must be at least ", kMinRelativeTol, " x max_length = ",
                  kMinRelativeTol * max_length, " m, the round-off of positions (got ", tol, ")");
  }
}

}  // namespace refracta
