// Stopping long calls on request: loops that can run for minutes (a reference's sample batches,
// every frame a pipeline renders) call pollInterrupt() between steps. The Python module installs a
// poll for the duration of a call (InterruptPoll) that raises KeyboardInterrupt on Ctrl-C; the CLI
// installs none (SIGINT ends the process). Per thread: only the calling thread polls.
#pragma once
#include <functional>
#include <utility>

namespace tandem {

// Throws whatever the installed poll throws when a stop was requested; nothing when none is
// installed.
void pollInterrupt();

// Installs `poll` on this thread while it lives (the previous one after).
class InterruptPoll {
 public:
  explicit InterruptPoll(std::function<void()> poll);
  ~InterruptPoll();
  InterruptPoll(const InterruptPoll&) = delete;
  InterruptPoll& operator=(const InterruptPoll&) = delete;

 private:
  std::function<void()> previous_;
};

}  // namespace tandem
