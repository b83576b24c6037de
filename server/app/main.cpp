// physics-server: the authoritative physics server on the command line. Everything
// it does is in the physics_server libraries: the flags, the scene and a game's rules
// library (--rules) in server/server_cli.h, the server in server/server.h.
#include "server/server_cli.h"

int main(int argc, char** argv) { return server::run_server_cli(argc, argv, {}); }
