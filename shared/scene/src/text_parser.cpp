#include "text_parser.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include <limits>
#include <string>

namespace scene::detail {

namespace protobuf = google::protobuf;

namespace {

// Keeps the first error only: later ones are usually consequences of it.
class FirstErrorCollector final : public protobuf::io::ErrorCollector {
 public:
  void AddError(int line, protobuf::io::ColumnNumber column, const std::string& message) override {
    if (error_) return;
    error_ = Error{line, column, message};
  }
  // Warnings (such as deprecated fields) do not refuse a scene.
  void AddWarning(int /*line*/, protobuf::io::ColumnNumber /*column*/,
                  const std::string& /*message*/) override {}

  struct Error {
    int line = -1;  // zero-based, as Protobuf gives them
    int column = -1;
    std::string message;
  };
  const std::optional<Error>& error() const { return error_; }

 private:
  std::optional<Error> error_;
};

// Protobuf words an unknown field as: ... has no field named "radiuss".
// The quoted name is the field the user wrote, so the error names it.
std::string field_named_in(const std::string& message) {
  const std::string marker = "no field named \"";
  const std::size_t start = message.find(marker);
  if (start == std::string::npos) return {};
  const std::size_t name_start = start + marker.size();
  const std::size_t end = message.find('"', name_start);
  if (end == std::string::npos) return {};
  return message.substr(name_start, end - name_start);
}

}  // namespace

std::optional<SceneError> parse_text(std::string_view text, std::string_view origin,
                                     physics::scene::Scene* message,
                                     protobuf::TextFormat::ParseInfoTree* locations) {
  SceneError error;
  error.file = std::string(origin);
  // ArrayInputStream counts in int; the file loader refuses far smaller inputs.
  if (text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    error.message = "scene text is too large";
    return error;
  }
  FirstErrorCollector collector;
  protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&collector);
  parser.WriteLocationsTo(locations);
  parser.AllowUnknownField(false);
  parser.AllowUnknownExtension(false);
  protobuf::io::ArrayInputStream input(text.data(), static_cast<int>(text.size()));
  if (parser.Parse(&input, message)) return std::nullopt;

  if (const auto& first = collector.error()) {
    error.line = first->line >= 0 ? first->line + 1 : 0;
    error.column = first->column >= 0 ? first->column + 1 : 0;
    error.field = field_named_in(first->message);
    error.message = first->message;
  } else {
    error.message = "scene text does not parse";
  }
  return error;
}

}  // namespace scene::detail
