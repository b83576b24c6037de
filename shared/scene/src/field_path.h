#pragma once
// A path to a field of a scene message, such as `bodies[3].circle.radius`: what an
// error names, and what finds the line and column the text parser recorded for it.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/text_format.h>

#include <string>
#include <string_view>
#include <vector>

namespace scene::detail {

struct TextLocation {
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
};

class FieldPath {
 public:
  // The path of the root message itself (empty).
  FieldPath() = default;

  // The path one field further down; `index` is for repeated fields, -1 otherwise.
  FieldPath child(std::string_view field_name, int index = -1) const;

  // "bodies[3].circle.radius"
  std::string to_string() const;

  // Where the field was written in the text. A field that was not written (a
  // missing value) is located at its nearest written parent, so that an error
  // still points into the right block.
  TextLocation locate(const google::protobuf::Descriptor& root,
                      const google::protobuf::TextFormat::ParseInfoTree& tree) const;

 private:
  struct Segment {
    std::string name;
    int index = -1;
  };
  std::vector<Segment> segments_;
};

}  // namespace scene::detail
