#include "stragglers.h"

#include <algorithm>

namespace server {

std::vector<ClientId> StragglerWatch::after_step(const std::vector<ClientId>& missing,
                                                 bool timed_out) {
  // Whoever is not missing sent its input: its run of misses is over.
  for (auto it = misses_.begin(); it != misses_.end();) {
    if (std::find(missing.begin(), missing.end(), it->first) == missing.end()) {
      it = misses_.erase(it);
    } else {
      ++it;
    }
  }
  std::vector<ClientId> reached;
  if (!timed_out) return reached;
  for (const ClientId client : missing) {
    const int count = ++misses_[client];
    if (limit_ > 0 && count >= limit_) reached.push_back(client);
  }
  std::sort(reached.begin(), reached.end());
  return reached;
}

int StragglerWatch::misses(ClientId client) const {
  const auto it = misses_.find(client);
  return it == misses_.end() ? 0 : it->second;
}

}  // namespace server
