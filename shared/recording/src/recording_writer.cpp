#include <cerrno>
#include <cstring>

#include "recording/recording_file.h"
#include "wire/framing.h"

namespace recording {

std::string encode_preamble(std::uint32_t version) {
  std::string out(kMagic);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((version >> (8 * i)) & 0xFFu));
  return out;
}

std::string encode_recording(const physics::recording::Header& header,
                             const std::vector<physics::recording::Record>& records) {
  std::string out = encode_preamble();
  wire::append_frame(header, out);
  for (const auto& record : records) wire::append_frame(record, out);
  return out;
}

std::unique_ptr<RecordingWriter> RecordingWriter::create(const std::filesystem::path& path,
                                                         const physics::recording::Header& header,
                                                         std::string* error) {
  std::unique_ptr<RecordingWriter> writer(new RecordingWriter());
  writer->out_.open(path, std::ios::binary | std::ios::trunc);
  if (!writer->out_) {
    if (error) *error = "cannot create " + path.string() + ": " + std::strerror(errno);
    return nullptr;
  }
  std::string bytes = encode_preamble();
  wire::append_frame(header, bytes);
  if (!writer->write(bytes) || !writer->flush()) {
    if (error) *error = "cannot write " + path.string() + ": " + std::strerror(errno);
    return nullptr;
  }
  return writer;
}

RecordingWriter::~RecordingWriter() { flush(); }

bool RecordingWriter::append(const physics::recording::Record& record) {
  if (!ok_) return false;
  scratch_.clear();
  wire::append_frame(record, scratch_);
  return write(scratch_);
}

bool RecordingWriter::write(const std::string& bytes) {
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out_) {
    ok_ = false;
    return false;
  }
  bytes_written_ += bytes.size();
  return true;
}

bool RecordingWriter::flush() {
  if (!ok_) return false;
  out_.flush();
  ok_ = static_cast<bool>(out_);
  return ok_;
}

}  // namespace recording
