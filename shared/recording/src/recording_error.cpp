#include "recording/recording_file.h"

namespace recording {

std::string RecordingError::to_string() const {
  return "offset " + std::to_string(offset) + ": " + message;
}

}  // namespace recording
