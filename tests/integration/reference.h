#pragma once
// The same scene stepped in-process, for comparing against what the server sent:
// physics::testing's ReferenceRun, the one users' own tests use too.
#include "physics_testing/reference_run.h"

namespace itest {

using physics_testing::ReferenceRun;

}  // namespace itest
