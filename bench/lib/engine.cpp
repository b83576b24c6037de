#include "engine.h"

#include "peer_banners.h"
#include "peer_engines.h"

namespace bench {

std::string_view to_string(EngineKind kind) {
  switch (kind) {
    case EngineKind::Ours:
      return "ours";
    case EngineKind::Baseline:
      return "baseline";
    case EngineKind::Box2D:
      return "box2d";
    case EngineKind::Chipmunk:
      return "chipmunk";
  }
  return "?";
}

std::optional<EngineKind> engine_from_string(std::string_view name) {
  for (EngineKind kind :
       {EngineKind::Ours, EngineKind::Baseline, EngineKind::Box2D, EngineKind::Chipmunk}) {
    if (to_string(kind) == name) return kind;
  }
  return std::nullopt;
}

bool runs_our_settings(EngineKind kind) {
  return kind == EngineKind::Ours || kind == EngineKind::Baseline;
}

bool engine_available(EngineKind kind) {
  switch (kind) {
    case EngineKind::Ours:
      return true;
    case EngineKind::Baseline:
#ifdef PHYSICS_BENCH_HAVE_BASELINE
      return true;
#else
      return false;
#endif
    case EngineKind::Box2D:
#ifdef PHYSICS_BENCH_HAVE_BOX2D
      return true;
#else
      return false;
#endif
    case EngineKind::Chipmunk:
#ifdef PHYSICS_BENCH_HAVE_CHIPMUNK
      return true;
#else
      return false;
#endif
  }
  return false;
}

void absorb_peer_banners() {
#ifdef PHYSICS_BENCH_HAVE_CHIPMUNK
  absorb_chipmunk_banner();
#endif
}

std::unique_ptr<Engine> make_engine(EngineKind kind, const SceneSpec& scene,
                                    const EngineOptions& options) {
  switch (kind) {
    case EngineKind::Ours:
      return make_ours_engine(scene, options);
    case EngineKind::Baseline:
#ifdef PHYSICS_BENCH_HAVE_BASELINE
      return make_baseline_engine(scene, options);
#else
      return nullptr;
#endif
    case EngineKind::Box2D:
#ifdef PHYSICS_BENCH_HAVE_BOX2D
      return make_box2d_engine(scene, options);
#else
      return nullptr;
#endif
    case EngineKind::Chipmunk:
#ifdef PHYSICS_BENCH_HAVE_CHIPMUNK
      return make_chipmunk_engine(scene, options);
#else
      return nullptr;
#endif
  }
  return nullptr;
}

}  // namespace bench
