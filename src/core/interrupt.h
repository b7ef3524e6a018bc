// Stopping long calls on request: loops that can run for minutes (a reference's sample batches,
// every frame a pipeline renders) call pollInterrupt() between steps. The Python module installs a
// poll for the duration of a call (InterruptPoll) that raises KeyboardInterrupt on Ctrl-C; the CLI
// installs none (SIGINT ends the process). Per thread: only the calling thread polls.
#pragma once

namespace tandem {

// Throws whatever the installed poll throws when a stop was requested; nothing when none is
// installed.
void pollInterrupt();

// A poll: a plain function, so the per-thread slot needs no destructor at thread exit (one would
// run after a detached Python thread's join, unordered with the next thread reusing its stack).
using InterruptPollFn = void (*)();

// Installs `poll` on this thread while it lives (the previous one after).
class InterruptPoll {
 public:
  explicit InterruptPoll(InterruptPollFn poll);
  ~InterruptPoll();
  InterruptPoll(const InterruptPoll&) = delete;
  InterruptPoll& operator=(const InterruptPoll&) = delete;

 private:
  InterruptPollFn previous_;
};

}  // namespace tandem
