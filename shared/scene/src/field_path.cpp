#include "field_path.h"

#include <string>

namespace scene::detail {

namespace protobuf = google::protobuf;

FieldPath FieldPath::child(std::string_view field_name, int index) const {
  FieldPath path = *this;
  path.segments_.push_back({std::string(field_name), index});
  return path;
}

std::string FieldPath::to_string() const {
  std::string text;
  for (const Segment& segment : segments_) {
    if (!text.empty()) text += '.';
    text += segment.name;
    if (segment.index >= 0) text += '[' + std::to_string(segment.index) + ']';
  }
  return text;
}

TextLocation FieldPath::locate(const protobuf::Descriptor& root,
                               const protobuf::TextFormat::ParseInfoTree& tree) const {
  TextLocation best;
  const protobuf::Descriptor* message = &root;
  const protobuf::TextFormat::ParseInfoTree* node = &tree;
  for (const Segment& segment : segments_) {
    if (message == nullptr || node == nullptr) break;
    const protobuf::FieldDescriptor* field = message->FindFieldByName(segment.name);
    if (field == nullptr) break;
    // The tree indexes repeated fields by position and singular ones by -1; a
    // repeated field named as a whole has no single location (Protobuf aborts on
    // index -1 there), so the parent's location stands.
    if (field->is_repeated() && segment.index < 0) break;
    const int index = field->is_repeated() ? segment.index : -1;
    const protobuf::TextFormat::ParseLocation where = node->GetLocation(field, index);
    if (where.line < 0) break;  // not written: keep the parent's location
    best = {where.line + 1, where.column + 1};
    if (field->type() != protobuf::FieldDescriptor::TYPE_MESSAGE) break;
    node = node->GetTreeForNested(field, index);
    message = field->message_type();
  }
  return best;
}

}  // namespace scene::detail
