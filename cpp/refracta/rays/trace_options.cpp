// Parsing and validation of TraceOptions.
#include "refracta/rays/trace_options.h"

#include "refracta/core/error.h"

#include <charconv>
#include <cmath>
#include <string>

namespace refracta {

namespace {

// The shortest text that reads back as x (as Python's repr).
std::string shortest(double x) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  return std::string(text, end);
}
}  // namespace

TraceMethod parse_trace_method(const std::string& name) {
  if (name == "rk4") return TraceMethod::kRk4;
  if (name == "rk45") return TraceMethod::kRk45;
  if (name == "stratified") return TraceMethod::kStratified;
  throw_invalid("trace must be 'rk4', 'rk45' or 'stratified' (got '", name, "')");
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
  Problems problems("TraceOptions");
  check(problems);
  problems.throw_if_any();
}

void TraceOptions::check(Problems& problems) const {
  problems.check(tol > 0.0 && std::isfinite(tol), "tol must be > 0 (got ", tol, ")");
  problems.check(step >= 0.0 && std::isfinite(step), "step must be > 0, or 0 for the default (got ", step, ")");
  problems.check(max_length > 0.0 && std::isfinite(max_length), "max_length must be > 0 and finite (got ", max_length, ")");
  if (stop_height) problems.check(std::isfinite(*stop_height), "stop_height must be finite (got ", *stop_height, ")");
  problems.check(max_steps > 0, "max_steps must be > 0 (got ", max_steps, ")");
  if (ior_floor) {
    problems.check(*ior_floor > 0.0 && std::isfinite(*ior_floor), "ior_floor must be > 0 and finite (got ", *ior_floor, ")");
  }
  if (!problems.empty()) return;  // the checks below combine fields that must be valid first
  // Refused before any work: a path that needs more than max_steps steps (rk4: max_length / step;
  // rk45: at least max_length / step when a largest step is given; stratified: at least
  // max_length / node spacing) would run for minutes and fill memory with nodes.
  const double least_step = this->least_step();
  problems.check(!(least_step > 0 && max_length / least_step > double(max_steps)), trace_method_name(trace),
                 " with step ", least_step, " m needs more than ", max_steps, " steps for max_length ", max_length,
                 " m (raise step or lower max_length)");
  // rk45 and stratified aim at tol over the whole path. Below round-off of the positions (1e-15
  // of the path) rk45's error control divided by an underflowed allowance and the state became
  // NaN ("height -nan m"), and stratified split panels chasing noise into 10 million nodes.
  // The bound printed in full (shortest round trip): 1e-15 x 1e9 m is 1.0000000000000002e-06 m,
  // which six digits showed as "at least 1e-06 (got 1e-06)".
  problems.check(trace == TraceMethod::kRk4 || tol >= kMinRelativeTol * max_length, trace_method_name(trace),
                 ": tol must be at least ", kMinRelativeTol, " x max_length = ", shortest(kMinRelativeTol * max_length),
                 " m, the round-off of positions (got ", shortest(tol), "): raise tol or lower max_length");
}

}  // namespace refracta
