#include "core/interrupt.h"

namespace tandem {

namespace {
thread_local std::function<void()> tPoll;
}  // namespace

void pollInterrupt() {
  if (tPoll) tPoll();
}

InterruptPoll::InterruptPoll(std::function<void()> poll) : previous_(std::move(tPoll)) {
  tPoll = std::move(poll);
}

InterruptPoll::~InterruptPoll() {
  tPoll = std::move(previous_);
}

}  // namespace tandem
