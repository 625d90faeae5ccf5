// The C++ work running on behalf of Python (run_interruptible), so that interpreter exit can stop
// it first: an atexit hook (registered by bind_core) cancels every running call and waits for
// each to hand control back to Python. After that no refracta code touches Python again: a call
// still running (a daemon thread the hook could not wait for) parks its thread instead of taking
// the GIL of a finalizing interpreter, which would abort the process ("terminate called without an
// active exception", or "FATAL: exception not rethrown" from a CustomField).
#pragma once

#include "refracta/core/parallel.h"

namespace refracta {

// Registers control as running; throws std::runtime_error once the interpreter is shutting down.
// Call with the GIL held.
void enter_running_work(WorkControl& control);
// The work behind control has returned. Call with the GIL held, after enter_running_work.
void leave_running_work(WorkControl& control);
// True once shutdown_running_work has begun: no Python API may be called any more by work
// threads that do not hold the GIL.
bool python_is_shutting_down();
// Called without the GIL by a call whose work has finished: if the interpreter is shutting down,
// unregisters control and never returns (the thread sleeps until the process exits); else returns.
void park_if_shutting_down(WorkControl& control);
// The atexit hook: cancels every running call and waits (GIL released) up to timeout_seconds for
// them to return to Python.
void shutdown_running_work(double timeout_seconds);

}  // namespace refracta
