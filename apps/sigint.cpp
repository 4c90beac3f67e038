// SPDX-License-Identifier: BSD-3-Clause
#include "apps/sigint.hpp"

#include <csignal>

namespace imcol {

namespace {

const StopSource* g_source = nullptr;  // the handler's only state: set while a SigintStop lives
struct sigaction g_previous {};

extern "C" void on_sigint(int) {
  if (g_source) g_source->request_stop();  // a lock-free atomic store (SA_RESETHAND has restored the default action)
}

}  // namespace

SigintStop::SigintStop() {
  g_source = &source_;
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &sa, &g_previous);
}

SigintStop::~SigintStop() {
  sigaction(SIGINT, &g_previous, nullptr);
  g_source = nullptr;
}

}  // namespace imcol
