#pragma once
// Debian's Chipmunk prints a banner on stdout when its first space is made (a build
// with its debug checks on). absorb_peer_banners makes that space with stdout sent
// to /dev/null, so that a CSV on stdout stays clean: call it before writing to
// stdout. It does nothing in a build without Chipmunk.
namespace bench {

void absorb_peer_banners();
void absorb_chipmunk_banner();  // chipmunk_engine.cpp, when Chipmunk is built in

}  // namespace bench
