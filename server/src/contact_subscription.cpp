#include "contact_subscription.h"

#include <algorithm>

namespace server {

bool ContactFilter::matches(const phys::ContactEvent& event,
                            std::optional<std::uint64_t> own) const {
  const std::uint64_t a = event.a.packed();
  const std::uint64_t b = event.b.packed();
  switch (kind) {
    case Kind::All:
      return true;
    case Kind::OwnBody:
      return own && (a == *own || b == *own);
    case Kind::Bodies:
      return std::binary_search(bodies.begin(), bodies.end(), a) ||
             std::binary_search(bodies.begin(), bodies.end(), b);
  }
  return false;
}

std::string resolve_contacts(const physics::wire::ContactSubscription& request, bool spectator,
                             ContactFilter& filter) {
  const bool listed = request.body_ids_size() > 0;
  if (!spectator) {
    if (request.all() || listed) {
      return "contacts: a player hears of its own body's contacts only; leave all and "
             "body_ids empty";
    }
    filter = {};
    return {};
  }
  if (request.all() && listed) return "contacts: all and body_ids together; give one";
  if (!request.all() && !listed) return "contacts: a spectator gives all or body_ids";
  if (request.body_ids_size() > static_cast<int>(kMaxContactBodies)) {
    return "contacts: " + std::to_string(request.body_ids_size()) + " body_ids, at most " +
           std::to_string(kMaxContactBodies);
  }
  ContactFilter checked;
  checked.kind = request.all() ? ContactFilter::Kind::All : ContactFilter::Kind::Bodies;
  checked.bodies.assign(request.body_ids().begin(), request.body_ids().end());
  std::sort(checked.bodies.begin(), checked.bodies.end());
  checked.bodies.erase(std::unique(checked.bodies.begin(), checked.bodies.end()),
                       checked.bodies.end());
  filter = std::move(checked);
  return {};
}

void fill_sensor_event(const phys::SensorEvent& event, physics::wire::SensorEvent& out) {
  out.set_end(event.kind == phys::SensorEventKind::End);
  out.set_tick(event.step);
  out.set_sensor(event.sensor.packed());
  out.set_visitor(event.visitor.packed());
}

void fill_contact_event(const phys::ContactEvent& event, physics::wire::ContactEvent& out) {
  out.set_end(event.kind == phys::ContactEventKind::End);
  out.set_tick(event.step);
  out.set_body_a(event.a.packed());
  out.set_body_b(event.b.packed());
  out.mutable_point()->set_x(event.point.x);
  out.mutable_point()->set_y(event.point.y);
  out.mutable_normal()->set_x(event.normal.x);
  out.mutable_normal()->set_y(event.normal.y);
  out.set_closing_speed(event.closing_speed);
}

}  // namespace server
