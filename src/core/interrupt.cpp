#include "core/interrupt.h"

namespace tandem {

namespace {
thread_local InterruptPollFn tPoll = nullptr;
}  // namespace

void pollInterrupt() {
  if (tPoll) tPoll();
}

InterruptPoll::InterruptPoll(InterruptPollFn poll) : previous_(tPoll) {
  tPoll = poll;
}

InterruptPoll::~InterruptPoll() {
  tPoll = previous_;
}

}  // namespace tandem
