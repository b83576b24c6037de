#include <sstream>
#include <utility>

#include "recording/recording_file.h"

namespace recording {
namespace {

constexpr int kMaxVarintBytes = 10;

std::string header_kind_missing() {
  return "header has no kind (neither a server nor a client run)";
}

}  // namespace

RecordingReader::RecordingReader(std::unique_ptr<std::istream> in, std::uint64_t size)
    : in_(std::move(in)), size_(size) {}

RecordingReader::Opened RecordingReader::open(const std::filesystem::path& path) {
  auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
  if (!*file) return RecordingError{0, "cannot open " + path.string()};
  file->seekg(0, std::ios::end);
  const std::streamoff end = file->tellg();
  file->seekg(0, std::ios::beg);
  if (end < 0 || !*file) return RecordingError{0, "cannot read " + path.string()};
  std::unique_ptr<RecordingReader> reader(
      new RecordingReader(std::move(file), static_cast<std::uint64_t>(end)));
  if (!reader->read_preamble()) return reader->error_;
  return reader;
}

RecordingReader::Opened RecordingReader::from_bytes(std::string bytes) {
  const std::uint64_t size = bytes.size();
  std::unique_ptr<RecordingReader> reader(
      new RecordingReader(std::make_unique<std::istringstream>(std::move(bytes)), size));
  if (!reader->read_preamble()) return reader->error_;
  return reader;
}

bool RecordingReader::fail(std::uint64_t offset, std::string message) {
  failed_ = true;
  error_ = RecordingError{offset, std::move(message)};
  return false;
}

bool RecordingReader::read_preamble() {
  char preamble[kPreambleBytes];
  if (size_ < kPreambleBytes) {
    return fail(size_, "truncated: " + std::to_string(size_) +
                           " bytes, a recording starts with 12 (magic and version)");
  }
  in_->read(preamble, static_cast<std::streamsize>(kPreambleBytes));
  if (!*in_) return fail(0, "cannot read the preamble");
  position_ = kPreambleBytes;
  if (std::string_view(preamble, kMagic.size()) != kMagic) {
    return fail(0, "not a recording (the file does not start with \"PHYSREC\\n\")");
  }
  std::uint32_t version = 0;
  for (int i = 0; i < 4; ++i) {
    version |= static_cast<std::uint32_t>(static_cast<unsigned char>(preamble[8 + i])) << (8 * i);
  }
  if (version != kVersion) {
    return fail(8, "unsupported version " + std::to_string(version) + " (this program reads " +
                       std::to_string(kVersion) + ")");
  }
  const std::uint64_t prefix_at = position_;
  if (position_ == size_) return fail(prefix_at, "truncated: no header after the preamble");
  if (!read_frame(kMaxHeaderBytes, "header", scratch_)) return false;
  header_offset_ = position_ - scratch_.size();
  if (scratch_.empty()) return fail(prefix_at, "empty header");
  if (!header_.ParseFromString(scratch_)) {
    return fail(header_offset_, "header does not parse (corrupted)");
  }
  if (header_.kind_case() == physics::recording::Header::KIND_NOT_SET) {
    return fail(header_offset_, header_kind_missing());
  }
  return true;
}

bool RecordingReader::read_frame(std::uint64_t limit, const char* what, std::string& bytes) {
  const std::uint64_t prefix_at = position_;
  std::uint64_t length = 0;
  int used = 0;
  for (;;) {
    if (position_ == size_) {
      return fail(prefix_at, std::string("truncated inside the length prefix of a ") + what);
    }
    const int c = in_->get();
    if (c == std::char_traits<char>::eof()) return fail(position_, "read error");
    ++position_;
    const auto byte = static_cast<std::uint8_t>(c);
    // The 10th byte of a 64-bit varint carries one bit (64 = 9 * 7 + 1).
    if (used == kMaxVarintBytes - 1 && byte > 1) {
      return fail(prefix_at,
                  std::string("bad length prefix of a ") + what + " (more than 64 bits)");
    }
    length |= static_cast<std::uint64_t>(byte & 0x7Fu) << (7 * used);
    ++used;
    if ((byte & 0x80u) == 0) break;
  }
  if (length > limit) {
    return fail(prefix_at, std::string(what) + " of " + std::to_string(length) +
                               " bytes is over the limit of " + std::to_string(limit));
  }
  const std::uint64_t left = size_ - position_;
  if (length > left) {
    return fail(prefix_at, std::string("truncated: ") + what + " of " + std::to_string(length) +
                               " bytes, only " + std::to_string(left) + " left in the file");
  }
  // Checked against the limit and the file's size above: only now allocated.
  bytes.resize(static_cast<std::size_t>(length));
  if (length > 0) {
    in_->read(bytes.data(), static_cast<std::streamsize>(length));
    if (!*in_) return fail(position_, "read error");
  }
  position_ += length;
  return true;
}

RecordingReader::Next RecordingReader::next(physics::recording::Record& record) {
  if (failed_) return Next::Error;
  if (position_ == size_) return Next::End;
  record_offset_ = position_;
  if (!read_frame(kMaxRecordBytes, "record", scratch_)) return Next::Error;
  if (scratch_.empty()) {
    fail(record_offset_, "empty record (a record holds exactly one kind)");
    return Next::Error;
  }
  record.Clear();
  if (!record.ParseFromString(scratch_)) {
    fail(record_offset_, "record does not parse (corrupted)");
    return Next::Error;
  }
  if (record.kind_case() == physics::recording::Record::KIND_NOT_SET) {
    fail(record_offset_, "record has no known kind");
    return Next::Error;
  }
  return Next::Record;
}

namespace {

std::variant<LoadedRecording, RecordingError> load_all(RecordingReader::Opened opened) {
  if (auto* error = std::get_if<RecordingError>(&opened)) return *error;
  auto& reader = *std::get<std::unique_ptr<RecordingReader>>(opened);
  LoadedRecording loaded;
  loaded.header = reader.header();
  loaded.header_offset = reader.header_offset();
  physics::recording::Record record;
  for (;;) {
    switch (reader.next(record)) {
      case RecordingReader::Next::End:
        return loaded;
      case RecordingReader::Next::Error:
        return reader.error();
      case RecordingReader::Next::Record:
        loaded.records.push_back(std::move(record));
        loaded.offsets.push_back(reader.record_offset());
        break;
    }
  }
}

}  // namespace

std::variant<LoadedRecording, RecordingError> load_recording(const std::filesystem::path& path) {
  return load_all(RecordingReader::open(path));
}

std::variant<LoadedRecording, RecordingError> load_recording_bytes(std::string bytes) {
  return load_all(RecordingReader::from_bytes(std::move(bytes)));
}

}  // namespace recording
