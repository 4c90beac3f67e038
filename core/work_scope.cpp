// SPDX-License-Identifier: BSD-3-Clause
#include "core/work_scope.hpp"

#include <utility>

namespace imcol {

namespace {
thread_local WorkControl current_work;
}  // namespace

const WorkControl& this_thread_work() { return current_work; }

WorkScope::WorkScope(WorkControl control) : previous_(std::exchange(current_work, std::move(control))) {}

WorkScope::~WorkScope() { current_work = std::move(previous_); }

}  // namespace imcol
