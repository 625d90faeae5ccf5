// The C++ work running on behalf of Python (run_interruptible), so that interpreter exit can stop
// it first: an atexit hook (registered by bind_core) cancels every running call and waits for
// each to hand control back to Python. After that no refracta code touches Python again: a call
// still running (a daemon thread the hook could not wait for) parks its thread instead of taking
// the GIL of a finalizing interpreter, which would abort the process ("terminate called without an
// active exception", or "FATAL: exception not rethrown" from a CustomField).
#pragma once

#include "refracta/core/parallel.h"

#include <vector>

namespace refracta {

// Registers control as running on behalf of the calling Python thread (its threading.get_ident());
// throws std::runtime_error once the interpreter is shutting down. Call with the GIL held.
void enter_running_work(WorkControl& control);
// The work behind control has returned. Call with the GIL held, after enter_running_work.
void leave_running_work(WorkControl& control);
// True once shutdown_running_work has begun: no Python API may be called any more by work
// threads that do not hold the GIL.
bool python_is_shutting_down();
// Called without the GIL by a call whose work has finished: if the interpreter is shutting down,
// unregisters control and never returns (the thread sleeps until the process exits); else returns.
void park_if_shutting_down(WorkControl& control);
// Cancels the work of the Python threads `thread_ids` (threading.get_ident() values) -- the calls
// running on them and every call they start until end_thread_cancel -- so that a Ctrl-C in the
// main thread stops the tasks it handed to a thread pool. Returns how many running calls it
// cancelled. Call with the GIL held.
int cancel_thread_work(const std::vector<unsigned long>& thread_ids);
// Lets thread_id's calls run again (its cancelled task has ended).
void end_thread_cancel(unsigned long thread_id);
// The atexit hook: cancels every running call and waits (GIL released) up to timeout_seconds for
// them to return to Python.
void shutdown_running_work(double timeout_seconds);

}  // namespace refracta
