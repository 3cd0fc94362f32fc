// Containment for TetGen 1.5.0, which aborts (assertions) or segfaults on some inputs that no
// screening predicts (seen: seven small-integer points, centred and rounded to float). The library
// must stay alive whatever the input, so the call runs under temporary handlers that turn a fatal
// signal raised on this thread into a failed attempt.
#pragma once

#include <mutex>

namespace tetprobe {

// Serialises every use of TetGen's global state (its calls and its predicates' constants).
std::mutex& tetgen_mutex();

// Runs fn(context); returns false if it raised SIGABRT, SIGSEGV, SIGBUS or SIGFPE on the calling
// thread. What fn allocated before failing is leaked (its state cannot be trusted). The handlers are
// process-wide while fn runs: callers serialise (TetGen is not thread-safe anyway).
bool call_guarded_against_crashes(void (*fn)(void*), void* context);

}  // namespace tetprobe
