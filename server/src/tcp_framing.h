#pragma once
// The TCP port's framing: each message after its varint length (Protobuf's
// length-delimited form, wire/framing.h), the limit checked on the prefix.
#include <span>

#include "framing.h"
#include "wire/framing.h"

namespace server {

class TcpFraming final : public Framing {
 public:
  explicit TcpFraming(std::size_t max_message_bytes) : reader_(max_message_bytes) {}

  void feed(const std::uint8_t* data, std::size_t size) override {
    reader_.feed(std::span<const std::uint8_t>(data, size));
  }
  Status next(std::string& out) override;
  void set_max_message_bytes(std::size_t max) override { reader_.set_max_message_bytes(max); }
  bool open() const override { return true; }
  std::string header(std::size_t payload_bytes) const override;
  std::string take_output() override { return {}; }
  void close() override {}

 private:
  wire::FrameReader reader_;
};

}  // namespace server
