#pragma once
// Recording files: the bytes "PHYSREC\n", a 4-byte little-endian version, then
// varint-length-prefixed Protobuf messages: one physics.recording.Header, then
// physics.recording.Record until the end of the file (proto/recording.proto,
// docs/REPLAY.md). The writer appends; the reader takes one record at a time and
// names the byte offset of whatever it refuses.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "recording.pb.h"

namespace recording {

inline constexpr std::string_view kMagic{"PHYSREC\n", 8};
inline constexpr std::uint32_t kVersion = 1;
// Magic plus version: where the header's length prefix starts.
inline constexpr std::uint64_t kPreambleBytes = 12;
// Length prefixes over these are refused before anything is allocated: a header
// holds a whole scene (the scene loader's 2^20 bodies fit), a record at most one
// tick's body hashes or one received message.
inline constexpr std::uint64_t kMaxHeaderBytes = 256u << 20;
inline constexpr std::uint64_t kMaxRecordBytes = 64u << 20;

// Why a file was refused: the byte offset (from the start of the file) of the
// prefix or message at fault, and what is wrong there.
struct RecordingError {
  std::uint64_t offset = 0;
  std::string message;
  // "offset N: message".
  std::string to_string() const;
};

// The preamble (magic and version) as bytes.
std::string encode_preamble(std::uint32_t version = kVersion);
// A whole recording in memory: preamble, header, records (tests, tools).
std::string encode_recording(const physics::recording::Header& header,
                             const std::vector<physics::recording::Record>& records);

// Appends to a file. Each append goes to a buffered stream; flush() pushes it to the
// operating system (the destructor flushes too).
class RecordingWriter {
 public:
  // Creates (or truncates) `path` and writes the preamble and `header`. Returns
  // nullptr and sets *error (the path and the system's reason) when it cannot.
  static std::unique_ptr<RecordingWriter> create(const std::filesystem::path& path,
                                                 const physics::recording::Header& header,
                                                 std::string* error);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // False once a write failed (the disk is full, ...); later appends do nothing.
  bool append(const physics::recording::Record& record);
  bool flush();
  bool ok() const { return ok_; }
  std::uint64_t bytes_written() const { return bytes_written_; }

 private:
  RecordingWriter() = default;
  bool write(const std::string& bytes);
  std::ofstream out_;
  std::string scratch_;
  std::uint64_t bytes_written_ = 0;
  bool ok_ = true;
};

// Reads a recording front to back. Never throws on bad bytes, and never allocates
// from a length it has not checked against both its limit and the bytes left in
// the file.
class RecordingReader {
 public:
  using Opened = std::variant<std::unique_ptr<RecordingReader>, RecordingError>;
  // Opens the file and reads the preamble and the header.
  static Opened open(const std::filesystem::path& path);
  // The same over bytes in memory.
  static Opened from_bytes(std::string bytes);

  const physics::recording::Header& header() const { return header_; }
  // Where the header's message starts (after its length prefix).
  std::uint64_t header_offset() const { return header_offset_; }

  enum class Next { Record, End, Error };
  // The next record into `record`; End at the end of the file (exactly after a
  // whole record); Error (see error()) for anything else, after which it stays Error.
  Next next(physics::recording::Record& record);
  const RecordingError& error() const { return error_; }
  // The offset of the length prefix of the record last returned.
  std::uint64_t record_offset() const { return record_offset_; }
  // Bytes of the file consumed so far.
  std::uint64_t position() const { return position_; }
  std::uint64_t size() const { return size_; }

 private:
  RecordingReader(std::unique_ptr<std::istream> in, std::uint64_t size);
  bool read_preamble();
  // Reads one length-prefixed message of at most `limit` bytes into `bytes`; false
  // (error_ set) on any fault. `what` names it in errors ("header", "record").
  bool read_frame(std::uint64_t limit, const char* what, std::string& bytes);
  bool fail(std::uint64_t offset, std::string message);

  std::unique_ptr<std::istream> in_;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = 0;
  std::uint64_t header_offset_ = 0;
  std::uint64_t record_offset_ = 0;
  physics::recording::Header header_;
  RecordingError error_;
  bool failed_ = false;
  std::string scratch_;
};

// Every record of a recording in memory, for callers that seek (a viewer) or read
// a file more than once. Refuses what the reader refuses.
struct LoadedRecording {
  physics::recording::Header header;
  std::uint64_t header_offset = 0;
  std::vector<physics::recording::Record> records;
  std::vector<std::uint64_t> offsets;  // each record's offset in the file
};
std::variant<LoadedRecording, RecordingError> load_recording(const std::filesystem::path& path);
std::variant<LoadedRecording, RecordingError> load_recording_bytes(std::string bytes);

}  // namespace recording
