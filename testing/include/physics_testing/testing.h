#pragma once
// physics::testing, everything at once: servers under test (in-process or a child
// process), clients, waits with deadlines, the in-process reference run, and the link
// conditioner that puts a real path between them; a game's rules stepped in-process,
// and the check that they keep their state in the world.
#include "physics_testing/clients.h"
#include "physics_testing/endpoint.h"
#include "physics_testing/game_run.h"
#include "physics_testing/in_process_server.h"
#include "physics_testing/link_conditioner.h"
#include "physics_testing/lockstep_check.h"
#include "physics_testing/outcome.h"
#include "physics_testing/reference_run.h"
#include "physics_testing/rules_state_check.h"
#include "physics_testing/server_process.h"
